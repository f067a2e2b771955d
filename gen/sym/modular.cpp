#include "sym/modular.hpp"

#include <cmath>
#include <unordered_map>

namespace dyncc::sym {

std::uint64_t PrimeField::pow(std::uint64_t a, std::uint64_t e) const {
  std::uint64_t r = 1;
  a %= p_;
  while (e != 0) {
    if ((e & 1U) != 0) r = mul(r, a);
    a = mul(a, a);
    e >>= 1U;
  }
  return r;
}

std::uint64_t PrimeField::inv(std::uint64_t a) const {
  if (a % p_ == 0) throw std::domain_error("division by zero in GF(p)");
  return pow(a, p_ - 2);
}

std::uint64_t PrimeField::from_int(std::int64_t v) const {
  const auto m = static_cast<std::int64_t>(p_);
  std::int64_t r = v % m;
  if (r < 0) r += m;
  return static_cast<std::uint64_t>(r);
}

std::uint64_t PrimeField::from(const Rational& r) const { return mul(from_int(r.num()), inv(from_int(r.den()))); }

ModularFunction::ModularFunction(std::span<const Expr> outputs, std::span<const Expr> inputs) : inputs_(inputs.size()) {
  std::unordered_map<const Node*, std::uint32_t> slot_of;
  for (std::size_t i = 0; i < inputs.size(); ++i) slot_of.emplace(inputs[i].node(), static_cast<std::uint32_t>(i));
  auto input_index = [&](Expr s) -> std::uint32_t {
    const auto it = slot_of.find(s.node());
    if (it == slot_of.end() || it->second >= inputs_) throw NotModular("symbol '" + s.name() + "' is not an input");
    return it->second;
  };
  auto compile = [&](Expr root) {
    std::vector<std::pair<Expr, bool>> stack{{root, false}};
    while (!stack.empty()) {
      auto [e, ready] = stack.back();
      stack.pop_back();
      if (slot_of.contains(e.node())) continue;
      const bool trig = e.kind() == Kind::Sin || e.kind() == Kind::Cos;
      if (!ready) {
        stack.emplace_back(e, true);
        if (!trig) {
          for (const Expr a : e.args()) {
            if (!slot_of.contains(a.node())) stack.emplace_back(a, false);
          }
        }
        continue;
      }
      Instruction ins{e.kind(), static_cast<std::uint32_t>(operands_.size()), 0, Rational(0)};
      switch (e.kind()) {
        case Kind::Number: ins.value = e.value(); break;
        case Kind::Symbol: throw NotModular("symbol '" + e.name() + "' is not an input");
        case Kind::Constant: throw NotModular("pi outside sin/cos cannot be evaluated exactly");
        case Kind::Sqrt:
        case Kind::Atan2: throw NotModular("sqrt and atan2 cannot be evaluated exactly");
        case Kind::Add:
        case Kind::Mul:
          ins.value = e.value();
          for (std::size_t i = 0; i < e.args().size(); ++i)
            operands_.push_back({slot_of.at(e.args()[i].node()), e.weights()[i]});
          ins.count = static_cast<std::uint32_t>(e.args().size());
          break;
        case Kind::Sin:
        case Kind::Cos: {
          // The argument must be sum_j n_j * x_j (integer n_j) plus a constant angle. A constant
          // angle (alpha = pi/3, an offset 0.3) gets its own point on the circle: relations that
          // hold for every value of it are then found, ones special to its value are not (the
          // base parameters can only come out less regrouped, never wrong).
          const Expr arg = e.args()[0];
          std::vector<std::pair<Rational, Expr>> constant_part;
          auto add_term = [&](const Rational& c, Expr t) {
            if (t.kind() == Kind::Symbol) {
              if (!c.is_integer()) throw NotModular("sin/cos argument has a fractional multiple of a symbol");
              operands_.push_back({input_index(t), c});
            } else if (free_symbols(t).empty()) {
              constant_part.emplace_back(c, t);
            } else {
              throw NotModular("sin/cos argument is not linear in the symbols");
            }
          };
          Rational offset;
          if (arg.kind() == Kind::Add) {
            offset = arg.value();
            for (std::size_t i = 0; i < arg.args().size(); ++i) add_term(arg.weights()[i], arg.args()[i]);
          } else if (arg.is_number()) {
            offset = arg.value();
          } else {
            auto [c, t] = split_coefficient(arg);
            add_term(c, t);
          }
          if (!offset.is_zero() || !constant_part.empty()) {
            const Expr angle = linear_combination(constant_part, offset);
            auto [it, inserted] =
                constant_angles_.try_emplace(angle, static_cast<std::uint32_t>(inputs_ + constant_angles_.size()));
            operands_.push_back({it->second, Rational(1)});
          }
          ins.count = static_cast<std::uint32_t>(operands_.size()) - ins.first;
          break;
        }
      }
      slot_of.emplace(e.node(), static_cast<std::uint32_t>(inputs_ + instructions_.size()));
      instructions_.push_back(ins);
    }
  };
  for (const Expr out : outputs) {
    compile(out);
    output_slots_.push_back(slot_of.at(out.node()));
  }
}

const ModularFunction::BoundConstants& ModularFunction::bind(const PrimeField& f) const {
  for (const auto& [prime, constants] : bound_) {
    if (prime == f.prime()) return constants;
  }
  BoundConstants b;
  b.values.reserve(instructions_.size());
  for (const Instruction& ins : instructions_)
    b.values.push_back(ins.kind == Kind::Number || ins.kind == Kind::Add || ins.kind == Kind::Mul ? f.from(ins.value)
                                                                                                  : 0);
  b.coefficients.assign(operands_.size(), 0);
  for (const Instruction& ins : instructions_) {
    if (ins.kind != Kind::Add) continue;
    for (std::uint32_t i = 0; i < ins.count; ++i)
      b.coefficients[ins.first + i] = f.from(operands_[ins.first + i].coefficient);
  }
  bound_.emplace_back(f.prime(), std::move(b));
  return bound_.back().second;
}

std::vector<std::uint64_t> ModularFunction::evaluate(const PrimeField& f, const ModularPoint& pt) const {
  const BoundConstants& bound = bind(f);
  std::vector<std::uint64_t> slots(inputs_ + instructions_.size());
  for (std::size_t i = 0; i < inputs_; ++i) slots[i] = pt.value[i];
  for (std::size_t k = 0; k < instructions_.size(); ++k) {
    const Instruction& ins = instructions_[k];
    const Operand* ops = operands_.data() + ins.first;
    std::uint64_t r = 0;
    switch (ins.kind) {
      case Kind::Number: r = bound.values[k]; break;
      case Kind::Add:
        r = bound.values[k];
        for (std::uint32_t i = 0; i < ins.count; ++i)
          r = f.add(r, f.mul(bound.coefficients[ins.first + i], slots[ops[i].slot]));
        break;
      case Kind::Mul:
        r = bound.values[k];
        for (std::uint32_t i = 0; i < ins.count; ++i) {
          const std::int64_t e = ops[i].coefficient.num();
          const std::uint64_t b = slots[ops[i].slot];
          if (e == 1) {
            r = f.mul(r, b);
          } else {
            r = f.mul(r, e >= 0 ? f.pow(b, static_cast<std::uint64_t>(e))
                                : f.inv(f.pow(b, static_cast<std::uint64_t>(-e))));
          }
        }
        break;
      case Kind::Sin:
      case Kind::Cos: {
        // (re + i im) = prod_j (c_j + i s_j)^{n_j}; conjugate for negative n_j (|c + i s| = 1).
        std::uint64_t re = 1;
        std::uint64_t im = 0;
        for (std::uint32_t i = 0; i < ins.count; ++i) {
          const std::int64_t n = ops[i].coefficient.num();
          const std::uint64_t c = pt.cos[ops[i].slot];
          const std::uint64_t s = n >= 0 ? pt.sin[ops[i].slot] : f.neg(pt.sin[ops[i].slot]);
          for (std::int64_t k2 = 0; k2 < (n >= 0 ? n : -n); ++k2) {
            const std::uint64_t nre = f.sub(f.mul(re, c), f.mul(im, s));
            const std::uint64_t nim = f.add(f.mul(re, s), f.mul(im, c));
            re = nre;
            im = nim;
          }
        }
        r = ins.kind == Kind::Cos ? re : im;
        break;
      }
      default: break;
    }
    slots[inputs_ + k] = r;
  }
  std::vector<std::uint64_t> out;
  out.reserve(output_slots_.size());
  for (const std::uint32_t s : output_slots_) out.push_back(slots[s]);
  return out;
}

ModularPoint random_point(const PrimeField& f, std::size_t symbols, std::mt19937_64& rng) {
  ModularPoint pt;
  std::uniform_int_distribution<std::uint64_t> uniform(1, f.prime() - 1);
  for (std::size_t i = 0; i < symbols; ++i) {
    pt.value.push_back(uniform(rng));
    // Rational parametrisation of the circle: s = 2t/(1+t^2), c = (1-t^2)/(1+t^2).
    for (;;) {
      const std::uint64_t t = uniform(rng);
      const std::uint64_t t2 = f.mul(t, t);
      const std::uint64_t den = f.add(1, t2);
      if (den == 0) continue;
      const std::uint64_t inv = f.inv(den);
      pt.sin.push_back(f.mul(f.mul(2, t), inv));
      pt.cos.push_back(f.mul(f.sub(1, t2), inv));
      break;
    }
  }
  return pt;
}

std::optional<Rational> rational_reconstruct(UInt128 a, UInt128 m) {
  // Extended Euclid on (m, a) until the remainder drops below sqrt(m/2).
  __extension__ using Int128 = __int128;
  Int128 r0 = static_cast<Int128>(m);
  Int128 r1 = static_cast<Int128>(a % m);
  Int128 t0 = 0;
  Int128 t1 = 1;
  // bound = floor(sqrt(m/2)), from a long double estimate corrected to the exact integer
  const UInt128 half = m / 2;
  auto bound = static_cast<UInt128>(std::sqrt(static_cast<long double>(half)));
  while (bound > 0 && bound * bound > half) --bound;
  while ((bound + 1) * (bound + 1) <= half) ++bound;
  while (static_cast<UInt128>(r1) > bound) {
    const Int128 q = r0 / r1;
    const Int128 r2 = r0 - q * r1;
    r0 = r1;
    r1 = r2;
    const Int128 t2 = t0 - q * t1;
    t0 = t1;
    t1 = t2;
  }
  const Int128 den = t1 < 0 ? -t1 : t1;
  const Int128 num = t1 < 0 ? -r1 : r1;
  if (den == 0 || static_cast<UInt128>(den) > bound) return std::nullopt;
  const Int128 limit = static_cast<Int128>(INT64_MAX);
  if (num > limit || num < -limit || den > limit) return std::nullopt;
  return Rational(static_cast<std::int64_t>(num), static_cast<std::int64_t>(den));
}

UInt128 crt(std::uint64_t a1, std::uint64_t p1, std::uint64_t a2, std::uint64_t p2) {
  // x = a1 + p1 * ((a2 - a1) * p1^-1 mod p2)
  const PrimeField f2(p2);
  const std::uint64_t k = f2.mul(f2.sub(a2 % p2, a1 % p2), f2.inv(p1 % p2));
  return static_cast<UInt128>(a1) + static_cast<UInt128>(p1) * k;
}

}  // namespace dyncc::sym
