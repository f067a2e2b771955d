// Named intermediate results ("let" bindings) for algorithms built from expressions.
//
// Why: canonical sums are flat, so a recursive algorithm's intermediate sums (a link's force,
// used by its own joint and again by its parent's) would be merged into every sum that uses
// them, and the sharing the algorithm was designed around is lost. Binding an intermediate to
// a fresh symbol keeps it one value; the code generator lowers each definition once, in order.
// Expressions that contain bound symbols must not be differentiated or substituted as if the
// symbols were independent variables.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "sym/expr.hpp"

namespace dyncc::sym {

class Bindings {
 public:
  /// A fresh symbol standing for value (numbers and symbols are returned as they are: binding
  /// them saves nothing). Names are "$let<prefix><index>": unique within this object.
  Expr bind(Expr value);

  /// symbol -> definition, in the order bound (a definition only uses earlier symbols).
  [[nodiscard]] const std::vector<std::pair<Expr, Expr>>& list() const { return list_; }

 private:
  std::vector<std::pair<Expr, Expr>> list_;
};

}  // namespace dyncc::sym
