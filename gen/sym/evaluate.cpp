#include "sym/evaluate.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace dyncc::sym {

CompiledFunction::CompiledFunction(std::span<const Expr> outputs, std::span<const Expr> inputs)
    : num_inputs_(inputs.size()) {
  std::unordered_map<const Node*, std::uint32_t> slot_of;
  for (std::size_t i = 0; i < inputs.size(); ++i) slot_of.emplace(inputs[i].node(), static_cast<std::uint32_t>(i));

  // Iterative post-order so deep expressions cannot overflow the stack.
  auto compile = [&](Expr root) -> std::uint32_t {
    std::vector<std::pair<Expr, bool>> stack{{root, false}};
    while (!stack.empty()) {
      auto [e, children_done] = stack.back();
      stack.pop_back();
      if (slot_of.contains(e.node())) continue;
      if (!children_done) {
        stack.emplace_back(e, true);
        for (const Expr a : e.args()) {
          if (!slot_of.contains(a.node())) stack.emplace_back(a, false);
        }
        continue;
      }
      Instruction ins{e.kind(), static_cast<std::uint32_t>(operands_.size()),
                      static_cast<std::uint32_t>(e.args().size()), 0.0};
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
        operands_.push_back({slot_of.at(e.args()[i].node()), w});
      }
      const auto slot = static_cast<std::uint32_t>(num_inputs_ + instructions_.size());
      instructions_.push_back(ins);
      slot_of.emplace(e.node(), slot);
    }
    return slot_of.at(root.node());
  };
  for (const Expr out : outputs) output_slots_.push_back(compile(out));
}

void CompiledFunction::evaluate(std::span<const double> inputs, std::span<double> outputs) const {
  if (inputs.size() != num_inputs_ || outputs.size() != output_slots_.size()) {
    throw std::invalid_argument("CompiledFunction::evaluate: wrong number of inputs or outputs");
  }
  std::vector<double> slots(num_inputs_ + instructions_.size());
  std::copy(inputs.begin(), inputs.end(), slots.begin());
  for (std::size_t i = 0; i < instructions_.size(); ++i) {
    const Instruction& ins = instructions_[i];
    const Operand* ops = operands_.data() + ins.first;
    double r = 0.0;
    switch (ins.kind) {
      case Kind::Number:
      case Kind::Constant: r = ins.value; break;
      case Kind::Add:
        r = ins.value;
        for (std::uint32_t k = 0; k < ins.count; ++k) r += ops[k].weight * slots[ops[k].slot];
        break;
      case Kind::Mul:
        r = ins.value;
        for (std::uint32_t k = 0; k < ins.count; ++k) {
          const double b = slots[ops[k].slot];
          const double e = ops[k].weight;
          r *= (e == 1.0) ? b : (e == 2.0 ? b * b : std::pow(b, e));
        }
        break;
      case Kind::Sin: r = std::sin(slots[ops[0].slot]); break;
      case Kind::Cos: r = std::cos(slots[ops[0].slot]); break;
      case Kind::Sqrt: r = std::sqrt(slots[ops[0].slot]); break;
      case Kind::Atan2: r = std::atan2(slots[ops[0].slot], slots[ops[1].slot]); break;
      case Kind::Symbol: break;
    }
    slots[num_inputs_ + i] = r;
  }
  for (std::size_t k = 0; k < output_slots_.size(); ++k) outputs[k] = slots[output_slots_[k]];
}

std::vector<double> CompiledFunction::operator()(std::span<const double> inputs) const {
  std::vector<double> out(output_slots_.size());
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
