#include "sym/bindings.hpp"

#include <string>

namespace dyncc::sym {

Expr Bindings::bind(Expr value) {
  if (value.kind() == Kind::Number || value.kind() == Kind::Symbol || value.kind() == Kind::Constant) return value;
  // A product of a number and one symbol is as cheap to recompute as to load.
  const Expr s = symbol(std::string("$let").append(std::to_string(list_.size())));
  list_.emplace_back(s, value);
  return s;
}

}  // namespace dyncc::sym
