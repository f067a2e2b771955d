#include "sym/diff.hpp"

#include <stdexcept>
#include <vector>

namespace dyncc::sym {

Differentiator::Differentiator(Expr var) : var_(var) {
  if (var.kind() != Kind::Symbol) throw std::invalid_argument("can only differentiate with respect to a symbol");
}

Expr Differentiator::operator()(Expr e) {
  if (e == var_) return Expr(1);
  if (e.args().empty()) return Expr(0);  // numbers, constants, other symbols
  if (const auto it = memo_.find(e.node()); it != memo_.end()) return it->second;

  Expr result;
  const auto args = e.args();
  switch (e.kind()) {
    case Kind::Add: {
      std::vector<std::pair<Rational, Expr>> terms;
      terms.reserve(args.size());
      for (std::size_t i = 0; i < args.size(); ++i) {
        const Expr d = (*this)(args[i]);
        if (!d.is_zero()) terms.emplace_back(e.weights()[i], d);
      }
      result = linear_combination(terms);
      break;
    }
    case Kind::Mul: {
      // d(c * prod b_i^e_i) = sum_i c * e_i * b_i^(e_i - 1) * b_i' * prod_{j != i} b_j^e_j
      std::vector<std::pair<Rational, Expr>> terms;
      std::vector<Expr> factors(args.size() + 1);
      for (std::size_t i = 0; i < args.size(); ++i) {
        const Expr d = (*this)(args[i]);
        if (d.is_zero()) continue;
        const auto weights = e.weights();
        for (std::size_t j = 0; j < args.size(); ++j) {
          const int ej = static_cast<int>(weights[j].num());
          factors[j] = pow(args[j], j == i ? ej - 1 : ej);
        }
        factors[args.size()] = d;
        terms.emplace_back(e.value() * weights[i], mul(factors));
      }
      result = linear_combination(terms);
      break;
    }
    case Kind::Sin: result = cos(args[0]) * (*this)(args[0]); break;
    case Kind::Cos: result = -sin(args[0]) * (*this)(args[0]); break;
    case Kind::Sqrt: result = (*this)(args[0]) / (Expr(2) * e); break;
    case Kind::Atan2: {
      const Expr y = args[0];
      const Expr x = args[1];
      const Expr dy = (*this)(y);
      const Expr dx = (*this)(x);
      result = (x * dy - y * dx) / (x * x + y * y);
      break;
    }
    default: result = Expr(0); break;
  }
  memo_.emplace(e.node(), result);
  return result;
}

Expr diff(Expr e, Expr var) { return Differentiator(var)(e); }

}  // namespace dyncc::sym
