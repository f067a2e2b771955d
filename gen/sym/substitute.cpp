#include "sym/substitute.hpp"

#include <vector>

namespace dyncc::sym {

Expr rebuild(Expr e, std::span<const Expr> new_args) {
  const std::span<const Expr> a = new_args;  // short name for the cases below
  switch (e.kind()) {
    case Kind::Add: {
      std::vector<std::pair<Rational, Expr>> terms;
      terms.reserve(a.size());
      for (std::size_t i = 0; i < a.size(); ++i) terms.emplace_back(e.weights()[i], a[i]);
      return linear_combination(terms, e.value());
    }
    case Kind::Mul: {
      std::vector<Expr> factors;
      factors.reserve(a.size() + 1);
      factors.emplace_back(number(e.value()));
      for (std::size_t i = 0; i < a.size(); ++i) factors.push_back(pow(a[i], static_cast<int>(e.weights()[i].num())));
      return mul(factors);
    }
    case Kind::Sin: return sin(a[0]);
    case Kind::Cos: return cos(a[0]);
    case Kind::Sqrt: return sqrt(a[0]);
    case Kind::Atan2: return atan2(a[0], a[1]);
    default: return e;
  }
}

namespace {

struct Substituter {
  const Substitution& map;
  std::unordered_map<const Node*, Expr> memo;

  Expr run(Expr e) {
    if (const auto it = map.find(e); it != map.end()) return it->second;
    if (e.args().empty()) return e;
    if (const auto it = memo.find(e.node()); it != memo.end()) return it->second;
    std::vector<Expr> new_args;
    new_args.reserve(e.args().size());
    bool changed = false;
    for (const Expr a : e.args()) {
      new_args.push_back(run(a));
      changed = changed || !(new_args.back() == a);
    }
    const Expr result = changed ? rebuild(e, new_args) : e;
    memo.emplace(e.node(), result);
    return result;
  }
};

}  // namespace

Expr substitute(Expr e, const Substitution& map) {
  if (map.empty()) return e;
  Substituter s{map, {}};
  return s.run(e);
}

}  // namespace dyncc::sym
