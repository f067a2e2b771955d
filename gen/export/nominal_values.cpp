#include "export/nominal_values.hpp"

#include "sym/evaluate.hpp"

namespace dyncc::exporting {

SymbolValues nominal_symbol_values(const robot::RobotDescription& robot) {
  SymbolValues values;
  for (const auto& [name, value] : robot.constant_doubles()) values.emplace(name, value);
  for (const auto& [name, value] : robot.nominal_values()) values.emplace(name, value);
  return values;
}

double value_of(sym::Expr e, const SymbolValues& values) { return sym::evaluate(e, values); }

}  // namespace dyncc::exporting
