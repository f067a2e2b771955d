#include "codegen/ir.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>

namespace dyncc::codegen {

OpCounts& OpCounts::operator+=(const OpCounts& o) {
  mul += o.mul;
  add += o.add;
  div += o.div;
  trig += o.trig;
  sqrt += o.sqrt;
  other += o.other;
  neg += o.neg;
  return *this;
}

std::size_t Program::KeyHash::operator()(const Value& v) const {
  std::size_t h = std::hash<int>()(static_cast<int>(v.op));
  auto mix = [&h](std::size_t x) { h ^= x + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2); };
  mix(std::hash<int>()(v.a));
  mix(std::hash<int>()(v.b));
  mix(std::hash<double>()(v.constant));
  mix(std::hash<int>()(v.input));
  return h;
}

bool Program::KeyEqual::operator()(const Value& x, const Value& y) const {
  // Bitwise comparison of constants: 0.0 and -0.0 stay distinct, NaN never occurs.
  return x.op == y.op && x.a == y.a && x.b == y.b &&
         std::bit_cast<std::uint64_t>(x.constant) == std::bit_cast<std::uint64_t>(y.constant) && x.input == y.input;
}

ValueId Program::intern(Value v) {
  const auto it = numbering_.find(v);
  if (it != numbering_.end()) return it->second;
  const auto id = static_cast<ValueId>(values_.size());
  values_.push_back(v);
  numbering_.emplace(v, id);
  return id;
}

ValueId Program::input(const std::string& c_name) {
  const auto it = input_ids_.find(c_name);
  if (it != input_ids_.end()) return it->second;
  Value v;
  v.op = Op::Input;
  v.input = static_cast<int>(inputs_.size());
  inputs_.push_back(c_name);
  const ValueId id = intern(v);
  input_ids_.emplace(c_name, id);
  return id;
}

ValueId Program::constant(double c) {
  Value v;
  v.op = Op::Constant;
  v.constant = c == 0.0 ? 0.0 : c;  // one zero
  return intern(v);
}

bool Program::is_constant(ValueId id, double v) const {
  const Value& x = (*this)[id];
  return x.op == Op::Constant && x.constant == v;
}

namespace {
Value binary(Op op, ValueId a, ValueId b) {
  Value v;
  v.op = op;
  v.a = a;
  v.b = b;
  return v;
}
Value unary(Op op, ValueId a) {
  Value v;
  v.op = op;
  v.a = a;
  return v;
}
}  // namespace

// Commutative operations order their operands so a*b and b*a are one value.
ValueId Program::add(ValueId a, ValueId b) {
  if (is_constant(a) && is_constant(b)) return constant((*this)[a].constant + (*this)[b].constant);
  if (is_constant(a, 0.0)) return b;
  if (is_constant(b, 0.0)) return a;
  if ((*this)[b].op == Op::Neg) return sub(a, (*this)[b].a);
  if ((*this)[a].op == Op::Neg) return sub(b, (*this)[a].a);
  return intern(binary(Op::Add, std::min(a, b), std::max(a, b)));
}

ValueId Program::sub(ValueId a, ValueId b) {
  if (is_constant(a) && is_constant(b)) return constant((*this)[a].constant - (*this)[b].constant);
  if (is_constant(b, 0.0)) return a;
  if (is_constant(a, 0.0)) return neg(b);
  if (a == b) return constant(0.0);
  if ((*this)[b].op == Op::Neg) return add(a, (*this)[b].a);
  return intern(binary(Op::Sub, a, b));
}

ValueId Program::mul(ValueId a, ValueId b) {
  if (is_constant(a) && is_constant(b)) return constant((*this)[a].constant * (*this)[b].constant);
  if (is_constant(a, 0.0) || is_constant(b, 0.0)) return constant(0.0);
  if (is_constant(a, 1.0)) return b;
  if (is_constant(b, 1.0)) return a;
  if (is_constant(a, -1.0)) return neg(b);
  if (is_constant(b, -1.0)) return neg(a);
  return intern(binary(Op::Mul, std::min(a, b), std::max(a, b)));
}

ValueId Program::div(ValueId a, ValueId b) {
  if (is_constant(a) && is_constant(b)) return constant((*this)[a].constant / (*this)[b].constant);
  if (is_constant(b, 1.0)) return a;
  if (is_constant(a, 0.0)) return constant(0.0);
  return intern(binary(Op::Div, a, b));
}

ValueId Program::neg(ValueId a) {
  if (is_constant(a)) return constant(-(*this)[a].constant);
  if ((*this)[a].op == Op::Neg) return (*this)[a].a;
  return intern(unary(Op::Neg, a));
}

ValueId Program::sin(ValueId a) {
  if (is_constant(a)) return constant(std::sin((*this)[a].constant));
  return intern(unary(Op::Sin, a));
}

ValueId Program::cos(ValueId a) {
  if (is_constant(a)) return constant(std::cos((*this)[a].constant));
  return intern(unary(Op::Cos, a));
}

ValueId Program::sqrt(ValueId a) {
  if (is_constant(a)) return constant(std::sqrt((*this)[a].constant));
  return intern(unary(Op::Sqrt, a));
}

ValueId Program::atan2(ValueId y, ValueId x) {
  if (is_constant(y) && is_constant(x)) return constant(std::atan2((*this)[y].constant, (*this)[x].constant));
  return intern(binary(Op::Atan2, y, x));
}

ValueId Program::integer_power(ValueId a, int n) {
  if (n == 1) return a;
  if (n % 2 == 0) {
    const ValueId half = integer_power(a, n / 2);
    return mul(half, half);
  }
  return mul(integer_power(a, n - 1), a);
}

ValueId Program::real_power(ValueId a, double exponent) {
  if (is_constant(a)) return constant(std::pow((*this)[a].constant, exponent));
  Value v = unary(Op::Pow, a);
  v.constant = exponent;
  return intern(v);
}

// Depth-first from each output in turn: a value is computed just before its first use, which
// keeps live ranges short (register allocation time in the C++ compiler grows with them).
std::vector<ValueId> Program::live_values() const {
  std::vector<char> state(values_.size(), 0);  // 0 new, 1 operands pending, 2 emitted
  std::vector<ValueId> order;
  std::vector<ValueId> stack;
  for (const Output& o : outputs_) {
    stack.push_back(o.value);
    while (!stack.empty()) {
      const ValueId id = stack.back();
      char& st = state[static_cast<std::size_t>(id)];
      if (st == 2) {
        stack.pop_back();
        continue;
      }
      const Value& v = (*this)[id];
      if (st == 0) {
        st = 1;
        if (v.b >= 0 && state[static_cast<std::size_t>(v.b)] == 0) stack.push_back(v.b);
        if (v.a >= 0 && state[static_cast<std::size_t>(v.a)] == 0) stack.push_back(v.a);
        continue;
      }
      st = 2;
      order.push_back(id);
      stack.pop_back();
    }
  }
  return order;
}

OpCounts Program::count_operations() const {
  OpCounts c;
  for (const ValueId id : live_values()) {
    switch ((*this)[id].op) {
      case Op::Add:
      case Op::Sub: ++c.add; break;
      case Op::Mul: ++c.mul; break;
      case Op::Div: ++c.div; break;
      case Op::Neg: ++c.neg; break;
      case Op::Sin:
      case Op::Cos: ++c.trig; break;
      case Op::Sqrt: ++c.sqrt; break;
      case Op::Atan2:
      case Op::Pow: ++c.other; break;
      case Op::Input:
      case Op::Constant: break;
    }
  }
  return c;
}

}  // namespace dyncc::codegen
