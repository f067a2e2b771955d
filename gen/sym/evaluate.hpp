// Numeric evaluation of expressions.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "sym/expr.hpp"

namespace dyncc::sym {

/// A set of expressions compiled once into a flat instruction tape (each DAG node computed
/// once, shared across outputs) and evaluated many times: used for sampling-based checks and
/// for the model's torque along a log.
///
/// The tape's values live in registers that are reused once their last reader has run (a
/// linear scan over the tape, as a compiler's register allocator does), so the working set is
/// the tape's widest point rather than its length. evaluate_rows() runs each instruction over a
/// block of points before the next: the dispatch is paid once per block and the arithmetic of
/// sums and products runs over contiguous rows. Each point's arithmetic is the same, operation
/// for operation, whichever entry point computes it, so both give the same bits.
class CompiledFunction {
 public:
  /// inputs: the symbols, in the order their values are passed to evaluate().
  /// Throws std::invalid_argument naming a symbol of outputs that is not an input.
  CompiledFunction(std::span<const Expr> outputs, std::span<const Expr> inputs);

  void evaluate(std::span<const double> inputs, std::span<double> outputs) const;
  [[nodiscard]] std::vector<double> operator()(std::span<const double> inputs) const;

  /// The outputs at `rows` points: inputs[i * rows + r] is input i at point r and
  /// outputs[k * rows + r] receives output k at point r (column-major rows x inputs and
  /// rows x outputs matrices).
  void evaluate_rows(std::span<const double> inputs, std::size_t rows, std::span<double> outputs) const;

  [[nodiscard]] std::size_t instruction_count() const { return instructions_.size(); }
  [[nodiscard]] std::size_t input_count() const { return num_inputs_; }
  [[nodiscard]] std::size_t output_count() const { return output_count_; }
  /// Registers the tape needs (inputs included): at most num_inputs + instruction_count.
  [[nodiscard]] std::size_t register_count() const { return register_count_; }

 private:
  struct Instruction {
    Kind kind;
    std::uint32_t first;  // into operands_
    std::uint32_t count;
    std::uint32_t target;   // register written
    std::uint32_t outputs;  // how many of copies_ are written after it (the next ones in order)
    double value;           // Number value, Add constant, Mul coefficient
  };
  struct Operand {
    std::uint32_t reg;
    double weight;  // Add coefficient or Mul exponent
  };
  struct OutputCopy {
    std::uint32_t reg;     // register holding the output's value
    std::uint32_t output;  // output index
  };
  // Runs the tape over a block of points (at most kBlockRows) whose inputs are already in
  // registers[0 .. num_inputs * points); register g of point r is registers[g * points + r].
  // Output k of point r goes to outputs[k * output_stride + output_offset + r]. Rows is
  // std::size_t, or a compile-time 1 for a single point (its loops then vanish).
  template <class Rows>
  void run(double* registers, Rows points, double* outputs, std::size_t output_stride, std::size_t output_offset) const;

  std::vector<Instruction> instructions_;
  std::vector<Operand> operands_;
  // In the order they are written: first the outputs that are inputs (input_copies_ of them),
  // then each instruction's outputs right after it has run.
  std::vector<OutputCopy> copies_;
  std::uint32_t input_copies_ = 0;
  std::size_t num_inputs_ = 0;
  std::size_t output_count_ = 0;
  std::size_t register_count_ = 0;
};

/// One-off evaluation with symbol values by name ("pi" is built in).
double evaluate(Expr e, const std::unordered_map<std::string, double>& values);

}  // namespace dyncc::sym
