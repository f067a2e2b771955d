// Printing expressions as text that parse() reads back to the same canonical node.
#pragma once

#include <string>

#include "sym/expr.hpp"

namespace dyncc::sym {

/// Infix text in a readable, deterministic order (positive terms first, names in natural
/// order: q2 before q10), exact rational coefficients ("0.18", "1/3").
std::string to_string(Expr e);

/// LaTeX for documents: \sin(q_{2}), fractions, subscripts on trailing digits.
std::string to_latex(Expr e);

}  // namespace dyncc::sym
