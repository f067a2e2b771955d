// The standard (barycentric) parameters: the dynamics is linear in them.
//
// Per link: mass M, first moments MX, MY, MZ (= mass * centre of mass, link frame) and the
// inertia tensor about the link ORIGIN, XX, XY, XZ, YY, YZ, ZZ (tensor entries, so XY is
// -integral(x*y dm), as in the description). Per coordinate: reflected rotor inertia IA
// (gear_ratio^2 * Jm), Coulomb friction FC and viscous friction FV. Each has a definition in the
// description's own names (XX3 = i3xx + m3*(y3^2 + z3^2)); parameters whose definition is
// identically 0 (a centre of mass on an axis, a diagonal inertia) are left out.
#pragma once

#include <string>
#include <vector>

#include "robot/description.hpp"
#include "sym/expr.hpp"

namespace dyncc::dyn {

enum class StandardKind { M, MX, MY, MZ, XX, XY, XZ, YY, YZ, ZZ, IA, FC, FV };

struct StandardParameter {
  std::string name;      // e.g. "MX2"
  sym::Expr symbol;      // the symbol the derived expressions contain
  sym::Expr definition;  // in the description's parameter names and constants
  StandardKind kind = StandardKind::M;
  int link = -1;        // inertial kinds
  int coordinate = -1;  // IA, FC, FV
};

struct StandardParameters {
  std::vector<StandardParameter> list;
  /// Index into list of each link's parameters (or -1 when left out), in StandardKind order M..ZZ.
  std::vector<std::array<int, 10>> of_link;
  std::vector<int> rotor_of, coulomb_of, viscous_of;  // per coordinate, -1 when absent

  [[nodiscard]] sym::Expr symbol_or_zero(int index) const {
    return index < 0 ? sym::Expr(0) : list[static_cast<std::size_t>(index)].symbol;
  }
  [[nodiscard]] std::vector<sym::Expr> symbols() const;
  /// standard symbol -> definition in the description's names.
  [[nodiscard]] sym::Substitution definitions() const;
};

StandardParameters standard_parameters(const robot::RobotDescription& robot);

std::string_view to_string(StandardKind kind);

}  // namespace dyncc::dyn
