// Internal to the loader: expressions and "number or parameter name" entries from YAML scalars,
// with errors pointing at the exact character inside the scalar.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "robot/yaml_reader.hpp"
#include "sym/expr.hpp"

namespace dyncc::robot::detail {

/// Which names an expression may use, and why other known names may not appear.
struct SymbolScope {
  std::string description;                       // e.g. "coordinates, constants and pi"
  std::set<std::string> names;                   // allowed names (also the suggestions)
  std::map<std::string, std::string> forbidden;  // known name -> what it is ("an inertial parameter")
};

/// Longest expression accepted: descriptions are written by hand, so anything longer is a mistake
/// (or an attack) and would only make later stages slow.
inline constexpr std::size_t kMaxExpressionLength = 10000;

/// Parses an expression scalar and checks every symbol against the scope.
std::optional<sym::Expr> read_expression(YamlReader& reader, const Located& value, const SymbolScope& scope);

/// An inertial, friction or rotor entry: an exact number or the name of an unknown parameter.
struct NumberOrName {
  std::optional<sym::Rational> number;
  std::string name;  // set when not a number
};
std::optional<NumberOrName> read_number_or_name(YamlReader& reader, const Located& value);

}  // namespace dyncc::robot::detail
