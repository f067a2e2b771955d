// The excitation logs of sim/excite.cpp, against physics: without effects the rigid plant's logged
// torque IS the description's inverse dynamics along the logged motion; each hidden effect changes
// the logged torque (or the measured positions) by what the effect physically is; the two plants
// agree. Noise-free, unquantised runs, so the motion's derivatives come from plain differences.
#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "excite.hpp"
#include "plant.hpp"

namespace dyncc::sim {

// The plant's name in test output (GoogleTest finds it by argument-dependent lookup).
void PrintTo(PlantKind plant, std::ostream* out) { *out << (plant == PlantKind::mujoco ? "mujoco" : "dyncc"); }

namespace {

namespace gen = dyncc::generated::kraft_right;
constexpr const char* kMjcf = DYNCC_KRAFT_MJCF;
constexpr double kGravity = 9.81;

ExciteSettings clean(PlantKind plant, double duration = 20.0) {
  ExciteSettings s;
  s.plant = plant;
  s.mjcf = kMjcf;
  s.rate = 200;
  s.duration = duration;
  s.quantum = 0;
  s.noise = 0;
  return s;
}

// The log along its own motion, one entry per inner control period i: the motion over the period
// (the torque is held over it) by differences of the positions `of` (the logged ones, or the true
// link angles): q and qd at its middle, qdd as the difference of the neighbouring periods' mean
// velocities. That difference weighs the accelerations of periods i-1, i, i+1 by 1/4, 1/2, 1/4,
// so the logged torque is compared with the same weighting of its own samples.
struct Along {
  std::vector<Joints> q, qd, qdd, tau, model;  // model: the description's inverse dynamics
  std::vector<const ExciteSample*> sample;
};

template <typename Of>
Along along(const ExciteRun& run, Of of, double from = 3.0) {
  Along a;
  const double h = 1.0 / run.settings.rate;
  const auto& x = run.samples;
  Parameters nominal{};
  for (int b = 0; b < kParameters; ++b) nominal[b] = Kraft::nominal_parameters[b];
  for (std::size_t i = 1; i + 2 < x.size(); ++i) {
    if (x[i].t < from) continue;  // after the fade-in and the start's transients
    Joints q{}, qd{}, qdd{}, tau{};
    for (int k = 0; k < kDof; ++k) {
      const double p0 = of(x[i - 1])[k], p1 = of(x[i])[k], p2 = of(x[i + 1])[k], p3 = of(x[i + 2])[k];
      q[k] = 0.5 * (p1 + p2);
      qd[k] = (p2 - p1) / h;
      qdd[k] = ((p3 - p2) - (p1 - p0)) / (2 * h * h);
      tau[k] = 0.25 * x[i - 1].tau[k] + 0.5 * x[i].tau[k] + 0.25 * x[i + 1].tau[k];
    }
    Joints model{};
    gen::inverse_dynamics<double>(q.data(), qd.data(), qdd.data(), nominal.data(), model.data());
    a.q.push_back(q);
    a.qd.push_back(qd);
    a.qdd.push_back(qdd);
    a.tau.push_back(tau);
    a.model.push_back(model);
    a.sample.push_back(&x[i]);
  }
  return a;
}

Along along_measured(const ExciteRun& run) {
  return along(run, [](const ExciteSample& s) -> const Joints& { return s.measured; });
}

// Least-squares slope of y on x over the entries where `use` holds.
template <typename X, typename Y, typename Use>
double slope(const Along& a, X x, Y y, Use use) {
  double xy = 0, xx = 0;
  for (std::size_t i = 0; i < a.q.size(); ++i) {
    if (!use(i)) continue;
    xy += x(i) * y(i);
    xx += x(i) * x(i);
  }
  return xy / xx;
}

double rms_of(const std::vector<double>& v) {
  double s = 0;
  for (const double x : v) s += x * x;
  return std::sqrt(s / static_cast<double>(v.size()));
}

// Per joint: RMS of (logged - model) over entries moving faster than `speed` on that joint
// (the plant's Coulomb friction turns over within 0.01 rad/s, the model's sign at once), as a
// share of the logged torque's RMS.
Joints relative_gap(const Along& a, double speed = 0.05) {
  Joints out{};
  for (int k = 0; k < kDof; ++k) {
    std::vector<double> gap, torque;
    for (std::size_t i = 0; i < a.q.size(); ++i) {
      torque.push_back(a.tau[i][k]);
      if (std::abs(a.qd[i][k]) > speed) gap.push_back(a.tau[i][k] - a.model[i][k]);
    }
    out[k] = rms_of(gap) / rms_of(torque);
  }
  return out;
}

class ExciteOnBothPlants : public ::testing::TestWithParam<PlantKind> {};

INSTANTIATE_TEST_SUITE_P(Plants, ExciteOnBothPlants, ::testing::Values(PlantKind::dyncc, PlantKind::mujoco),
                         [](const auto& info) { return info.param == PlantKind::mujoco ? "mujoco" : "dyncc"; });

// Without effects the plant is the description's arm: the commanded torque is the model's inverse
// dynamics along the motion, and the controller tracks the excitation closely.
TEST_P(ExciteOnBothPlants, WithoutEffectsTheLoggedTorqueIsTheModelsInverseDynamics) {
  const ExciteRun run = excite(clean(GetParam()));
  const Along a = along_measured(run);
  // MuJoCo's soft loop constraints and implicit damping differ from RK4 on the reduced model by a
  // little more than the rigid plant's integration error.
  const double tolerance = GetParam() == PlantKind::mujoco ? 5e-3 : 1e-3;
  const Joints gap = relative_gap(a);
  for (int k = 0; k < kDof; ++k) EXPECT_LT(gap[k], tolerance) << "joint " << k + 1;
  double worst = 0;
  for (const ExciteSample& s : run.samples) {
    for (int k = 0; k < kDof; ++k) worst = std::max(worst, std::abs(s.measured[k] - s.desired[k]));
  }
  EXPECT_LT(worst, 5e-3) << "rad: tracking of the Fourier excitation";
}

// The two plants log the same torque for the same excitation. They differ where a joint reverses:
// MuJoCo's dry friction is a constraint that holds the joint for a moment, the rigid plant's a
// regularised sign; everywhere else they agree to a few tenths of a per cent.
TEST(Excite, BothPlantsLogTheSameTorqueWithoutEffects) {
  const ExciteRun rigid = excite(clean(PlantKind::dyncc)), mujoco = excite(clean(PlantKind::mujoco));
  ASSERT_EQ(rigid.samples.size(), mujoco.samples.size());
  const double h = 1.0 / rigid.settings.rate;
  for (int k = 0; k < kDof; ++k) {
    std::vector<double> difference, moving, torque;
    for (std::size_t i = 0; i + 1 < rigid.samples.size(); ++i) {
      const ExciteSample &a = rigid.samples[i], &b = mujoco.samples[i];
      if (a.t < 3.0) continue;
      const double speed = std::abs(rigid.samples[i + 1].measured[k] - a.measured[k]) / h;
      difference.push_back(a.tau[k] - b.tau[k]);
      if (speed > 0.05) moving.push_back(a.tau[k] - b.tau[k]);
      torque.push_back(a.tau[k]);
    }
    EXPECT_LT(rms_of(moving), 0.01 * rms_of(torque)) << "joint " << k + 1;
    EXPECT_LT(rms_of(difference), 0.05 * rms_of(torque)) << "joint " << k + 1;
  }
}

// Extra friction adds exactly its own torque on its own joint: viscous on joint 1, Coulomb on
// joint 2, Stribeck on joint 3, in one run (friction of one joint does not reach the others).
TEST_P(ExciteOnBothPlants, FrictionEffectsAddTheirTorqueOnTheirJoint) {
  ExciteSettings s = clean(GetParam());
  JointEffects& j = s.effects.joints;
  j.viscous[0] = 0.05;
  j.coulomb[1] = 0.1;
  j.stribeck[2] = 0.08;
  j.stribeck_velocity[2] = 0.15;
  const Along a = along_measured(excite(s));
  auto gap = [&a](int k) { return [&a, k](std::size_t i) { return a.tau[i][k] - a.model[i][k]; }; };
  auto moving = [&a](int k, double speed) {
    return [&a, k, speed](std::size_t i) { return std::abs(a.qd[i][k]) > speed; };
  };
  const double fv = slope(
      a, [&a](std::size_t i) { return a.qd[i][0]; }, gap(0), moving(0, 0.05));
  EXPECT_NEAR(fv, 0.05, 0.02 * 0.05);
  const double fc = slope(
      a, [&a](std::size_t i) { return a.qd[i][1] > 0 ? 1.0 : -1.0; }, gap(1), moving(1, 0.05));
  EXPECT_NEAR(fc, 0.1, 0.02 * 0.1);
  const double fs = slope(
      a,
      [&a](std::size_t i) {
        const double v = a.qd[i][2] / 0.15;
        return std::exp(-v * v) * (a.qd[i][2] > 0 ? 1.0 : -1.0);
      },
      gap(2), moving(2, 0.03));
  EXPECT_NEAR(fs, 0.08, 0.05 * 0.08);
}

// Rotor inertia: ia qdd on its joint. Torque gain: the motor gives gain times the command, so
// the command is the needed torque divided by the gain.
TEST_P(ExciteOnBothPlants, RotorInertiaAddsIaQddAndAGainDividesTheCommand) {
  ExciteSettings s = clean(GetParam());
  s.effects.joints.rotor_inertia[0] = 0.05;
  s.effects.torque_gain[1] = 1.1;
  const Along a = along_measured(excite(s));
  auto all = [](std::size_t) { return true; };
  const double ia = slope(
      a, [&a](std::size_t i) { return a.qdd[i][0]; }, [&a](std::size_t i) { return a.tau[i][0] - a.model[i][0]; }, all);
  EXPECT_NEAR(ia, 0.05, 0.02 * 0.05);
  const double ratio = slope(
      a, [&a](std::size_t i) { return a.model[i][1]; }, [&a](std::size_t i) { return a.tau[i][1]; },
      [&a](std::size_t i) { return std::abs(a.qd[i][1]) > 0.05; });
  EXPECT_NEAR(ratio, 1 / 1.1, 0.002 / 1.1);
}

// A payload on the hook: its weight through the hook's lever arms, m g dz/dq (the slow part of
// the excitation, where its inertia is a few per cent of its weight).
TEST_P(ExciteOnBothPlants, PayloadAddsItsWeightTimesTheLeverArm) {
  ExciteSettings s = clean(GetParam());
  s.effects.payload = 0.5;
  s.excitation_scale = 0.5;
  const ExciteRun run = excite(s);
  const Along a = along_measured(run);
  double gz = 0, gg = 0;
  for (std::size_t i = 0; i < a.q.size(); ++i) {
    ASSERT_TRUE(a.sample[i]->payload);
    const auto j = forearm_point_jacobian(a.q[i], kHookInForearm);
    for (int k = 1; k < kDof; ++k) {
      const double lever = kGravity * j[6 + k];  // N m per kg
      gz += lever * (a.tau[i][k] - a.model[i][k]);
      gg += lever * lever;
    }
  }
  EXPECT_NEAR(gz / gg, 0.5, 0.01 * 0.5) << "kg";
}

// The sensors report the arm's angles of `delay` ago plus the offset (an interface effect: the
// same on both plants).
TEST(Excite, SensorDelayAndOffsetAreWhatTheSensorsReport) {
  ExciteSettings s = clean(PlantKind::dyncc);
  s.effects.sensor_delay = 0.013;  // not a whole number of 5 ms periods
  s.effects.position_offset[2] = 0.02;
  const ExciteRun run = excite(s);
  const auto& x = run.samples;
  const double h = 1.0 / s.rate;
  double worst = 0;
  for (std::size_t i = 10; i < x.size(); ++i) {
    // The true angle at t - delay, interpolated between the samples around it (5 ms apart: the
    // interpolation's error is below 1e-5 rad at these accelerations).
    const double at = x[i].t - s.effects.sensor_delay;
    const auto j = static_cast<std::size_t>(std::floor(at / h));
    const double u = (at - x[j].t) / h;
    for (int k = 0; k < kDof; ++k) {
      const double truth = x[j].link[k] + u * (x[j + 1].link[k] - x[j].link[k]);
      worst = std::max(worst, std::abs(x[i].measured[k] - truth - s.effects.position_offset[k]));
    }
  }
  EXPECT_LT(worst, 2e-5);
}

// The hook presses on the table for part of the run, and the torque then differs from the free
// arm's by the contact force through the hook Jacobian, -J^T F: F's vertical part is the plant's
// normal force and its horizontal part no more than the friction cone allows. Compared as means
// over 50 ms windows: MuJoCo's hard contact touches the sliding hook at some integration steps
// only, with larger forces, and what the torque and the diagnosis see is the mean.
TEST_P(ExciteOnBothPlants, ContactPressesOnTheTableWithTheForceTheTorqueShows) {
  ExciteSettings s = clean(GetParam());
  s.effects.contact.present = true;
  s.effects.contact.depth = 0.03;  // deep enough to press for a while in several swings
  const ExciteRun run = excite(s);
  const Along a = along_measured(run);
  constexpr std::size_t kWindow = 10;  // periods (50 ms at 200 Hz)
  std::size_t windows = 0, pressing = 0, close = 0;
  double fz_fn = 0, fn_fn = 0, tangential = 0, normals = 0;
  for (std::size_t w = 0; w + kWindow <= a.q.size(); w += kWindow) {
    ++windows;
    Joints q{}, r{};
    double normal = 0;
    for (std::size_t i = w; i < w + kWindow; ++i) {
      for (int k = 0; k < kDof; ++k) {
        q[k] += a.q[i][k] / kWindow;
        r[k] += (a.model[i][k] - a.tau[i][k]) / kWindow;  // J^T F: the table helps the motors
      }
      normal += a.sample[i]->contact_force / kWindow;
    }
    if (normal < 1.0) continue;  // well above the differences' noise (1 N through 0.5 m levers)
    ++pressing;
    // Solve J^T F = r by Gaussian elimination (J is regular away from the stretched arm).
    const auto j = forearm_point_jacobian(q, kHookInForearm);
    MassMatrix m{};
    for (int row = 0; row < kDof; ++row) {
      for (int c = 0; c < kDof; ++c) m[row * kDof + c] = j[c * 3 + row];
    }
    for (int c = 0; c < kDof; ++c) {
      for (int row = c + 1; row < kDof; ++row) {
        const double f = m[row * kDof + c] / m[c * kDof + c];
        for (int k = c; k < kDof; ++k) m[row * kDof + k] -= f * m[c * kDof + k];
        r[row] -= f * r[c];
      }
    }
    Vec3 force{};
    for (int row = kDof - 1; row >= 0; --row) {
      double v = r[row];
      for (int k = row + 1; k < kDof; ++k) v -= m[row * kDof + k] * force[k];
      force[row] = v / m[row * kDof + row];
    }
    close += std::abs(force[2] - normal) < 0.3 * normal ? 1 : 0;
    fz_fn += force[2] * normal;
    fn_fn += normal * normal;
    tangential += std::hypot(force[0], force[1]);
    normals += normal;
  }
  const double share = static_cast<double>(pressing) / static_cast<double>(windows);
  EXPECT_GT(share, 0.03) << "the hook presses on the table in a few per cent of the run";
  EXPECT_LT(share, 0.3);
  ASSERT_GT(pressing, 10U);
  EXPECT_NEAR(fz_fn / fn_fn, 1.0, 0.05) << "vertical force from the torque / the plant's normal force";
  EXPECT_GE(close, 9 * pressing / 10) << pressing << " windows pressing";
  EXPECT_LT(tangential, 1.05 * s.effects.contact.friction * normals) << "inside the friction cone";
  EXPECT_GT(tangential, 0.5 * s.effects.contact.friction * normals) << "the hook slides on the table";
}

// Backlash: the motor (where the sensor is) and the link are never further apart than half the
// dead band plus the teeth's deflection, and the gap is crossed when the torque reverses.
TEST(Excite, BacklashKeepsMotorAndLinkWithinTheDeadBand) {
  ExciteSettings s = clean(PlantKind::dyncc);
  const double width = 0.02;
  s.effects.joints.transmission[0].width = width;
  const ExciteRun run = excite(s);
  double largest = 0, smallest = 0;
  for (const ExciteSample& x : run.samples) {
    const double gap = x.sensor[0] - x.link[0];
    largest = std::max(largest, gap);
    smallest = std::min(smallest, gap);
    EXPECT_NEAR(x.measured[0], x.sensor[0], 1e-12) << "the sensor is on the motor";
  }
  const double teeth = 6.0 / kBacklashStiffness;  // the largest yaw torque's deflection
  EXPECT_LT(largest, width / 2 + teeth);
  EXPECT_GT(smallest, -width / 2 - teeth);
  EXPECT_GT(largest, 0.9 * width / 2) << "pushed against one side";
  EXPECT_LT(smallest, -0.9 * width / 2) << "and against the other";
}

// A table a few millimetres above how low the Fourier run's hook goes is touched in three of the
// run's 10 s periods at least, however the joints' waves fall (their frequencies differ, so the
// hook's path does not repeat). Above its single lowest point instead, the hook touched the table
// in one burst on these bench runs (seeds 647 case 12, 557 case 36, 509 case 12): nothing for a
// test on held-out data to learn a contact from.
TEST(Excite, AFourierRunsTableIsTouchedInThreePeriodsAtLeast) {
  for (const unsigned seed : {647012U, 557036U, 509012U}) {
    SCOPED_TRACE(seed);
    ExciteSettings s = clean(PlantKind::dyncc, 60.0);
    s.seed = seed;
    s.effects.contact.present = true;
    s.effects.contact.depth = 0.003;
    const ExciteRun run = excite(s);
    std::set<int> touched;  // the 10 s periods with a touch
    for (const ExciteSample& x : run.samples) {
      if (x.contact) touched.insert(static_cast<int>(x.t / 10.0));
    }
    EXPECT_GE(touched.size(), 3U);
  }
}

// A series spring: the link lags the motor by what the spring passes over its stiffness, the
// commanded torque less what accelerates the motor's own inertia (the description's jm2).
TEST(Excite, JointElasticityDeflectsByTheTransmittedTorqueOverTheStiffness) {
  ExciteSettings s = clean(PlantKind::dyncc);
  const double k = 60.0;
  s.effects.joints.transmission[1].stiffness = k;
  const ExciteRun run = excite(s);
  const Along motor = along(run, [](const ExciteSample& x) -> const Joints& { return x.sensor; });
  const Along link = along(run, [](const ExciteSample& x) -> const Joints& { return x.link; });
  const double jm = rotor_inertias()[1];
  const double stiffness = slope(
      motor, [&](std::size_t i) { return motor.q[i][1] - link.q[i][1]; },
      [&](std::size_t i) { return motor.tau[i][1] - jm * motor.qdd[i][1]; }, [](std::size_t) { return true; });
  // The spring's damping (10 % of critical) passes a little torque too, in quadrature with the
  // deflection over the excitation's slow periods: it hardly biases the fit.
  EXPECT_NEAR(stiffness, k, 0.02 * k);
}

TEST(Excite, TheMujocoPlantRefusesBacklashAndElasticity) {
  for (const bool backlash : {true, false}) {
    ExciteSettings s = clean(PlantKind::mujoco, 1.0);
    if (backlash) {
      s.effects.joints.transmission[0].width = 0.01;
    } else {
      s.effects.joints.transmission[0].stiffness = 50;
    }
    try {
      excite(s);
      ADD_FAILURE() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("rigid plant"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace dyncc::sim
