#include "sym/expand.hpp"

#include <unordered_map>
#include <vector>

#include "sym/substitute.hpp"

namespace dyncc::sym {
namespace {

// A sum being accumulated: coefficient per coefficient-free term. Number terms are keyed by 1.
using SumMap = std::unordered_map<Expr, Rational>;

void add_into(SumMap& out, Expr term, const Rational& coef) {
  auto [c, rest] = split_coefficient(term);
  Rational& slot = out[rest];
  slot += coef * c;
}

// Terms of an expanded expression as (coef, coef-free term) pairs.
std::vector<std::pair<Rational, Expr>> terms_of(Expr e) {
  std::vector<std::pair<Rational, Expr>> out;
  if (e.kind() == Kind::Add) {
    out.reserve(e.args().size() + 1);
    if (!e.value().is_zero()) out.emplace_back(e.value(), Expr(1));
    for (std::size_t i = 0; i < e.args().size(); ++i) out.emplace_back(e.weights()[i], e.args()[i]);
  } else {
    auto [c, rest] = split_coefficient(e);
    out.emplace_back(c, rest);
  }
  return out;
}

// True when t is a single term with no sum left to distribute.
bool is_distributed(Expr t) {
  if (t.kind() == Kind::Add) return false;
  if (t.kind() == Kind::Mul) {
    for (std::size_t i = 0; i < t.args().size(); ++i) {
      if (t.args()[i].kind() == Kind::Add && !t.weights()[i].is_negative()) return false;
    }
  }
  return true;
}

std::vector<std::pair<Rational, Expr>> multiply(const std::vector<std::pair<Rational, Expr>>& a,
                                                const std::vector<std::pair<Rational, Expr>>& b) {
  SumMap acc;
  acc.reserve(a.size() * b.size());
  for (const auto& [ca, ta] : a) {
    for (const auto& [cb, tb] : b) {
      const Expr product = ta * tb;
      if (is_distributed(product)) {
        add_into(acc, product, ca * cb);
      } else {
        // The product of two expanded terms can be a sum again: sqrt(u)*sqrt(u) == u. Expand it
        // too, or the result is not fully expanded (and expand is not idempotent).
        for (const auto& [c, t] : terms_of(expand(product))) add_into(acc, t, ca * cb * c);
      }
    }
  }
  std::vector<std::pair<Rational, Expr>> out;
  out.reserve(acc.size());
  for (const auto& [t, c] : acc) {
    if (!c.is_zero()) out.emplace_back(c, t);
  }
  return out;
}

struct Expander {
  std::unordered_map<const Node*, Expr> memo;

  Expr run(Expr e) {
    if (e.args().empty()) return e;
    if (const auto it = memo.find(e.node()); it != memo.end()) return it->second;
    Expr result;
    switch (e.kind()) {
      case Kind::Add: {
        std::vector<std::pair<Rational, Expr>> terms;
        terms.reserve(e.args().size());
        for (std::size_t i = 0; i < e.args().size(); ++i) terms.emplace_back(e.weights()[i], run(e.args()[i]));
        result = linear_combination(terms, e.value());
        break;
      }
      case Kind::Mul: {
        std::vector<std::pair<Rational, Expr>> acc{{e.value(), Expr(1)}};
        for (std::size_t i = 0; i < e.args().size(); ++i) {
          const int exponent = static_cast<int>(e.weights()[i].num());
          const Expr base = run(e.args()[i]);
          if (exponent > 0 && base.kind() == Kind::Add) {
            const auto base_terms = terms_of(base);
            for (int k = 0; k < exponent; ++k) acc = multiply(acc, base_terms);
          } else {
            acc = multiply(acc, terms_of(pow(base, exponent)));
          }
        }
        result = linear_combination(acc);
        break;
      }
      default: {
        std::vector<Expr> args;
        args.reserve(e.args().size());
        for (const Expr a : e.args()) args.push_back(run(a));
        result = rebuild(e, args);
        break;
      }
    }
    memo.emplace(e.node(), result);
    return result;
  }
};

}  // namespace

Expr expand(Expr e) {
  Expander x;
  return x.run(e);
}

}  // namespace dyncc::sym
