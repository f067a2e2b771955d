#include "sym/diff.hpp"

#include <stdexcept>
#include <unordered_map>
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

namespace dyncc::sym {

std::vector<Expr> gradient(Expr f, std::span<const Expr> vars) {
  // Post-order of the nodes that depend on some variable.
  std::unordered_map<const Node*, int> var_index;
  for (std::size_t i = 0; i < vars.size(); ++i) var_index.emplace(vars[i].node(), static_cast<int>(i));
  std::unordered_map<const Node*, bool> depends;
  std::vector<Expr> order;
  std::vector<std::pair<Expr, bool>> stack{{f, false}};
  while (!stack.empty()) {
    auto [e, ready] = stack.back();
    stack.pop_back();
    if (depends.contains(e.node())) continue;
    if (!ready) {
      stack.emplace_back(e, true);
      for (const Expr a : e.args()) {
        if (!depends.contains(a.node())) stack.emplace_back(a, false);
      }
      continue;
    }
    bool d = var_index.contains(e.node());
    for (const Expr a : e.args()) d = d || depends.at(a.node());
    depends.emplace(e.node(), d);
    if (d) order.push_back(e);
  }
  // Adjoint contributions, summed once when a node is reached (parents come first in reverse order).
  std::unordered_map<const Node*, std::vector<Expr>> contributions;
  contributions[f.node()].push_back(Expr(1));
  std::vector<Expr> result(vars.size(), Expr(0));
  for (std::size_t i = order.size(); i-- > 0;) {
    const Expr e = order[i];
    const auto found = contributions.find(e.node());
    if (found == contributions.end()) continue;
    const Expr adj = add(found->second);
    contributions.erase(found);
    if (adj.is_zero()) continue;
    if (const auto v = var_index.find(e.node()); v != var_index.end())
      result[static_cast<std::size_t>(v->second)] = adj;
    const auto args = e.args();
    auto push = [&](Expr child, Expr partial) {
      if (depends.at(child.node())) contributions[child.node()].push_back(adj * partial);
    };
    switch (e.kind()) {
      case Kind::Add:
        for (std::size_t i = 0; i < args.size(); ++i) push(args[i], number(e.weights()[i]));
        break;
      case Kind::Mul:
        for (std::size_t i = 0; i < args.size(); ++i) {
          if (!depends.at(args[i].node())) continue;
          push(args[i], number(e.weights()[i]) * e / args[i]);
        }
        break;
      case Kind::Sin: push(args[0], cos(args[0])); break;
      case Kind::Cos: push(args[0], -sin(args[0])); break;
      case Kind::Sqrt: push(args[0], Expr(1) / (Expr(2) * e)); break;
      case Kind::Atan2: {
        const Expr r2 = args[0] * args[0] + args[1] * args[1];
        push(args[0], args[1] / r2);
        push(args[1], -args[0] / r2);
        break;
      }
      default: break;
    }
  }
  return result;
}

}  // namespace dyncc::sym
