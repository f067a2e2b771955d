#include "sym/bindings.hpp"

#include <string>
#include <unordered_map>

#include "sym/diff.hpp"

namespace dyncc::sym {

Expr Bindings::bind(Expr value) {
  if (value.kind() == Kind::Number || value.kind() == Kind::Symbol || value.kind() == Kind::Constant) return value;
  // A product of a number and one symbol is as cheap to recompute as to load.
  const Expr s = symbol(std::string(prefix_).append(std::to_string(list_.size())));
  list_.emplace_back(s, value);
  return s;
}

std::vector<Expr> gradient_through(Expr objective, const Bindings& bindings, std::span<const Expr> vars,
                                   Bindings& adjoints) {
  std::unordered_map<Expr, std::size_t> bound_index;
  for (std::size_t k = 0; k < bindings.list().size(); ++k) bound_index.emplace(bindings.list()[k].first, k);
  std::unordered_map<Expr, bool> is_var;
  for (const Expr v : vars) is_var.emplace(v, true);
  // d objective / d x = the sum of these terms, one per use of x; summed once, when x is reached
  // (adding one term at a time would rebuild an ever longer canonical sum: quadratic).
  std::unordered_map<Expr, std::vector<Expr>> adjoint;
  auto propagate = [&](Expr expression, Expr weight) {
    std::vector<Expr> inner;
    for (const Expr s : free_symbols(expression)) {
      if (bound_index.contains(s) || is_var.contains(s)) inner.push_back(s);
    }
    if (inner.empty()) return;
    const std::vector<Expr> partials = gradient(expression, inner);
    for (std::size_t j = 0; j < inner.size(); ++j) {
      if (!partials[j].is_zero()) adjoint[inner[j]].push_back(weight * partials[j]);
    }
  };
  propagate(objective, Expr(1));
  for (std::size_t k = bindings.list().size(); k-- > 0;) {
    const auto& [symbol, definition] = bindings.list()[k];
    const auto it = adjoint.find(symbol);
    if (it == adjoint.end()) continue;
    const Expr total = add(it->second);
    if (total.is_zero()) continue;
    propagate(definition, adjoints.bind(total));
  }
  std::vector<Expr> out;
  out.reserve(vars.size());
  for (const Expr v : vars) {
    const auto it = adjoint.find(v);
    out.push_back(it == adjoint.end() ? Expr(0) : add(it->second));
  }
  return out;
}

}  // namespace dyncc::sym
