// The straight-line program the emitter prints: binary operations on values, each computed
// once (global value numbering), constants folded as they are built.
//
// Why a second representation next to sym::Expr: the expression DAG keeps sums and products
// flat and canonical (right for proofs), while code wants binary operations whose partial
// products can be shared ((s2*c3)*p4 and (s2*c3)*p7 reuse s2*c3) and whose count IS the cost.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace dyncc::codegen {

enum class Op : std::uint8_t { Input, Constant, Add, Sub, Mul, Div, Neg, Sin, Cos, Sqrt, Atan2, Pow };

using ValueId = int;

struct Value {
  Op op = Op::Constant;
  ValueId a = -1, b = -1;  // operands (b for binary ops only)
  double constant = 0.0;   // Constant value; Pow exponent
  int input = -1;          // Input index into Program::inputs
};

/// Operation counts of a program, as a compiler would see them (each value computed once).
struct OpCounts {
  int mul = 0, add = 0, div = 0, trig = 0, sqrt = 0, other = 0;  // add includes subtraction; other: atan2, pow
  int neg = 0;                                                   // negations (free on most targets)
  OpCounts& operator+=(const OpCounts& o);
};

struct Output {
  std::string target;  // e.g. "H[3]"
  ValueId value = -1;
};

class Program {
 public:
  /// An input value named by its C expression (e.g. "q[0]"); the same name gives the same value.
  ValueId input(const std::string& c_name);
  ValueId constant(double c);
  ValueId add(ValueId a, ValueId b);
  ValueId sub(ValueId a, ValueId b);
  ValueId mul(ValueId a, ValueId b);
  ValueId div(ValueId a, ValueId b);
  ValueId neg(ValueId a);
  ValueId sin(ValueId a);
  ValueId cos(ValueId a);
  ValueId sqrt(ValueId a);
  ValueId atan2(ValueId y, ValueId x);
  /// a^n for an integer n >= 1, by repeated squaring (x^4 = (x^2)^2: two multiplications).
  ValueId integer_power(ValueId a, int n);
  ValueId real_power(ValueId a, double exponent);

  void set_output(const std::string& target, ValueId v) { outputs_.push_back({target, v}); }

  [[nodiscard]] const std::vector<Value>& values() const { return values_; }
  [[nodiscard]] const std::vector<Output>& outputs() const { return outputs_; }
  [[nodiscard]] const std::vector<std::string>& inputs() const { return inputs_; }
  [[nodiscard]] const Value& operator[](ValueId id) const { return values_[static_cast<std::size_t>(id)]; }
  [[nodiscard]] bool is_constant(ValueId id, double v) const;
  [[nodiscard]] bool is_constant(ValueId id) const { return (*this)[id].op == Op::Constant; }

  /// Values reachable from the outputs, in a valid evaluation order (operands first).
  [[nodiscard]] std::vector<ValueId> live_values() const;
  /// Operation counts over the live values.
  [[nodiscard]] OpCounts count_operations() const;

 private:
  ValueId intern(Value v);

  std::vector<Value> values_;
  std::vector<Output> outputs_;
  std::vector<std::string> inputs_;
  std::unordered_map<std::string, ValueId> input_ids_;
  struct KeyHash {
    std::size_t operator()(const Value& v) const;
  };
  struct KeyEqual {
    bool operator()(const Value& x, const Value& y) const;
  };
  std::unordered_map<Value, ValueId, KeyHash, KeyEqual> numbering_;
};

}  // namespace dyncc::codegen
