// Random robot descriptions for the export tests, built to reach every path of the export: both
// D-H conventions, revolute and prismatic joints, branches, joint offsets and arbitrary twists,
// joints driven by a scaled coordinate (2*q1, -q2), extra joints coupled to one or several
// coordinates (a second joint at 2*q1, one at q3 - q1 + 0.2), welded links (a constant joint
// variable), a massless first link on the base, thin rods (a zero principal moment), rotors with
// gear ratios, friction, joint limits, and gravity of 9.81 in a random direction.
// Inertias are physically consistent (boxes and rods turned by random rotations), so dyncc
// accepts them; MuJoCo still needs the export's repairs for the massless link and the rods.
#pragma once

#include <Eigen/Geometry>
#include <iomanip>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace dyncc::test {

/// Concatenation by append: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string at -O3.
inline std::string cat(std::initializer_list<std::string_view> parts) {
  std::string s;
  for (const std::string_view p : parts) s.append(p);
  return s;
}

inline std::string exact(double x) {
  std::ostringstream s;
  s << std::setprecision(17) << x;
  return s.str();
}

inline std::string random_export_robot(std::mt19937_64& rng, int index) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // Geometry is exact in dyncc (0.123 is 123/1000): few digits keep its rationals small.
  auto between = [&](double lo, double hi) {
    std::ostringstream t;
    t << std::fixed << std::setprecision(3) << lo + (hi - lo) * u(rng);
    return t.str();
  };
  auto pick = [&](const std::vector<std::string>& options) {
    return options[std::uniform_int_distribution<std::size_t>(0, options.size() - 1)(rng)];
  };
  const std::vector<std::string> angles{"0", "pi/2", "-pi/2", "pi", "pi/3", "-pi/4", "0.3"};
  const int n = std::uniform_int_distribution<int>(2, 4)(rng);
  const int extra = std::uniform_int_distribution<int>(1, 3)(rng);
  std::ostringstream y, params, limits, friction, rotors;
  // 9.81 in directions with short exact components (URDF consumers assume that size).
  const std::string gravity = pick({"[0, 0, -9.81]", "[0, -9.81, 0]", "[9.81, 0, 0]", "[0, 5.886, -7.848]",
                                    "[-5.886, 0, -7.848]", "[3.5316, 4.7088, -7.848]"});
  y << "name: random_export_" << index << "\nconvention: " << (u(rng) < 0.5 ? "modified" : "standard")
    << "\ngravity: " << gravity << "\ncoordinates: [";
  for (int k = 1; k <= n; ++k) y << (k > 1 ? ", " : "") << "q" << k;
  y << "]\nlinks:\n";
  for (int i = 1; i <= n + extra; ++i) {
    const std::string s = std::to_string(i);
    const std::string parent = i == 1 || u(rng) < 0.25
                                   ? std::string("base")
                                   : cat({"link", std::to_string(std::uniform_int_distribution<int>(1, i - 1)(rng))});
    std::string variable;  // the joint variable's coordinate part; empty for a welded link
    if (i <= n) {
      variable = cat({pick({"", "", "-", "2*"}), "q", s});
    } else {
      const std::string qa = cat({"q", std::to_string(std::uniform_int_distribution<int>(1, n)(rng))});
      const std::string qb = cat({"q", std::to_string(std::uniform_int_distribution<int>(1, n)(rng))});
      const double kind = u(rng);
      if (kind < 0.35) {
        variable = cat({"2*", qa});  // follows one joint: an MJCF joint equality, a URDF mimic
      } else if (kind < 0.75) {
        variable = qa == qb ? qa : cat({qa, " - ", qb});  // follows several: an MJCF tendon equality
      } else if (kind < 0.9) {
        variable = cat({qa, " + ", qb});
      }  // else welded: a constant joint variable
    }
    const bool prismatic = !variable.empty() && u(rng) < 0.25;
    const bool massless = i == 1 && parent == "base" && !prismatic && u(rng) < 0.3;
    const bool rod = !massless && u(rng) < 0.2;
    std::string theta = pick(angles), d = between(-0.3, 0.3);
    if (prismatic) {
      d = cat({variable, " + ", between(0.0, 0.2)});
    } else if (!variable.empty()) {
      theta = u(rng) < 0.5 ? variable : cat({variable, " + ", pick(angles)});
    }
    y << "  - name: link" << s << "\n    parent: " << parent
      << "\n    joint: " << (prismatic ? "prismatic" : "revolute")
      << "\n    a: " << (u(rng) < 0.3 ? std::string("0") : between(-0.4, 0.4)) << "\n    alpha: " << pick(angles)
      << "\n    d: " << d << "\n    theta: " << theta << "\n    mass: m" << s << "\n    com: [x" << s << ", y" << s
      << ", z" << s << "]\n    inertia: {xx: i" << s << "xx, yy: i" << s << "yy, zz: i" << s << "zz, xy: i" << s
      << "xy, xz: i" << s << "xz, yz: i" << s << "yz}\n";
    // A box (or a rod: two sides 0) turned by a random rotation. The massless link keeps a box's
    // inertia (like the PUMA 560's link 1, which has mass 0 and a moment about its axis).
    const double m = massless ? 0.0 : 0.2 + 3.0 * u(rng);
    const double bx = 0.05 + 0.4 * u(rng), by = rod ? 0.0 : 0.02 + 0.3 * u(rng), bz = rod ? 0.0 : 0.02 + 0.3 * u(rng);
    const double box_mass = massless ? 1.0 : m;
    const Eigen::Vector3d principal(box_mass * (by * by + bz * bz) / 12, box_mass * (bx * bx + bz * bz) / 12,
                                    box_mass * (bx * bx + by * by) / 12);
    const Eigen::Quaterniond turn(Eigen::Vector4d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized());
    const Eigen::Matrix3d R = turn.toRotationMatrix();
    const Eigen::Matrix3d I = R * principal.asDiagonal() * R.transpose();
    params << "  m" << s << ": " << exact(m) << "\n";
    for (const char* axis : {"x", "y", "z"}) params << "  " << axis << s << ": " << between(-0.2, 0.2) << "\n";
    params << "  i" << s << "xx: " << exact(I(0, 0)) << "\n  i" << s << "yy: " << exact(I(1, 1)) << "\n  i" << s
           << "zz: " << exact(I(2, 2)) << "\n  i" << s << "xy: " << exact(I(0, 1)) << "\n  i" << s
           << "xz: " << exact(I(0, 2)) << "\n  i" << s << "yz: " << exact(I(1, 2)) << "\n";
  }
  for (int k = 1; k <= n; ++k) {
    const std::string s = std::to_string(k);
    if (u(rng) < 0.5) {
      rotors << "  q" << s << ": {inertia: jm" << s << ", gear_ratio: " << between(5, 100) << "}\n";
      params << "  jm" << s << ": " << between(1e-5, 1e-4) << "\n";
    }
    if (u(rng) < 0.5) {
      friction << "  q" << s << ": {coulomb: fc" << s << ", viscous: fv" << s << "}\n";
      params << "  fc" << s << ": " << between(0, 0.5) << "\n  fv" << s << ": " << between(0, 0.5) << "\n";
    }
    if (u(rng) < 0.5) limits << "  q" << s << ": [" << between(-2, -0.5) << ", " << between(0.5, 2) << "]\n";
  }
  if (!rotors.str().empty()) y << "rotor:\n" << rotors.str();
  if (!friction.str().empty()) y << "friction:\n" << friction.str();
  if (!limits.str().empty()) y << "joint_limits:\n" << limits.str();
  y << "physical_consistency: warn\nparameters:\n" << params.str();
  return y.str();
}

}  // namespace dyncc::test
