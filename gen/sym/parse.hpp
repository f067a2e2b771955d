// Parser for the expressions written in robot descriptions and on the command line.
//
// Grammar (usual precedence, '^' and '**' right-associative, unary minus binds looser than '^'):
//   expr   := term (('+' | '-') term)*
//   term   := unary (('*' | '/') unary)*
//   unary  := ('-' | '+') unary | power
//   power  := primary (('^' | '**') unary)?
//   primary:= NUMBER | NAME | NAME '(' expr (',' expr)* ')' | '(' expr ')'
// Numbers are exact: "0.18" is 9/50. Functions: sin, cos, sqrt, atan2. 'pi' is the constant.
// Exponents must fold to an integer (|n| <= 64) or a half-integer (then sqrt is used).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sym/expr.hpp"

namespace dyncc::sym {

struct SymbolUse {
  std::string name;
  std::size_t column;  // 1-based column of the name's first character within the parsed text
};

struct ParseError {
  std::size_t column = 0;  // 1-based
  std::string message;     // what was expected, e.g. "expected ')' to close '(' at column 3"
};

struct ParseResult {
  std::optional<Expr> expr;        // set on success
  ParseError error;                // set on failure
  std::vector<SymbolUse> symbols;  // every symbol occurrence, in text order (for unknown-name checks)
  [[nodiscard]] bool ok() const { return expr.has_value(); }
};

ParseResult parse(std::string_view text);

/// Convenience for code and tests: parses or throws std::invalid_argument with the message.
Expr parse_or_throw(std::string_view text);

}  // namespace dyncc::sym
