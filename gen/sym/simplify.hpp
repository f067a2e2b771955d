// Simplification: the smallest of the canonical, expanded and trigonometric-normal forms.
#pragma once

#include "sym/expr.hpp"

namespace dyncc::sym {

/// Returns the smallest (by DAG size) of: e itself, expand(e), and its trigonometric normal
/// form. All three are equal as functions; the normal form proves identities such as
/// sin(x)^2 + cos(x)^2 == 1.
Expr simplify(Expr e);

}  // namespace dyncc::sym
