// Exact differentiation over the DAG.
#pragma once

#include <span>
#include <unordered_map>
#include <vector>

#include "sym/expr.hpp"

namespace dyncc::sym {

/// d/d(var) with a memo table over nodes, so a subexpression shared by many outputs is
/// differentiated once. Keep one Differentiator per variable alive to reuse its memo across
/// many expressions (e.g. every entry of a mass matrix).
class Differentiator {
 public:
  explicit Differentiator(Expr var);
  Expr operator()(Expr e);

 private:
  Expr var_;
  std::unordered_map<const Node*, Expr> memo_;
};

Expr diff(Expr e, Expr var);

}  // namespace dyncc::sym

namespace dyncc::sym {

/// All partial derivatives of f with respect to vars in ONE reverse (adjoint) sweep over the
/// DAG: d f / d vars[i]. Much cheaper than one forward derivative per variable when there are
/// many variables (e.g. the regressor: the torque differentiated by every parameter).
std::vector<Expr> gradient(Expr f, std::span<const Expr> vars);

}  // namespace dyncc::sym
