// The node layout behind Expr. Only the sym/ sources include this.
#pragma once

#include <string>
#include <vector>

#include "sym/expr.hpp"

namespace dyncc::sym {

struct Node {
  Kind kind = Kind::Number;
  std::size_t hash = 0;
  Rational value;                 // Number value | Add constant | Mul coefficient
  std::string name;               // Symbol / Constant name
  std::vector<Expr> args;         // Add terms | Mul bases | function arguments
  std::vector<Rational> weights;  // Add coefficients | Mul exponents
};

/// Interns a node built by a constructor (the node must already be canonical).
Expr intern(Node&& node);

}  // namespace dyncc::sym
