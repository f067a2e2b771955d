// Numbers for a description's symbols: its constants and the nominal values of its parameters.
// Export writes one concrete mechanism, so every geometric and inertial entry becomes a number.
#pragma once

#include <string>
#include <unordered_map>

#include "robot/description.hpp"
#include "sym/expr.hpp"

namespace dyncc::exporting {

using SymbolValues = std::unordered_map<std::string, double>;

/// Constants and parameters (nominal values) by name; coordinates are not included.
SymbolValues nominal_symbol_values(const robot::RobotDescription& robot);

/// The value of an expression in constants, parameters (and pi).
double value_of(sym::Expr e, const SymbolValues& values);

}  // namespace dyncc::exporting
