// Expansion: products and positive integer powers of sums are multiplied out.
#pragma once

#include "sym/expr.hpp"

namespace dyncc::sym {

/// Fully distributes products over sums (also inside function arguments). Negative powers
/// are kept as factors. Memoised over the DAG within one call.
Expr expand(Expr e);

}  // namespace dyncc::sym
