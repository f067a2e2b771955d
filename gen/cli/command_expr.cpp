// `dyncc expr`: the expression engine for engineers at the command line.
#include <fmt/core.h>

#include <cmath>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "cli/commands.hpp"
#include "sym/diff.hpp"
#include "sym/evaluate.hpp"
#include "sym/expand.hpp"
#include "sym/parse.hpp"
#include "sym/print.hpp"
#include "sym/rational.hpp"
#include "sym/simplify.hpp"
#include "sym/trig_normal_form.hpp"

namespace dyncc::cli {
namespace {

// Parses an argument; on error prints the text with a caret under the column.
std::optional<sym::Expr> parse_argument(const std::string& text, const std::string& what) {
  const sym::ParseResult r = sym::parse(text);
  if (r.ok()) return r.expr;
  fmt::print(stderr, "{}:1:{}: error: {}\n  {}\n  {}^\n", what, r.error.column, r.error.message, text,
             std::string(r.error.column - 1, ' '));
  return std::nullopt;
}

std::string show(sym::Expr e, bool latex) { return latex ? sym::to_latex(e) : sym::to_string(e); }

}  // namespace

int run_expr_diff(const ExprOptions& o) {
  const auto e = parse_argument(o.expression, "EXPR");
  if (!e) return kBadInput;
  const sym::ParseResult v = sym::parse(o.variable);
  if (!v.ok() || !v.expr->is_symbol()) {
    fmt::print(stderr, "VAR: error: expected a symbol name to differentiate by, found '{}'\n", o.variable);
    return kBadInput;
  }
  fmt::print("{}\n", show(sym::diff(*e, *v.expr), o.latex));
  return kSuccess;
}

int run_expr_simplify(const ExprOptions& o) {
  const auto e = parse_argument(o.expression, "EXPR");
  if (!e) return kBadInput;
  fmt::print("{}\n", show(sym::simplify(*e), o.latex));
  return kSuccess;
}

int run_expr_expand(const ExprOptions& o) {
  const auto e = parse_argument(o.expression, "EXPR");
  if (!e) return kBadInput;
  fmt::print("{}\n", show(sym::expand(*e), o.latex));
  return kSuccess;
}

int run_expr_zero(const ExprOptions& o) {
  const auto e = parse_argument(o.expression, "EXPR");
  if (!e) return kBadInput;
  const sym::ZeroTestResult r = sym::test_zero(*e);
  auto witness_text = [&] {
    std::string s;
    for (const auto& [name, value] : r.witness) s += fmt::format("{}{}={}", s.empty() ? "" : " ", name, value);
    return s;
  };
  switch (r.verdict) {
    case sym::ZeroVerdict::Zero: fmt::print("identically zero\n"); return kSuccess;
    case sym::ZeroVerdict::NonZero:
      fmt::print("not identically zero\n");
      fmt::print("witness: {} gives {:.17g}\n", r.witness.empty() ? "(no symbols)" : witness_text(), r.witness_value);
      if (!r.proved) fmt::print("(shown by evaluation; not in the decidable class: {})\n", r.note);
      return kCheckFailed;
    case sym::ZeroVerdict::Unknown:
      fmt::print("undecided: {}; no non-zero value found at 32 sample points\n", r.note);
      return kCheckFailed;
  }
  return kCheckFailed;
}

int run_expr_eval(const ExprOptions& o) {
  const auto e = parse_argument(o.expression, "EXPR");
  if (!e) return kBadInput;
  std::unordered_map<std::string, double> values;
  for (const std::string& a : o.assignments) {
    const auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0) {
      fmt::print(stderr, "error: expected VAR=VALUE, found '{}'\n", a);
      return kBadInput;
    }
    const std::string name = a.substr(0, eq);
    const auto value = parse_argument(a.substr(eq + 1), name);
    if (!value) return kBadInput;
    if (!value->is_number() && !(value->kind() == sym::Kind::Constant)) {
      try {
        values[name] = sym::evaluate(*value, {});
      } catch (const std::exception&) {
        fmt::print(stderr, "error: value of {} must be a number, found '{}'\n", name, a.substr(eq + 1));
        return kBadInput;
      }
    } else {
      values[name] = sym::evaluate(*value, {});
    }
  }
  for (const sym::Expr s : sym::free_symbols(*e)) {
    if (!values.contains(s.name())) {
      fmt::print(stderr, "error: no value given for '{}' (pass {}=VALUE)\n", s.name(), s.name());
      return kBadInput;
    }
  }
  fmt::print("{:.17g}\n", sym::evaluate(*e, values));
  return kSuccess;
}

}  // namespace dyncc::cli
