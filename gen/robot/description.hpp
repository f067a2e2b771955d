// RobotDescription: the validated content of a robot YAML file, the data type every later
// stage (kinematics, dynamics, code generation) consumes.
//
// Why expressions stay symbolic: geometry is kept in terms of the named constant symbols (l2,
// b1, ...) so derived formulas read like the paper's and a constant can be changed without
// re-deriving. constant_values() gives the substitution when numbers are wanted.
// Why inertial entries are Exprs: each is either an exact number (a known value) or a single
// parameter symbol (an unknown), which keeps the dynamics linear in the unknowns.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sym/expr.hpp"
#include "sym/rational.hpp"
#include "sym/substitute.hpp"

namespace dyncc::robot {

/// 1-based line and column in the source file; 0 when unknown (e.g. built in code).
struct SourceLocation {
  int line = 0;
  int column = 0;
  [[nodiscard]] bool known() const { return line > 0; }
};

enum class Convention {
  Modified,  // Craig: frame i from a_{i-1}, alpha_{i-1}, d_i, theta_i (RotX TransX RotZ TransZ)
  Standard,  // Denavit-Hartenberg: a_i, alpha_i, d_i, theta_i (RotZ TransZ TransX RotX)
};

enum class JointType {
  Revolute,   // theta is the joint variable
  Prismatic,  // d is the joint variable
};

/// What nominal values that break physics (negative mass, non-PSD inertia) are reported as.
enum class ConsistencyMode { Error, Warn };

std::string_view to_string(Convention convention);
std::string_view to_string(JointType joint);

struct Constant {
  std::string name;
  sym::Expr symbol;     // sym::symbol(name): what the expressions contain
  sym::Rational value;  // exact, as written ("0.180" is 9/50)
  SourceLocation location;
};

/// Inertia tensor about the centre of mass in link axes. Off-diagonal entries are the tensor
/// entries themselves (-integral of x*y dm), as in URDF; entries not written are 0.
struct InertiaTensor {
  sym::Expr xx, yy, zz, xy, xz, yz;
};

struct Link {
  std::string name;
  std::string parent_name;  // "base" or the name of an earlier link
  int parent = -1;          // index into RobotDescription::links; -1 = base
  JointType joint = JointType::Revolute;
  sym::Expr a, alpha, d, theta;  // in coordinates, constants and pi
  sym::Expr mass;
  std::array<sym::Expr, 3> com;  // centre of mass in the link frame
  InertiaTensor inertia;
  std::string description;  // optional free text
  SourceLocation location;  // of the link's entry in `links`
  /// Where each written field is, keyed by its path inside the link: "theta", "com[1]",
  /// "inertia.xy". Later stages use it to point error messages at the source.
  std::map<std::string, SourceLocation> field_locations;

  /// theta for a revolute link, d for a prismatic one.
  [[nodiscard]] sym::Expr joint_expression() const { return joint == JointType::Revolute ? theta : d; }
  /// Location of a field, falling back to the link's own location.
  [[nodiscard]] SourceLocation location_of(std::string_view field) const;
};

/// The role an unknown parameter plays; decides how the dynamics stage uses it.
enum class ParameterRole { Mass, CenterOfMass, Inertia, CoulombFriction, ViscousFriction, RotorInertia };
std::string_view to_string(ParameterRole role);

struct Parameter {
  std::string name;
  sym::Expr symbol;
  double nominal = 0.0;  // from `parameters`
  ParameterRole role = ParameterRole::Mass;
  int link = -1;                    // owning link for inertial roles, else -1
  int coordinate = -1;              // owning coordinate for friction/rotor roles, else -1
  std::string field;                // where it is used, e.g. "links[2].inertia.xy"
  SourceLocation location;          // of that use
  SourceLocation nominal_location;  // of its entry in `parameters`
};

struct Friction {
  int coordinate = -1;
  sym::Expr coulomb;  // number or parameter symbol; 0 when not written
  sym::Expr viscous;
  SourceLocation location;
};

/// Motor rotor inertia reflected through the gearbox: gear_ratio^2 * inertia about the coordinate.
struct Rotor {
  int coordinate = -1;
  sym::Expr inertia;         // number or parameter symbol
  sym::Rational gear_ratio;  // always a known number, so the reflected inertia stays linear
  SourceLocation location;
  [[nodiscard]] sym::Expr reflected_inertia() const;
};

struct JointLimit {
  int coordinate = -1;
  double lower = 0.0;
  double upper = 0.0;
  SourceLocation location;
};

struct LoopPoint {
  std::string link_name;        // a link or "base"
  int link = -1;                // -1 = base
  std::array<sym::Expr, 3> at;  // in the link's frame; coordinates, constants and pi
  SourceLocation location;
};

/// A closure: the two points coincide for every value of the coordinates.
struct Loop {
  std::string name;
  std::array<LoopPoint, 2> points;
  SourceLocation location;
};

/// A user-chosen grouping of parameters (e.g. the paper's p0..p14).
struct BaseParameter {
  std::string name;
  sym::Expr value;  // in parameter symbols, constants and pi
  SourceLocation location;
};

/// A starting value for one parameter of the user grouping (or a parameter outside it, such as
/// a friction coefficient): the `initial_estimate:` section, e.g. the paper's p0..p20, which a
/// controller maps onto the base parameters as its first estimate.
struct EstimateEntry {
  std::string name;
  double value = 0.0;
  SourceLocation location;
};

struct RobotDescription {
  std::string name;
  std::string description;
  std::filesystem::path source_path;
  Convention convention = Convention::Modified;
  std::array<sym::Expr, 3> gravity;                  // exact numbers, base frame, m/s^2
  std::vector<sym::Expr> coordinates;                // symbols, in the order of `coordinates`
  std::vector<SourceLocation> coordinate_locations;  // parallel to coordinates
  std::vector<Constant> constants;                   // in file order
  std::vector<Link> links;                           // parents before children
  std::vector<Friction> friction;                    // at most one per coordinate, in file order
  std::vector<Rotor> rotors;                         // at most one per coordinate, in file order
  std::vector<JointLimit> joint_limits;              // at most one per coordinate, in file order
  std::vector<Parameter> parameters;                 // the unknowns, in order of first use in the file
  std::vector<Loop> loops;
  std::vector<BaseParameter> base_parameters;   // in file order
  std::vector<EstimateEntry> initial_estimate;  // in file order; names are groupings or parameters
  ConsistencyMode physical_consistency = ConsistencyMode::Error;

  /// constant symbol -> exact value; substitute() it to turn geometry into numbers.
  [[nodiscard]] sym::Substitution constant_values() const;
  /// Constant name -> value as double (for numeric checks and printing).
  [[nodiscard]] std::map<std::string, double> constant_doubles() const;
  /// Parameter name -> nominal value.
  [[nodiscard]] std::map<std::string, double> nominal_values() const;
  [[nodiscard]] std::array<double, 3> gravity_values() const;

  [[nodiscard]] std::optional<int> find_link(std::string_view link_name) const;
  [[nodiscard]] std::optional<int> find_coordinate(std::string_view coordinate_name) const;
  [[nodiscard]] const Constant* find_constant(std::string_view constant_name) const;
  [[nodiscard]] const Parameter* find_parameter(std::string_view parameter_name) const;
  [[nodiscard]] const std::string& coordinate_name(int index) const;
  /// Direct children of a link (-1 = base), in file order.
  [[nodiscard]] std::vector<int> children(int link) const;
};

}  // namespace dyncc::robot
