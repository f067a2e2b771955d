// Physical consistency of the nominal values: a rigid body has mass >= 0 and an inertia tensor
// about its centre of mass whose principal moments are >= 0 and obey the triangle inequality
// (each at most the sum of the other two). Friction coefficients and rotor inertias are >= 0.
#include <fmt/core.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <optional>

#include "robot/load_state.hpp"

namespace dyncc::robot::detail {

namespace {

class ConsistencyChecker {
 public:
  ConsistencyChecker(const RobotDescription& robot, DiagnosticSink& sink)
      : robot_(robot), sink_(sink), nominal_(robot.nominal_values()) {}

  void run() {
    for (std::size_t i = 0; i < robot_.links.size(); ++i) check_link(i);
    for (const Friction& friction : robot_.friction) {
      const std::string& coordinate = robot_.coordinate_name(friction.coordinate);
      check_non_negative(friction.coulomb, friction.location, fmt::format("friction.{}.coulomb", coordinate),
                         "coulomb friction");
      check_non_negative(friction.viscous, friction.location, fmt::format("friction.{}.viscous", coordinate),
                         "viscous friction");
    }
    for (const Rotor& rotor : robot_.rotors) {
      check_non_negative(rotor.inertia, rotor.location,
                         fmt::format("rotor.{}.inertia", robot_.coordinate_name(rotor.coordinate)), "rotor inertia");
    }
  }

 private:
  // Nominal value of an entry that is a number or a parameter symbol; empty if unknown.
  [[nodiscard]] std::optional<double> value_of(sym::Expr entry) const {
    if (entry.is_number()) return entry.value().to_double();
    if (entry.is_symbol()) {
      if (const auto found = nominal_.find(entry.name()); found != nominal_.end()) return found->second;
    }
    return std::nullopt;
  }

  void report(SourceLocation location, const std::string& field, const std::string& problem) {
    if (robot_.physical_consistency == ConsistencyMode::Error) {
      sink_.error(location, field,
                  fmt::format("physically inconsistent nominal values: {}; set 'physical_consistency: warn' to "
                              "accept them",
                              problem));
    } else {
      sink_.warning(location, field, fmt::format("physically inconsistent nominal values: {}", problem));
    }
  }

  void check_non_negative(sym::Expr entry, SourceLocation location, const std::string& field, std::string_view what) {
    const auto value = value_of(entry);
    if (value && *value < 0.0) report(location, field, fmt::format("{} is negative ({})", what, *value));
  }

  void check_link(std::size_t index) {
    const Link& link = robot_.links[index];
    const std::string prefix = fmt::format("links[{}]", index);
    const auto mass = value_of(link.mass);
    if (mass && *mass < 0.0) {
      report(link.location_of("mass"), prefix + ".mass", fmt::format("negative mass ({} kg)", *mass));
    }
    const InertiaTensor& t = link.inertia;
    const auto xx = value_of(t.xx);
    const auto yy = value_of(t.yy);
    const auto zz = value_of(t.zz);
    const auto xy = value_of(t.xy);
    const auto xz = value_of(t.xz);
    const auto yz = value_of(t.yz);
    if (!xx || !yy || !zz || !xy || !xz || !yz) return;  // a missing nominal value is reported elsewhere
    const SourceLocation at = link.location_of("inertia");
    const std::string field = prefix + ".inertia";
    // Tolerance relative to the tensor's size, so rounding in hand-written values is not flagged.
    const double scale =
        std::max({std::abs(*xx), std::abs(*yy), std::abs(*zz), std::abs(*xy), std::abs(*xz), std::abs(*yz)});
    const double tolerance = 1e-9 * scale + 1e-15;
    // The diagonal triangle inequalities first: they give the most readable message.
    const struct {
      double first, second, third;
      const char* text;
    } triangles[] = {{*xx, *yy, *zz, "xx + yy >= zz"},
                     {*yy, *zz, *xx, "yy + zz >= xx"},
                     {*zz, *xx, *yy, "zz + xx >= yy"}};
    for (const auto& triangle : triangles) {
      if (triangle.first + triangle.second < triangle.third - tolerance) {
        report(at, field,
               fmt::format("the inertia violates the triangle inequality {} ({} + {} < {})", triangle.text,
                           triangle.first, triangle.second, triangle.third));
        return;
      }
    }
    Eigen::Matrix3d tensor;
    tensor << *xx, *xy, *xz, *xy, *yy, *yz, *xz, *yz, *zz;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(tensor, Eigen::EigenvaluesOnly);
    if (solver.info() != Eigen::Success) {
      report(at, field, "the inertia tensor's principal moments could not be computed");
      return;
    }
    const Eigen::Vector3d& moments = solver.eigenvalues();  // ascending
    if (moments[0] < -tolerance) {
      report(at, field,
             fmt::format("the inertia tensor is not positive semi-definite (principal moments {:.6g}, {:.6g}, "
                         "{:.6g})",
                         moments[0], moments[1], moments[2]));
      return;
    }
    if (moments[0] + moments[1] < moments[2] - tolerance) {
      report(at, field,
             fmt::format("the principal moments violate the triangle inequality ({:.6g} + {:.6g} < {:.6g})", moments[0],
                         moments[1], moments[2]));
      return;
    }
    const bool mass_written = link.field_locations.contains("mass");  // else "missing mass" was reported
    if (mass_written && mass && *mass == 0.0 && scale > 0.0) {
      report(at, field, "a link with zero mass cannot have a nonzero inertia");
    }
  }

  const RobotDescription& robot_;
  DiagnosticSink& sink_;
  std::map<std::string, double> nominal_;
};

}  // namespace

void check_physical_consistency(const RobotDescription& robot, DiagnosticSink& sink) {
  ConsistencyChecker(robot, sink).run();
}

}  // namespace dyncc::robot::detail
