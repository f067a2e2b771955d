// Named intermediate results ("let" bindings) for algorithms built from expressions.
//
// Why: canonical sums are flat, so a recursive algorithm's intermediate sums (a link's force,
// used by its own joint and again by its parent's) would be merged into every sum that uses
// them, and the sharing the algorithm was designed around is lost. Binding an intermediate to
// a fresh symbol keeps it one value; the code generator lowers each definition once, in order.
// Expressions that contain bound symbols must not be differentiated or substituted as if the
// symbols were independent variables.
#pragma once

#include <span>
#include <string>
#include <utility>
#include <vector>

#include "sym/expr.hpp"

namespace dyncc::sym {

class Bindings {
 public:
  explicit Bindings(std::string prefix = "$let") : prefix_(std::move(prefix)) {}

  /// A fresh symbol standing for value (numbers and symbols are returned as they are: binding
  /// them saves nothing). Names are prefix + index: unique within this object.
  Expr bind(Expr value);

  /// symbol -> definition, in the order bound (a definition only uses earlier symbols).
  [[nodiscard]] const std::vector<std::pair<Expr, Expr>>& list() const { return list_; }

 private:
  std::string prefix_;
  std::vector<std::pair<Expr, Expr>> list_;
};

/// d(objective)/d(vars) when objective and the definitions of `bindings` contain bound symbols:
/// one reverse (adjoint) sweep over the bindings, last to first, so the recursion's sharing
/// carries over to the derivative. Each adjoint that is used more than once is bound in
/// `adjoints` (a second Bindings whose symbols must not clash: give it another prefix).
/// vars must be plain symbols that are not bound.
std::vector<Expr> gradient_through(Expr objective, const Bindings& bindings, std::span<const Expr> vars,
                                   Bindings& adjoints);

}  // namespace dyncc::sym
