#include "sym/evaluate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <type_traits>

namespace dyncc::sym {
namespace {

// Points per block of evaluate_rows: long enough that an instruction's dispatch is a small
// part of its work, short enough that a Panda's registers (a few hundred) stay in the L2 cache.
constexpr std::size_t kBlockRows = 64;
constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();

// b^e as the product's factor: the common exponents without a call to pow.
inline double power(double b, double e) { return e == 1.0 ? b : (e == 2.0 ? b * b : std::pow(b, e)); }

}  // namespace

CompiledFunction::CompiledFunction(std::span<const Expr> outputs, std::span<const Expr> inputs)
    : num_inputs_(inputs.size()), output_count_(outputs.size()) {
  // 1. The tape in static single assignment: value v is input v (v < num_inputs) or the
  //    result of instruction v - num_inputs. Operand::reg holds the value's index here.
  std::unordered_map<const Node*, std::uint32_t> value_of;
  for (std::size_t i = 0; i < inputs.size(); ++i) value_of.emplace(inputs[i].node(), static_cast<std::uint32_t>(i));
  // Iterative post-order so deep expressions cannot overflow the stack.
  auto compile = [&](Expr root) -> std::uint32_t {
    std::vector<std::pair<Expr, bool>> stack{{root, false}};
    while (!stack.empty()) {
      auto [e, children_done] = stack.back();
      stack.pop_back();
      if (value_of.contains(e.node())) continue;
      if (!children_done) {
        stack.emplace_back(e, true);
        for (const Expr a : e.args()) {
          if (!value_of.contains(a.node())) stack.emplace_back(a, false);
        }
        continue;
      }
      Instruction ins{e.kind(),
                      static_cast<std::uint32_t>(operands_.size()),
                      static_cast<std::uint32_t>(e.args().size()),
                      kUnused,
                      0,
                      0.0};
      switch (e.kind()) {
        case Kind::Number: ins.value = e.value().to_double(); break;
        case Kind::Constant: ins.value = std::numbers::pi; break;
        case Kind::Symbol: throw std::invalid_argument("no value given for symbol '" + e.name() + "'");
        case Kind::Add:
        case Kind::Mul: ins.value = e.value().to_double(); break;
        default: break;
      }
      for (std::size_t i = 0; i < e.args().size(); ++i) {
        const double w = e.weights().empty() ? 0.0 : e.weights()[i].to_double();
        operands_.push_back({value_of.at(e.args()[i].node()), w});
      }
      const auto value = static_cast<std::uint32_t>(num_inputs_ + instructions_.size());
      instructions_.push_back(ins);
      value_of.emplace(e.node(), value);
    }
    return value_of.at(root.node());
  };
  std::vector<std::uint32_t> output_values;
  output_values.reserve(outputs.size());
  for (const Expr out : outputs) output_values.push_back(compile(out));

  // 2. Where each output is written: at the start (an input) or right after its instruction,
  //    so an output does not hold its register to the end. copies_ is in that order.
  const std::size_t count = instructions_.size();
  for (std::size_t k = 0; k < output_values.size(); ++k) {
    const std::uint32_t v = output_values[k];
    if (v < num_inputs_) {
      ++input_copies_;
    } else {
      ++instructions_[v - num_inputs_].outputs;
    }
    copies_.push_back({v, static_cast<std::uint32_t>(k)});
  }
  std::stable_sort(copies_.begin(), copies_.end(),
                   [](const OutputCopy& a, const OutputCopy& b) { return a.reg < b.reg; });

  // 3. Registers by a linear scan: inputs keep theirs; an instruction's result takes a free
  //    register (the most recently freed, still in cache) and gives it back after its last
  //    reader. A result is allocated before its operands are freed, so no instruction writes
  //    a register it reads (the row loops below rely on that).
  std::vector<std::uint32_t> last_reader(num_inputs_ + count, kUnused);
  for (std::size_t i = 0; i < count; ++i) {
    const Instruction& ins = instructions_[i];
    for (std::uint32_t k = 0; k < ins.count; ++k)
      last_reader[operands_[ins.first + k].reg] = static_cast<std::uint32_t>(i);
  }
  std::vector<std::uint32_t> register_of(num_inputs_ + count);
  for (std::size_t v = 0; v < num_inputs_; ++v) register_of[v] = static_cast<std::uint32_t>(v);
  std::vector<std::uint32_t> free_registers;
  auto next_register = static_cast<std::uint32_t>(num_inputs_);
  for (std::size_t i = 0; i < count; ++i) {
    Instruction& ins = instructions_[i];
    if (free_registers.empty()) {
      ins.target = next_register++;
    } else {
      ins.target = free_registers.back();
      free_registers.pop_back();
    }
    const std::size_t value = num_inputs_ + i;
    register_of[value] = ins.target;
    for (std::uint32_t k = 0; k < ins.count; ++k) {
      Operand& op = operands_[ins.first + k];
      const std::uint32_t v = op.reg;
      op.reg = register_of[v];
      // Free a computed value at its last reader, once (an instruction may read it twice).
      if (v >= num_inputs_ && last_reader[v] == i) {
        free_registers.push_back(register_of[v]);
        last_reader[v] = kUnused - 1;
      }
    }
    if (last_reader[value] == kUnused) free_registers.push_back(ins.target);  // only an output
  }
  for (OutputCopy& c : copies_) c.reg = register_of[c.reg];
  register_count_ = next_register;
}

template <class Rows>
void CompiledFunction::run(double* registers, Rows points, double* outputs, std::size_t output_stride,
                           std::size_t output_offset) const {
  const OutputCopy* next_copy = copies_.data();
  auto write_outputs = [&](std::uint32_t how_many) {
    for (; how_many > 0; --how_many, ++next_copy) {
      const double* from = registers + static_cast<std::size_t>(next_copy->reg) * points;
      std::copy(from, from + points, outputs + next_copy->output * output_stride + output_offset);
    }
  };
  constexpr bool kOnePoint = !std::is_same_v<Rows, std::size_t>;
  write_outputs(input_copies_);
  // Local copies: the stores below could alias the vectors' own pointers for all the compiler knows.
  const Operand* const all_operands = operands_.data();
  for (const Instruction *it = instructions_.data(), *end = it + instructions_.size(); it != end; ++it) {
    const Instruction& ins = *it;
    const Operand* ops = all_operands + ins.first;
    double* __restrict out = registers + static_cast<std::size_t>(ins.target) * points;
    auto operand = [&](std::uint32_t k) -> const double* {
      return registers + static_cast<std::size_t>(ops[k].reg) * points;
    };
    switch (ins.kind) {
      case Kind::Number:
      case Kind::Constant: std::fill(out, out + points, ins.value); break;
      case Kind::Add:
        if constexpr (kOnePoint) {  // an accumulator in a register, not in memory
          double r = ins.value;
          for (std::uint32_t k = 0; k < ins.count; ++k) r += ops[k].weight * operand(k)[0];
          out[0] = r;
        } else {
          std::fill(out, out + points, ins.value);
          for (std::uint32_t k = 0; k < ins.count; ++k) {
            const double* __restrict b = operand(k);
            const double w = ops[k].weight;
            for (std::size_t r = 0; r < points; ++r) out[r] += w * b[r];
          }
        }
        break;
      case Kind::Mul:  // the sum's shape, but the exponent is tested once per operand, not per row (4 %)
        if constexpr (kOnePoint) {
          double r = ins.value;
          for (std::uint32_t k = 0; k < ins.count; ++k) r *= power(operand(k)[0], ops[k].weight);
          out[0] = r;
        } else {
          std::fill(out, out + points, ins.value);
          for (std::uint32_t k = 0; k < ins.count; ++k) {
            const double* __restrict b = operand(k);
            const double e = ops[k].weight;
            if (e == 1.0) {
              for (std::size_t r = 0; r < points; ++r) out[r] *= b[r];
            } else if (e == 2.0) {
              for (std::size_t r = 0; r < points; ++r) out[r] *= b[r] * b[r];
            } else {
              for (std::size_t r = 0; r < points; ++r) out[r] *= std::pow(b[r], e);
            }
          }
        }
        break;
      case Kind::Sin:
        for (std::size_t r = 0; r < points; ++r) out[r] = std::sin(operand(0)[r]);
        break;
      case Kind::Cos:
        for (std::size_t r = 0; r < points; ++r) out[r] = std::cos(operand(0)[r]);
        break;
      case Kind::Sqrt:
        for (std::size_t r = 0; r < points; ++r) out[r] = std::sqrt(operand(0)[r]);
        break;
      case Kind::Atan2:
        for (std::size_t r = 0; r < points; ++r) out[r] = std::atan2(operand(0)[r], operand(1)[r]);
        break;
      case Kind::Symbol: break;
    }
    if (ins.outputs != 0) write_outputs(ins.outputs);
  }
}

void CompiledFunction::evaluate(std::span<const double> inputs, std::span<double> outputs) const {
  if (inputs.size() != num_inputs_ || outputs.size() != output_count_) {
    throw std::invalid_argument("CompiledFunction::evaluate: wrong number of inputs or outputs");
  }
  std::vector<double> registers(register_count_);
  std::copy(inputs.begin(), inputs.end(), registers.begin());
  run(registers.data(), std::integral_constant<std::size_t, 1>{}, outputs.data(), 1, 0);
}

void CompiledFunction::evaluate_rows(std::span<const double> inputs, std::size_t rows,
                                     std::span<double> outputs) const {
  if (inputs.size() != num_inputs_ * rows || outputs.size() != output_count_ * rows) {
    throw std::invalid_argument("CompiledFunction::evaluate_rows: wrong number of inputs or outputs");
  }
  std::vector<double> registers(register_count_ * std::min(rows, kBlockRows));
  for (std::size_t begin = 0; begin < rows; begin += kBlockRows) {
    const std::size_t block = std::min(kBlockRows, rows - begin);
    for (std::size_t i = 0; i < num_inputs_; ++i) {
      std::copy_n(inputs.begin() + static_cast<std::ptrdiff_t>(i * rows + begin), block,
                  registers.begin() + static_cast<std::ptrdiff_t>(i * block));
    }
    run(registers.data(), block, outputs.data(), rows, begin);
  }
}

std::vector<double> CompiledFunction::operator()(std::span<const double> inputs) const {
  std::vector<double> out(output_count_);
  evaluate(inputs, out);
  return out;
}

double evaluate(Expr e, const std::unordered_map<std::string, double>& values) {
  const std::vector<Expr> symbols = free_symbols(e);
  std::vector<double> inputs;
  inputs.reserve(symbols.size());
  for (const Expr s : symbols) {
    const auto it = values.find(s.name());
    if (it == values.end()) throw std::invalid_argument("no value given for symbol '" + s.name() + "'");
    inputs.push_back(it->second);
  }
  const Expr outs[1] = {e};
  return CompiledFunction(outs, symbols)(inputs)[0];
}

}  // namespace dyncc::sym
