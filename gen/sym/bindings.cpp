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
  // adjoint[x] = d objective / d x, accumulated over every use of x.
  std::unordered_map<Expr, Expr> adjoint;
  auto propagate = [&](Expr expression, Expr weight) {
    std::vector<Expr> inner;
    for (const Expr s : free_symbols(expression)) {
      if (bound_index.count(s) != 0 || is_var.count(s) != 0) inner.push_back(s);
    }
    if (inner.empty()) return;
    const std::vector<Expr> partials = gradient(expression, inner);
    for (std::size_t j = 0; j < inner.size(); ++j) {
      if (partials[j].is_zero()) continue;
      Expr& a = adjoint[inner[j]];
      a = a + weight * partials[j];
    }
  };
  propagate(objective, Expr(1));
  for (std::size_t k = bindings.list().size(); k-- > 0;) {
    const auto& [symbol, definition] = bindings.list()[k];
    const auto it = adjoint.find(symbol);
    if (it == adjoint.end() || it->second.is_zero()) continue;
    propagate(definition, adjoints.bind(it->second));
  }
  std::vector<Expr> out;
  out.reserve(vars.size());
  for (const Expr v : vars) {
    const auto it = adjoint.find(v);
    out.push_back(it == adjoint.end() ? Expr(0) : it->second);
  }
  return out;
}

}  // namespace dyncc::sym
