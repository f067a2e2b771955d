#include "robot/expression_reader.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <exception>

#include "robot/spelling.hpp"
#include "sym/parse.hpp"

namespace dyncc::robot::detail {

namespace {

// Column of the 1-based `column_in_text` inside the scalar, in file coordinates.
SourceLocation point_inside(const ScalarPosition& position, std::size_t column_in_text) {
  SourceLocation location = position.start;
  if (position.exact && column_in_text >= 1) location.column += static_cast<int>(column_in_text) - 1;
  return location;
}

}  // namespace

std::optional<sym::Expr> read_expression(YamlReader& reader, const Located& value, const SymbolScope& scope) {
  if (!reader.expect_scalar(value, "an expression")) return std::nullopt;
  const std::string& text = value.node.Scalar();
  if (text.size() > kMaxExpressionLength) {
    reader.sink().error(value.location, value.path,
                        fmt::format("expression is {} characters long; the limit is {}", text.size(),
                                    kMaxExpressionLength));
    return std::nullopt;
  }
  const ScalarPosition position = reader.scalar_position(value);
  sym::ParseResult parsed;
  try {
    parsed = sym::parse(text);
  } catch (const std::exception& e) {
    // The engine reports arithmetic trouble (overflow, domain) by exception; keep it a diagnostic.
    reader.sink().error(value.location, value.path, fmt::format("cannot evaluate expression: {}", e.what()));
    return std::nullopt;
  }
  if (!parsed.ok()) {
    reader.sink().error(point_inside(position, parsed.error.column), value.path,
                        fmt::format("invalid expression: {}", parsed.error.message));
    return std::nullopt;
  }
  bool all_known = true;
  for (const sym::SymbolUse& use : parsed.symbols) {
    if (scope.names.contains(use.name)) continue;
    all_known = false;
    const SourceLocation at = point_inside(position, use.column);
    if (const auto known = scope.forbidden.find(use.name); known != scope.forbidden.end()) {
      reader.sink().error(at, value.path,
                          fmt::format("'{}' is {}; this expression may use only {}", use.name, known->second,
                                      scope.description));
    } else {
      const std::string suggestion =
          reader.sink().saturated()
              ? std::string()
              : closest_match(use.name, std::vector<std::string>(scope.names.begin(), scope.names.end()));
      reader.sink().error(at, value.path,
                          unknown_name_message("symbol", use.name, "this expression may use " + scope.description,
                                               suggestion),
                          suggestion);
    }
  }
  if (!all_known) return std::nullopt;
  return parsed.expr;
}

std::optional<NumberOrName> read_number_or_name(YamlReader& reader, const Located& value) {
  if (!reader.expect_scalar(value, "a number or a parameter name")) return std::nullopt;
  const std::string& text = value.node.Scalar();
  if (looks_like_number(text) || is_non_finite_spelling(text)) {
    auto number = reader.exact_number(value);
    if (!number) return std::nullopt;
    return NumberOrName{number, {}};
  }
  if (!is_identifier(text)) {
    reader.sink().error(value.location, value.path,
                        fmt::format("expected a number or a parameter name, got '{}' (expressions are not allowed "
                                    "here: they would make the model nonlinear in its parameters; group "
                                    "parameters under base_parameters instead)",
                                    text.substr(0, 40)));
    return std::nullopt;
  }
  auto name = reader.identifier(value, "a parameter name");
  if (!name) return std::nullopt;
  return NumberOrName{std::nullopt, *name};
}

}  // namespace dyncc::robot::detail
