#include "codegen/emit_cpp.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace dyncc::codegen {

std::string scalar_literal(double value) {
  if (!std::isfinite(value)) throw std::domain_error(fmt::format("codegen: constant {} is not finite", value));
  return fmt::format("S({})", value);
}

namespace {

int precedence(Op op) {
  switch (op) {
    case Op::Add:
    case Op::Sub: return 1;
    case Op::Mul:
    case Op::Div: return 2;
    default: return 3;
  }
}

class Printer {
 public:
  explicit Printer(const Function& f) : f_(f), p_(f.program) {
    const std::vector<ValueId> live = p_.live_values();
    uses_.assign(p_.values().size(), 0);
    for (const ValueId id : live) {
      const Value& v = p_[id];
      if (v.a >= 0) ++uses_[static_cast<std::size_t>(v.a)];
      if (v.b >= 0) ++uses_[static_cast<std::size_t>(v.b)];
    }
    for (const Output& o : p_.outputs()) ++uses_[static_cast<std::size_t>(o.value)];
    names_.assign(p_.values().size(), "");
    for (const ValueId id : live) name_if_temporary(id);
  }

  RenderedFunction render() {
    RenderedFunction r;
    for (const ValueId id : p_.live_values()) {
      const std::string& name = names_[static_cast<std::size_t>(id)];
      if (name.empty()) continue;
      r.body += fmt::format("  const S {} = {};\n", name, expression(id));
      ++r.temporaries;
    }
    for (const Output& o : p_.outputs()) r.body += fmt::format("  {} = {};\n", o.target, text(o.value));
    r.counts = p_.count_operations();
    r.parameter_used.assign(f_.parameters.size(), false);
    for (const ValueId id : p_.live_values()) {
      if (p_[id].op != Op::Input) continue;
      const std::string& c = p_.inputs()[static_cast<std::size_t>(p_[id].input)];
      for (std::size_t k = 0; k < f_.parameters.size(); ++k) {
        const std::string& param = f_.parameters[k];
        if (c.starts_with(fmt::format("{}[", param)) || c.starts_with(fmt::format("sgn({}[", param))) {
          r.parameter_used[k] = true;
        }
      }
    }
    return r;
  }

 private:
  [[nodiscard]] std::string label_of_input(ValueId id) const {
    const std::string& c = p_.inputs()[static_cast<std::size_t>(p_[id].input)];
    const auto it = f_.labels.find(c);
    return it == f_.labels.end() ? std::string() : it->second;
  }

  // Sines and cosines of a coordinate are named after it (s_q2, c_q2); sgn(qd[k]) is evaluated
  // once; any other value used twice or more gets a numbered temporary.
  void name_if_temporary(ValueId id) {
    const Value& v = p_[id];
    std::string& name = names_[static_cast<std::size_t>(id)];
    if (v.op == Op::Constant) return;
    if (v.op == Op::Input) {
      const std::string label = label_of_input(id);
      if (label.starts_with("sgn_")) name = label;
      return;
    }
    if ((v.op == Op::Sin || v.op == Op::Cos) && p_[v.a].op == Op::Input) {
      const std::string label = label_of_input(v.a);
      if (!label.empty()) {
        name = fmt::format("{}_{}", v.op == Op::Sin ? "s" : "c", label);
        return;
      }
    }
    if (uses_[static_cast<std::size_t>(id)] >= 2) name = fmt::format("t{}", next_temporary_++);
  }

  [[nodiscard]] std::string text(ValueId id) const {
    const std::string& name = names_[static_cast<std::size_t>(id)];
    if (!name.empty()) return name;
    return expression(id);
  }

  // Text of an operand inside an operation of precedence `outer`; `right` operands of the
  // same precedence keep their parentheses so the evaluation order is the program's.
  [[nodiscard]] std::string operand(ValueId id, int outer, bool right) const {
    const std::string& name = names_[static_cast<std::size_t>(id)];
    const Value& v = p_[id];
    if (!name.empty() || v.op == Op::Input) return text(id);
    if (v.op == Op::Constant) return scalar_literal(v.constant);
    const int inner = precedence(v.op);
    const bool parens = right ? inner <= outer : inner < outer;
    return parens ? fmt::format("({})", expression(id)) : expression(id);
  }

  [[nodiscard]] std::string expression(ValueId id) const {
    const Value& v = p_[id];
    const int prec = precedence(v.op);
    switch (v.op) {
      case Op::Input: return p_.inputs()[static_cast<std::size_t>(v.input)];
      case Op::Constant: return scalar_literal(v.constant);
      case Op::Add: return fmt::format("{} + {}", operand(v.a, prec, false), operand(v.b, prec, true));
      case Op::Sub: return fmt::format("{} - {}", operand(v.a, prec, false), operand(v.b, prec, true));
      case Op::Mul: return fmt::format("{} * {}", operand(v.a, prec, false), operand(v.b, prec, true));
      case Op::Div: return fmt::format("{} / {}", operand(v.a, prec, false), operand(v.b, prec, true));
      case Op::Neg: return fmt::format("-{}", operand(v.a, 3, true));
      case Op::Sin: return fmt::format("std::sin({})", text(v.a));
      case Op::Cos: return fmt::format("std::cos({})", text(v.a));
      case Op::Sqrt: return fmt::format("std::sqrt({})", text(v.a));
      case Op::Atan2: return fmt::format("std::atan2({}, {})", text(v.a), text(v.b));
      case Op::Pow: return fmt::format("std::pow({}, {})", text(v.a), scalar_literal(v.constant));
    }
    return {};
  }

  const Function& f_;
  const Program& p_;
  std::vector<int> uses_;
  std::vector<std::string> names_;
  int next_temporary_ = 0;
};

}  // namespace

RenderedFunction render_body(const Function& f) { return Printer(f).render(); }

}  // namespace dyncc::codegen
