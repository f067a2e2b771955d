// dyncc's Lagrangian dynamics (H, Christoffel C, tau_g, the regressor) against an independent
// numeric recursive Newton-Euler algorithm (newton_euler.hpp), at random states: the PUMA 560
// (standard D-H), the Panda (modified D-H), the planar arm, the Kraft arm as a tree of driven
// joints, and randomly generated descriptions (random size, convention, geometry, revolute and
// prismatic joints, branches, coupled joints, rotors and physically consistent inertias).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iomanip>
#include <random>
#include <sstream>
#include <string>

#include "dynamics/newton_euler.hpp"
#include "dynamics_support.hpp"
#include "newton_euler.hpp"
#include "sym/evaluate.hpp"
#include "sym/substitute.hpp"

namespace dyncc::test {
namespace {

constexpr double kTolerance = 1e-9;  // relative
constexpr int kSamples = 25;

struct Worst {
  double tau = 0, H = 0, g = 0, coriolis = 0, regressor = 0;
  [[nodiscard]] double largest() const { return std::max({tau, H, g, coriolis, regressor}); }
};

// Checks, at random states, for the given parameter values:
//   H qdd + C qd + tau_g == RNEA(q, qd, qdd)
//   H e_k == RNEA(q, 0, e_k) - RNEA(q, 0, 0) (every column),  tau_g == RNEA(q, 0, 0)
//   C(q, qd) qd == RNEA(q, qd, 0) - RNEA(q, 0, 0)
//   Y(q, qd, v, a) p - friction == H a + C(q, qd) v + tau_g, the Slotine-Li form with v != qd,
//     where C(q, qd) v comes from RNEA by polarisation: the Christoffel symbols c_ijk are
//     symmetric in j, k, so C(q, qd) v = (Q(qd + v) - Q(qd) - Q(v)) / 2 with Q(x) = C(q, x) x.
Worst compare_with_rnea(const pipeline::Derivation& d, const std::map<std::string, double>& parameters,
                        std::uint64_t seed, const std::string& label) {
  const ne::Chain chain = ne::from_description(d.robot, parameters);
  const Eigen::VectorXd standard = d.numeric->standard_values(parameters);
  const auto n = static_cast<Eigen::Index>(d.model.q.size());
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  std::mt19937_64 rng(seed);
  Worst w;
  for (int k = 0; k < kSamples; ++k) {
    const dyn::State s = random_state(n, rng);
    const dyn::Evaluation e = d.numeric->evaluate(s, standard);

    const Eigen::VectorXd ours = e.H * s.a + e.C * s.qd + e.g;
    const Eigen::VectorXd theirs = ne::rnea(chain, s.q, s.qd, s.a);
    const double scale = std::max({max_abs(e.H * s.a), max_abs(e.C * s.qd), max_abs(e.g), max_abs(theirs)});
    w.tau = std::max(w.tau, relative_difference(ours, theirs, scale));

    const Eigen::VectorXd g = ne::rnea(chain, s.q, zero, zero);
    w.H = std::max(w.H, relative_difference(e.H, ne::mass_matrix(chain, s.q), max_abs(e.H)));
    w.g = std::max(w.g, relative_difference(e.g, g, std::max(max_abs(g), 1e-6 * max_abs(e.H))));

    auto quadratic = [&](const Eigen::VectorXd& x) { return Eigen::VectorXd(ne::rnea(chain, s.q, x, zero) - g); };
    const Eigen::VectorXd cqd = quadratic(s.qd);
    w.coriolis =
        std::max(w.coriolis, relative_difference(e.C * s.qd, cqd, std::max(max_abs(cqd), 1e-6 * max_abs(e.H))));

    const Eigen::VectorXd cv = 0.5 * (quadratic(s.qd + s.v) - quadratic(s.qd) - quadratic(s.v));
    const Eigen::VectorXd slotine_li = ne::mass_matrix(chain, s.q) * s.a + cv + g;
    const Eigen::VectorXd by_y = e.Y * standard - e.friction;
    w.regressor =
        std::max(w.regressor, relative_difference(by_y, slotine_li, std::max(max_abs(slotine_li), max_abs(e.H))));
  }
  EXPECT_LT(w.tau, kTolerance) << label << ": H qdd + C qd + g differs from RNEA";
  EXPECT_LT(w.H, kTolerance) << label << ": H differs from the RNEA columns";
  EXPECT_LT(w.g, kTolerance) << label << ": tau_g differs from RNEA(q, 0, 0)";
  // C qd is compared with a DIFFERENCE of two RNEA calls dominated by gravity, so the reference
  // itself loses ~1-2 digits to cancellation; the full torque above is held to kTolerance.
  EXPECT_LT(w.coriolis, 10 * kTolerance) << label << ": C qd differs from RNEA(q, qd, 0) - RNEA(q, 0, 0)";
  EXPECT_LT(w.regressor, kTolerance) << label << ": Y p differs from H a + C(q, qd) v + g";
  return w;
}

// Random parameter values around the nominal ones (the identities hold for any values, physical
// or not): each value scaled by a factor in [0.5, 1.5] plus a small offset.
std::map<std::string, double> perturbed(const robot::RobotDescription& robot, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> factor(0.5, 1.5), offset(-0.01, 0.01);
  std::map<std::string, double> out;
  for (const auto& [name, value] : robot.nominal_values()) out[name] = value * factor(rng) + offset(rng);
  return out;
}

void check_shipped(const std::string& file) {
  const auto d = derive_file(robots_dir() / file);
  ASSERT_TRUE(d);
  const Worst nominal = compare_with_rnea(*d, d->robot.nominal_values(), 11, file + " (nominal)");
  const Worst random = compare_with_rnea(*d, perturbed(d->robot, 12), 13, file + " (random parameters)");
  ::testing::Test::RecordProperty("largest_relative_error", scientific(std::max(nominal.largest(), random.largest())));
}

TEST(DynamicsNewtonEuler, Puma560StandardDhMatchesRecursiveNewtonEuler) { check_shipped("puma560.yaml"); }

TEST(DynamicsNewtonEuler, PandaModifiedDhMatchesRecursiveNewtonEuler) { check_shipped("panda.yaml"); }

TEST(DynamicsNewtonEuler, PlanarArmMatchesRecursiveNewtonEuler) { check_shipped("planar_2link.yaml"); }

// The Kraft arm is derived as a tree whose joints are driven by the coordinates (the forearm at
// q3 - q2, the coupler at q2 - q3); the loop closes identically, so no constraint force does
// work and the tree's RNEA with the affine joint map gives the same generalised forces.
TEST(DynamicsNewtonEuler, KraftAsTreeOfDrivenJointsMatchesRecursiveNewtonEuler) { check_shipped("kraft.yaml"); }

// ---- random descriptions

std::string number(double x, int digits = 17) {
  std::ostringstream s;
  s << std::setprecision(digits) << x;
  return s.str();
}

std::string decimal(std::mt19937_64& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  std::ostringstream s;
  s << std::fixed << std::setprecision(3) << u(rng);
  return s.str();
}

template <typename T>
const T& pick(std::mt19937_64& rng, const std::vector<T>& options) {
  return options[std::uniform_int_distribution<std::size_t>(0, options.size() - 1)(rng)];
}

// A random tree of n links with coordinate k driving link k (sometimes coupled to an earlier
// coordinate), every inertial entry a named parameter with a physically consistent nominal value.
// Twists alpha and constant angles (joint offsets, the theta of prismatic links) are multiples of
// pi/2, or with `arbitrary_angles` also pi/3, -pi/4, 0.3 and -1.1 rad.
std::string random_description(std::mt19937_64& rng, int index, bool arbitrary_angles) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int n = std::uniform_int_distribution<int>(2, 7)(rng);
  const bool modified = u(rng) < 0.5;
  const std::vector<std::string> angles =
      arbitrary_angles ? std::vector<std::string>{"0", "pi/2", "-pi/2", "pi", "pi/3", "-pi/4", "0.3", "-1.1"}
                       : std::vector<std::string>{"0", "pi/2", "-pi/2", "pi"};
  std::ostringstream y;
  std::ostringstream params;
  y << "name: random_" << index << "\n"
    << "convention: " << (modified ? "modified" : "standard") << "\n"
    << "gravity: [" << decimal(rng, -3, 3) << ", " << decimal(rng, -3, 3) << ", " << decimal(rng, -10, -8) << "]\n"
    << "coordinates: [";
  for (int k = 1; k <= n; ++k) y << (k > 1 ? ", " : "") << "q" << k;
  y << "]\nlinks:\n";
  for (int i = 1; i <= n; ++i) {
    std::string parent = "base";
    if (i > 1) {
      const int p = u(rng) < 0.75 ? i - 1 : std::uniform_int_distribution<int>(0, i - 1)(rng);
      if (p > 0) parent = std::string("link").append(std::to_string(p));
    }
    const bool prismatic = u(rng) < 0.3;
    std::string variable =
        std::string("q").append(std::to_string(i));  // (not "q" + ...: GCC 12 -Wrestrict false positive)
    if (i > 1 && u(rng) < 0.2)
      variable.append(u(rng) < 0.5 ? " + q" : " - q")
          .append(std::to_string(std::uniform_int_distribution<int>(1, i - 1)(rng)));
    std::string theta = pick(rng, angles);
    std::string d = decimal(rng, -0.4, 0.4);
    if (prismatic) {
      d = variable + " + " + decimal(rng, 0.0, 0.3);
    } else {
      theta = variable + (u(rng) < 0.5 ? std::string() : " + " + pick(rng, angles));
    }
    y << "  - name: link" << i << "\n    parent: " << parent
      << "\n    joint: " << (prismatic ? "prismatic" : "revolute") << "\n"
      << "    a: " << (u(rng) < 0.2 ? std::string("0") : decimal(rng, -0.5, 0.5))
      << "\n    alpha: " << pick(rng, angles) << "\n"
      << "    d: " << d << "\n    theta: " << theta << "\n";
    const std::string s = std::to_string(i);
    y << "    mass: m" << s << "\n    com: [x" << s << ", y" << s << ", z" << s << "]\n"
      << "    inertia: {xx: i" << s << "xx, yy: i" << s << "yy, zz: i" << s << "zz, xy: i" << s << "xy, xz: i" << s
      << "xz, yz: i" << s << "yz}\n";
    // A solid box of random size, turned by a random rotation: consistent by construction.
    const double m = 0.2 + 4.8 * u(rng);
    const double bx = 0.02 + 0.4 * u(rng), by = 0.02 + 0.4 * u(rng), bz = 0.02 + 0.4 * u(rng);
    const Eigen::Vector3d principal(m * (by * by + bz * bz) / 12, m * (bx * bx + bz * bz) / 12,
                                    m * (bx * bx + by * by) / 12);
    const Eigen::Matrix3d R = Eigen::Quaterniond(Eigen::Vector4d::Random().normalized()).toRotationMatrix();
    const Eigen::Matrix3d I = R * principal.asDiagonal() * R.transpose();
    params << "  m" << s << ": " << number(m) << "\n";
    for (const char* axis : {"x", "y", "z"}) params << "  " << axis << s << ": " << number(0.4 * u(rng) - 0.2) << "\n";
    params << "  i" << s << "xx: " << number(I(0, 0)) << "\n  i" << s << "yy: " << number(I(1, 1)) << "\n  i" << s
           << "zz: " << number(I(2, 2)) << "\n  i" << s << "xy: " << number(I(0, 1)) << "\n  i" << s
           << "xz: " << number(I(0, 2)) << "\n  i" << s << "yz: " << number(I(1, 2)) << "\n";
  }
  std::ostringstream rotors;
  for (int k = 1; k <= n; ++k) {
    if (u(rng) < 0.4) {
      rotors << "  q" << k << ": {inertia: jm" << k << ", gear_ratio: " << decimal(rng, 5, 120) << "}\n";
      params << "  jm" << k << ": " << number(1e-5 + 1e-4 * u(rng)) << "\n";
    }
  }
  if (!rotors.str().empty()) y << "rotor:\n" << rotors.str();
  y << "parameters:\n" << params.str();
  return y.str();
}

void check_random_descriptions(std::uint64_t seed, bool arbitrary_angles) {
  std::mt19937_64 rng(seed);
  std::srand(static_cast<unsigned>(seed));  // Eigen's Random() (the inertia rotations)
  constexpr int kRobots = 5;
  double largest = 0.0;
  for (int r = 0; r < kRobots; ++r) {
    const std::string text = random_description(rng, r, arbitrary_angles);
    const std::string label = std::string("random description ").append(std::to_string(r));
    const auto d = derive_text(text, label);
    ASSERT_TRUE(d);
    const Worst w = compare_with_rnea(*d, d->robot.nominal_values(), seed + static_cast<std::uint64_t>(r),
                                      std::string(label).append(":\n").append(text));
    largest = std::max(largest, w.largest());
    if (::testing::Test::HasFailure()) return;  // one failing description is enough to read
  }
  ::testing::Test::RecordProperty("largest_relative_error", scientific(largest));
}

TEST(DynamicsNewtonEuler, RandomDescriptionsWithRightAngleTwistsMatchRecursiveNewtonEuler) {
  check_random_descriptions(20240611, false);
}

// Twists such as pi/3 and joint offsets such as q2 + 0.3 are valid descriptions (docs/robot-description.md).
TEST(DynamicsNewtonEuler, RandomDescriptionsWithArbitraryTwistsAndOffsetsMatchRecursiveNewtonEuler) {
  check_random_descriptions(777, true);
}

// The generator's SYMBOLIC Newton-Euler torque and composite-rigid-body mass matrix (which the
// code generator emits when cheaper) on the same random trees: prismatic joints, branches,
// coupled joints and rotors, both conventions. Compiled and evaluated against the Lagrangian
// model at random states, with and without named intermediates (bindings).
void check_symbolic_forms(std::uint64_t seed, bool arbitrary_angles) {
  std::mt19937_64 rng(seed);
  std::srand(static_cast<unsigned>(seed));
  for (int r = 0; r < 5; ++r) {
    const std::string text = random_description(rng, r, arbitrary_angles);
    const auto d = derive_text(text, "random description");
    ASSERT_TRUE(d);
    const dyn::DynamicModel& m = d->model;
    const std::size_t n = m.q.size();
    for (const bool bound : {false, true}) {
      sym::Bindings lets;
      sym::Bindings* bindings = bound ? &lets : nullptr;
      const auto tau = dyn::newton_euler_torque(d->robot, m, dyn::NewtonEulerInputs{m.qd, m.a, true, {}, bindings});
      const auto H = dyn::composite_rigid_body_mass_matrix(d->robot, m, {}, bindings);
      ASSERT_TRUE(tau && H) << text;
      // Bound symbols become outputs computed first, then inputs of the rest: substitute back.
      std::vector<sym::Expr> outputs = *tau;
      for (const auto& row : *H) outputs.insert(outputs.end(), row.begin(), row.end());
      sym::Substitution definitions;
      for (const auto& [symbol, definition] : lets.list())
        definitions[symbol] = sym::substitute(definition, definitions);
      for (sym::Expr& e : outputs) e = sym::substitute(e, definitions);
      std::vector<sym::Expr> inputs = m.q;
      inputs.insert(inputs.end(), m.qd.begin(), m.qd.end());
      inputs.insert(inputs.end(), m.a.begin(), m.a.end());
      const std::vector<sym::Expr> params = m.params.symbols();
      inputs.insert(inputs.end(), params.begin(), params.end());
      const sym::CompiledFunction f(outputs, inputs);
      const Eigen::VectorXd standard = d->numeric->nominal_standard_values();
      for (std::uint64_t k = 0; k < 5; ++k) {
        dyn::State s = dyn::random_state(n, seed * 31 + k);
        s.v = s.qd;
        const dyn::Evaluation ev = d->numeric->evaluate(s, standard, false);
        std::vector<double> in;
        for (const Eigen::VectorXd* v : {&s.q, &s.qd, &s.a}) in.insert(in.end(), v->data(), v->data() + v->size());
        in.insert(in.end(), standard.data(), standard.data() + standard.size());
        const std::vector<double> out = f(in);
        const Eigen::VectorXd rigid = ev.tau - ev.friction;
        for (std::size_t i = 0; i < n; ++i) {
          const auto row = static_cast<Eigen::Index>(i);
          EXPECT_NEAR(out[i], rigid[row], 1e-9 * (1 + rigid.norm()))
              << "tau " << i << (bound ? " bound\n" : "\n") << text;
          for (std::size_t j = 0; j < n; ++j) {
            EXPECT_NEAR(out[n + i * n + j], ev.H(row, static_cast<Eigen::Index>(j)), 1e-9 * (1 + ev.H.norm()))
                << "H " << i << "," << j << "\n"
                << text;
          }
        }
        if (::testing::Test::HasFailure()) return;
      }
    }
  }
}

TEST(DynamicsNewtonEuler, SymbolicNewtonEulerAndCompositeRigidBodyMatchOnRandomTrees) {
  check_symbolic_forms(4242, false);
  check_symbolic_forms(99, true);
}

}  // namespace
}  // namespace dyncc::test
