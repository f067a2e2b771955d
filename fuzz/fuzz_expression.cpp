// libFuzzer target: the expression front end (parser, printer, and the engine passes the
// parser's output feeds: diff, expand, the zero test, evaluation).
//
// What counts as a failure (the fuzzer stops and saves the input):
//   - any crash, sanitizer report (ASan/UBSan), or hang (-timeout);
//   - parse() letting an exception escape (it promises a ParseResult for every input);
//   - a parse error whose column is outside [1, size + 1] or whose message is empty;
//   - a SymbolUse whose column does not point at the symbol's name in the text;
//   - print round trip: parse(to_string(e)) failing or giving a different node than e;
//     (DYNCC_FUZZ_WEAK_ROUNDTRIP=1 skips this check, to look past known round-trip bugs);
//   - diff/expand/zero test/evaluation throwing anything but std::overflow_error (documented:
//     exact coefficients or degrees out of range). A domain_error from diff of an expression
//     the parser accepted means the parser let through something undefined (e.g. 0/0);
//   - the zero test *proving* expand(e) - e non-zero (a wrong answer: the two are equal)
//     (DYNCC_FUZZ_NO_ZERO_TEST=1 skips the zero test altogether).
// Work that can legitimately explode (expand of (a+b)^64 * (c+d)^64, the zero test) is only
// run when a cheap upper bound on its size is small, so the fuzzer finds bugs rather than
// spending its budget on big-but-correct computations.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "sym/diff.hpp"
#include "sym/evaluate.hpp"
#include "sym/expand.hpp"
#include "sym/expr.hpp"
#include "sym/parse.hpp"
#include "sym/print.hpp"
#include "sym/trig_normal_form.hpp"

namespace {

using dyncc::sym::Expr;
using dyncc::sym::Kind;

constexpr std::size_t kMaxInput = 4096;     // longer inputs only slow the fuzzer down
constexpr std::size_t kMaxDiffDag = 2000;   // differentiate when the DAG is at most this big
constexpr std::size_t kMaxDiffSymbols = 4;  // ... by at most this many symbols
constexpr double kMaxExpandTerms = 512.0;   // expand when the bound on terms is at most this
constexpr double kMaxExpandWork = 20000.0;  // ... and the bound summed over the DAG too
// The zero test's own budget (the default allows ~1.5 s; under ASan that is ~15 s per input).
constexpr std::size_t kZeroTestWorkBudget = 100'000;
constexpr std::size_t kMaxZeroTestInput = 96;  // zero test only on short texts
constexpr std::size_t kMaxZeroTestDag = 40;
constexpr double kMaxZeroTestTerms = 64.0;
constexpr std::int64_t kMaxZeroTestExponent = 8;  // (c + i s)^n and polynomial powers grow fast

[[noreturn]] void fail(std::string_view input, const std::string& what) {
  std::fprintf(stderr, "fuzz_expression: %s\n  input: \"%.*s\"\n", what.c_str(), static_cast<int>(input.size()),
               input.data());
  std::abort();
}

// Upper bounds on the number of terms expand() produces for each node, and the sum of those
// bounds over the DAG (a proxy for expand's total work). Saturates, never overflows.
class ExpansionBound {
 public:
  double terms(Expr e) {
    if (const auto it = memo_.find(e.node()); it != memo_.end()) return it->second;
    double n = 1.0;
    const auto args = e.args();
    switch (e.kind()) {
      case Kind::Add:
        n = e.value().is_zero() ? 0.0 : 1.0;
        for (const Expr a : args) n += terms(a);
        break;
      case Kind::Mul:
        for (std::size_t i = 0; i < args.size(); ++i) {
          const double t = terms(args[i]);
          const std::int64_t w = e.weights()[i].num();
          if (w > 0) n *= std::pow(t, static_cast<double>(w));  // inf saturates below
          max_exponent_ = std::max(max_exponent_, w < 0 ? -w : w);
        }
        break;
      default:  // functions are one term; their arguments are expanded on their own
        for (const Expr a : args) terms(a);
        break;
    }
    n = std::min(n, kSaturate);
    memo_.emplace(e.node(), n);
    work_ = std::min(work_ + n, kSaturate);
    return n;
  }
  [[nodiscard]] double work() const { return work_; }
  [[nodiscard]] std::int64_t max_exponent() const { return max_exponent_; }

 private:
  static constexpr double kSaturate = 1e12;
  std::unordered_map<const dyncc::sym::Node*, double> memo_;
  double work_ = 0.0;
  std::int64_t max_exponent_ = 0;
};

// Largest |numerator| or denominator of a number appearing in a sin/cos argument: the zero test
// expands sin(n*x) through (c + i s)^n.
std::int64_t max_trig_multiple(Expr e, std::unordered_map<const dyncc::sym::Node*, std::int64_t>& memo) {
  if (const auto it = memo.find(e.node()); it != memo.end()) return it->second;
  std::int64_t m = 0;
  if (e.kind() == Kind::Number || e.kind() == Kind::Add || e.kind() == Kind::Mul) {
    const auto& v = e.value();
    m = std::max(v.num() < 0 ? -(v.num() + 1) : v.num(), v.den());
  }
  for (const auto& w : e.weights()) m = std::max({m, w.num() < 0 ? -(w.num() + 1) : w.num(), w.den()});
  for (const Expr a : e.args()) m = std::max(m, max_trig_multiple(a, memo));
  memo.emplace(e.node(), m);
  return m;
}

// DYNCC_FUZZ_WEAK_ROUNDTRIP=1 skips the print round-trip check, so known, reported round-trip
// bugs (fuzz/crashes/expression-roundtrip-*) do not stop the fuzzer from finding others.
bool weak_roundtrip() {
  static const bool weak = [] {
    const char* v = std::getenv("DYNCC_FUZZ_WEAK_ROUNDTRIP");
    return v != nullptr && std::string_view(v) == "1";
  }();
  return weak;
}

// Known limit of the canonical form: a sum whose primitive form (denominators cleared) does not
// fit 64-bit coefficients cannot be normalised, so 2*(s)*sqrt(s) and (2*s)*sqrt(s) may stay two
// nodes (equal in value; the zero test still identifies them). Such sums print with integers of
// 12 or more digits; the round-trip check is relaxed to value equality for them.
bool has_near_overflow_coefficient(std::string_view printed) {
  std::size_t run = 0;
  for (const char c : printed) {
    run = (c >= '0' && c <= '9') ? run + 1 : 0;
    if (run >= 12) return true;
  }
  return false;
}

// DYNCC_FUZZ_NO_ZERO_TEST=1 skips the zero test, so its known exponential blow-up
// (fuzz/crashes/expression-zero-test-blowup*) does not end every run as a timeout.
bool skip_zero_test() {
  static const bool skip = [] {
    const char* v = std::getenv("DYNCC_FUZZ_NO_ZERO_TEST");
    return v != nullptr && std::string_view(v) == "1";
  }();
  return skip;
}

void check_parse_contract(std::string_view text, const dyncc::sym::ParseResult& r) {
  if (!r.ok()) {
    if (r.error.column < 1 || r.error.column > text.size() + 1) {
      fail(text, "parse error column " + std::to_string(r.error.column) + " outside [1, " +
                     std::to_string(text.size() + 1) + "]: " + r.error.message);
    }
    if (r.error.message.empty()) fail(text, "parse error without a message");
    return;
  }
  for (const auto& use : r.symbols) {
    if (use.column < 1 || use.column > text.size() || text.substr(use.column - 1, use.name.size()) != use.name) {
      fail(text, "symbol '" + use.name + "' reported at column " + std::to_string(use.column) +
                     " which does not hold that name");
    }
  }
}

// Runs f; overflow_error is an accepted outcome (exact arithmetic out of range), anything else
// escaping is a bug.
template <typename F>
void engine_step(std::string_view text, const char* step, F&& f) {
  try {
    f();
  } catch (const std::overflow_error&) {
    // documented: coefficients or degrees out of the exact range
  } catch (const std::exception& ex) {
    fail(text, std::string(step) + " threw " + ex.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > kMaxInput) return -1;  // -1: do not add to the corpus
  const std::string_view text(reinterpret_cast<const char*>(data), size);

  const dyncc::sym::ParseResult r = dyncc::sym::parse(text);  // must not throw
  check_parse_contract(text, r);
  if (!r.ok()) return 0;
  const Expr e = *r.expr;

  // Printing: the text form must read back to the very same (hash-consed) node.
  const std::string printed = dyncc::sym::to_string(e);
  const dyncc::sym::ParseResult again = dyncc::sym::parse(printed);
  // The printed form of a near-overflow sum may overflow while being read back (2*(... + big/den)
  // distributes the 2), a documented limit of 64-bit coefficients, not a printer bug.
  const bool overflow_limit =
      has_near_overflow_coefficient(printed) && again.error.message.find("overflows 64 bits") != std::string::npos;
  if (!again.ok() && !weak_roundtrip() && !overflow_limit) {
    fail(text, "printed form \"" + printed + "\" does not parse: column " + std::to_string(again.error.column) + ": " +
                   again.error.message);
  }
  // Near-overflow sums that read back as another node are accepted when the zero test cannot
  // prove the two differ (their difference itself may overflow: then they are accepted too).
  const auto equal_in_value = [&] {
    try {
      return dyncc::sym::test_zero(*again.expr - e, kZeroTestWorkBudget).verdict != dyncc::sym::ZeroVerdict::NonZero;
    } catch (const std::overflow_error&) {
      return true;
    }
  };
  if (again.ok() && !(*again.expr == e) && !weak_roundtrip() &&
      !(has_near_overflow_coefficient(printed) && equal_in_value())) {
    fail(text, "printed form \"" + printed + "\" parses to a different expression \"" +
                   dyncc::sym::to_string(*again.expr) + "\"");
  }
  (void)dyncc::sym::to_latex(e);

  const std::size_t dag = e.dag_size();
  const std::vector<Expr> symbols = dyncc::sym::free_symbols(e);

  // Evaluation at a fixed point: non-finite results are fine (1/x at x=0), UB is not.
  engine_step(text, "evaluate", [&] {
    const Expr outputs[1] = {e};
    const dyncc::sym::CompiledFunction f(outputs, symbols);
    std::vector<double> point(symbols.size());
    for (std::size_t i = 0; i < point.size(); ++i) point[i] = 0.25 + 0.5 * static_cast<double>(i);
    (void)f(point);
  });

  if (dag <= kMaxDiffDag) {
    std::size_t n = 0;
    for (const Expr s : symbols) {
      if (n++ == kMaxDiffSymbols) break;
      engine_step(text, "diff", [&] { (void)dyncc::sym::diff(e, s); });
    }
  }

  ExpansionBound bound;
  const double terms = bound.terms(e);
  if (terms <= kMaxExpandTerms && bound.work() <= kMaxExpandWork) {
    engine_step(text, "expand", [&] { (void)dyncc::sym::expand(e); });
  }

  if (!skip_zero_test() && size <= kMaxZeroTestInput && dag <= kMaxZeroTestDag && terms <= kMaxZeroTestTerms &&
      bound.max_exponent() <= kMaxZeroTestExponent) {
    std::unordered_map<const dyncc::sym::Node*, std::int64_t> memo;
    if (max_trig_multiple(e, memo) <= 64) {
      engine_step(text, "test_zero", [&] { (void)dyncc::sym::test_zero(e, kZeroTestWorkBudget); });
      // Semantic oracle: expand(e) equals e, so the zero test may say Zero or Unknown for the
      // difference, but a *proved* NonZero is a wrong answer from the decision procedure.
      engine_step(text, "test_zero(expand(e) - e)", [&] {
        const dyncc::sym::ZeroTestResult z = dyncc::sym::test_zero(dyncc::sym::expand(e) - e, kZeroTestWorkBudget);
        if (z.verdict == dyncc::sym::ZeroVerdict::NonZero && z.proved) {
          fail(text, "zero test proved expand(e) - e non-zero (witness value " + std::to_string(z.witness_value) + ")");
        }
      });
    }
  }
  return 0;
}
