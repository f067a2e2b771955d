// Numeric evaluation of expressions.
#pragma once

#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "sym/expr.hpp"

namespace dyncc::sym {

/// A set of expressions compiled once into a flat instruction tape (each DAG node computed
/// once, shared across outputs) and evaluated many times: used for sampling-based checks.
class CompiledFunction {
 public:
  /// inputs: the symbols, in the order their values are passed to evaluate().
  /// Throws std::invalid_argument naming a symbol of outputs that is not an input.
  CompiledFunction(std::span<const Expr> outputs, std::span<const Expr> inputs);

  void evaluate(std::span<const double> inputs, std::span<double> outputs) const;
  [[nodiscard]] std::vector<double> operator()(std::span<const double> inputs) const;
  [[nodiscard]] std::size_t instruction_count() const { return instructions_.size(); }

 private:
  struct Instruction {
    Kind kind;
    std::uint32_t first;  // into operands_
    std::uint32_t count;
    double value;  // Number value, Add constant, Mul coefficient
  };
  struct Operand {
    std::uint32_t slot;
    double weight;  // Add coefficient or Mul exponent
  };
  std::vector<Instruction> instructions_;  // instruction i writes slot num_inputs_ + i
  std::vector<Operand> operands_;
  std::vector<std::uint32_t> output_slots_;
  std::size_t num_inputs_ = 0;
};

/// One-off evaluation with symbol values by name ("pi" is built in).
double evaluate(Expr e, const std::unordered_map<std::string, double>& values);

}  // namespace dyncc::sym
