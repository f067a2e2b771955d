// The Slotine-Li runtime (runtime/include/dyncc/runtime/) in closed loop: on a hand-written
// pendulum (the textbook model, not generated) and on the generated Kraft arm. Properties, not
// snapshots: the Lyapunov function of the paper's eq. (5) never increases, tracking converges
// with exact parameters, adaptation recovers changed parameters under persistent excitation,
// the safeguards do what they say, and the estimator differentiates quantised positions.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "dyncc/runtime/position_estimator.hpp"
#include "dyncc/runtime/slotine_li_controller.hpp"
#include "kraft/model.hpp"
#include "runtime_test_models.hpp"

namespace dyncc::test {
namespace {

using runtime::Feedback;
using runtime::SlotineLiController;
using Kraft = dyncc::generated::kraft_right::Model;

// The Kraft model with the functions the plant needs beside the runtime's.
struct KraftPlantModel : Kraft {
  template <typename S>
  static void inverse_dynamics(const S* q, const S* qd, const S* qdd, const S* p, S* tau) {
    dyncc::generated::kraft_right::inverse_dynamics<S>(q, qd, qdd, p, tau);
  }
};

template <int N>
struct Desired {
  std::array<double, N> q{}, qd{}, qdd{};
};

// A sum of two sines per joint (persistently exciting for the small models here).
template <int N>
Desired<N> sines(double t, double scale = 1.0) {
  Desired<N> d;
  for (int k = 0; k < N; ++k) {
    const double a1 = 0.5 * scale, w1 = 1.1 + 0.4 * k, a2 = 0.25 * scale, w2 = 2.9 + 0.7 * k;
    d.q[k] = a1 * std::sin(w1 * t) + a2 * std::sin(w2 * t + k);
    d.qd[k] = a1 * w1 * std::cos(w1 * t) + a2 * w2 * std::cos(w2 * t + k);
    d.qdd[k] = -a1 * w1 * w1 * std::sin(w1 * t) - a2 * w2 * w2 * std::sin(w2 * t + k);
  }
  return d;
}

// V = 1/2 eps^T H(q) eps + 1/2 p~^T Gamma p~ (paper eq. 5), Gamma = diag(1 / gamma_inverse).
template <typename Model, typename C>
double lyapunov(const C& controller, const std::array<double, Model::parameters>& truth,
                const std::array<double, Model::dof>& q, const std::array<double, Model::dof>& eps) {
  constexpr int n = Model::dof;
  std::array<double, n * n> h{};
  Model::template mass_matrix<double>(q.data(), truth.data(), h.data());
  double v = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) v += 0.5 * eps[i] * h[i * n + j] * eps[j];
  }
  for (int b = 0; b < Model::parameters; ++b) {
    const double error = controller.estimate()[b] - truth[b];
    v += 0.5 * error * error / controller.settings().gamma_inverse[b];
  }
  return v;
}

// Closed loop in continuous time (controller and adaptation law inside the RK4 right-hand side),
// so dV/dt = -eps^T K_D eps holds up to integration error. Returns the largest increase of V
// over one step relative to V(0), and V at the end relative to V(0).
template <typename Model>
std::pair<double, double> lyapunov_run(typename SlotineLiController<Model, double>::Settings settings,
                                       std::array<double, Model::parameters> truth,
                                       std::array<double, Model::parameters> estimate,
                                       std::array<double, Model::dof> q0, double duration, double dt) {
  constexpr int n = Model::dof, r = Model::parameters;
  using Joints = std::array<double, n>;
  using Params = std::array<double, r>;
  struct State {
    Joints q, qd;
    Params p;
  };
  Plant<Model> plant;
  plant.p = truth;
  SlotineLiController<Model, double> controller(settings, estimate);
  auto derivative = [&](const State& x, double t) {
    controller.set_estimate(x.p);
    const Desired<n> d = sines<n>(t);
    const auto step = controller.evaluate(x.q, x.qd, d.q, d.qd, d.qdd);
    State dx{x.qd, plant.acceleration(x.q, x.qd, step.tau), {}};
    for (int b = 0; b < r; ++b) dx.p[b] = -settings.gamma_inverse[b] * step.ytE[b];
    return dx;
  };
  auto axpy = [](const State& x, const State& dx, double s) {
    State y = x;
    for (int k = 0; k < n; ++k) {
      y.q[k] += s * dx.q[k];
      y.qd[k] += s * dx.qd[k];
    }
    for (int b = 0; b < r; ++b) y.p[b] += s * dx.p[b];
    return y;
  };
  auto value = [&](const State& x, double t) {
    controller.set_estimate(x.p);
    const Desired<n> d = sines<n>(t);
    return lyapunov<Model>(controller, truth, x.q, controller.evaluate(x.q, x.qd, d.q, d.qd, d.qdd).eps);
  };
  State x{q0, Joints{}, estimate};
  const double v0 = value(x, 0.0);
  double v = v0, worst_increase = 0.0;
  for (double t = 0; t < duration; t += dt) {
    const State k1 = derivative(x, t);
    const State k2 = derivative(axpy(x, k1, dt / 2), t + dt / 2);
    const State k3 = derivative(axpy(x, k2, dt / 2), t + dt / 2);
    const State k4 = derivative(axpy(x, k3, dt), t + dt);
    x = axpy(axpy(axpy(axpy(x, k1, dt / 6), k2, dt / 3), k3, dt / 3), k4, dt / 6);
    const double next = value(x, t + dt);
    worst_increase = std::max(worst_increase, (next - v) / v0);
    v = next;
  }
  return {worst_increase, v / v0};
}

SlotineLiController<Pendulum, double>::Settings pendulum_settings() {
  SlotineLiController<Pendulum, double>::Settings s;
  s.lambda = 4.0;
  s.feedback = Feedback::constant_gain;
  s.k_d = {3.0};
  s.gamma_inverse = {0.5, 2.0, 0.5};
  s.period = 1e-3;
  return s;
}

TEST(SlotineLiPendulum, LyapunovFunctionNeverIncreasesWithConstantGain) {
  const auto [increase, final_ratio] =
      lyapunov_run<Pendulum>(pendulum_settings(), {0.5, 2.0, 0.1}, {0.3, 1.0, 0.0}, {0.4}, 10.0, 1e-3);
  EXPECT_LT(increase, 1e-8);
  EXPECT_LT(final_ratio, 0.5) << "V must also decrease overall";
}

TEST(SlotineLiPendulum, LyapunovFunctionNeverIncreasesWithLambdaH) {
  auto s = pendulum_settings();
  s.feedback = Feedback::lambda_H;  // K_D = lambda H^, folded into the regressor (ERRATA 2)
  const auto [increase, final_ratio] = lyapunov_run<Pendulum>(s, {0.5, 2.0, 0.1}, {0.3, 1.0, 0.0}, {0.4}, 10.0, 1e-3);
  EXPECT_LT(increase, 1e-8);
  EXPECT_LT(final_ratio, 0.5);
}

TEST(SlotineLiKraft, LyapunovFunctionNeverIncreasesOnTheGeneratedModel) {
  SlotineLiController<KraftPlantModel, double>::Settings s;
  s.lambda = 3.14159265358979;
  for (auto& g : s.gamma_inverse) g = 0.05;
  std::array<double, 19> truth{}, estimate{};
  for (int b = 0; b < 19; ++b) {
    truth[b] = Kraft::nominal_parameters[b];
    estimate[b] = Kraft::initial_estimate[b];
  }
  const auto [increase, final_ratio] = lyapunov_run<KraftPlantModel>(s, truth, estimate, {0.3, -0.2, 0.4}, 5.0, 5e-4);
  EXPECT_LT(increase, 1e-6);
  EXPECT_LT(final_ratio, 1.0);
}

// The sampled controller as it runs on an arm: fixed control period, zero-order hold, the
// plant integrated finer. Returns the RMS tracking error over the last `window` seconds.
template <typename Model>
double sampled_run(SlotineLiController<Model, double>& controller, Plant<Model>& plant, double duration, double window,
                   int substeps) {
  constexpr int n = Model::dof;
  const double period = controller.settings().period;
  double sum = 0;
  int count = 0;
  for (double t = 0; t < duration; t += period) {
    const Desired<n> d = sines<n>(t);
    const auto step = controller.step(plant.q, plant.qd, d.q, d.qd, d.qdd);
    if (t > duration - window) {
      for (int k = 0; k < n; ++k) sum += (plant.q[k] - d.q[k]) * (plant.q[k] - d.q[k]);
      ++count;
    }
    for (int i = 0; i < substeps; ++i) plant.step(step.tau, period / substeps);
  }
  return std::sqrt(sum / std::max(count, 1));
}

TEST(SlotineLiKraft, TracksWithExactParametersAndAdaptationOff) {
  SlotineLiController<KraftPlantModel, double>::Settings s;
  s.period = 1.0 / 500;
  std::array<double, 19> truth{};
  for (int b = 0; b < 19; ++b) truth[b] = Kraft::nominal_parameters[b];
  SlotineLiController<KraftPlantModel, double> controller(s, truth);
  controller.set_adaptation(false);
  Plant<KraftPlantModel> plant;
  plant.p = truth;
  plant.q = {0.2, -0.1, 0.3};
  const double rms = sampled_run(controller, plant, 10.0, 2.0, 4);
  EXPECT_LT(rms, 2e-3);
  for (int b = 0; b < 19; ++b) EXPECT_EQ(controller.estimate()[b], truth[b]);
}

TEST(SlotineLiPendulum, AdaptationRecoversTheParametersUnderPersistentExcitation) {
  auto s = pendulum_settings();
  s.gamma_inverse = {2.0, 10.0, 2.0};
  SlotineLiController<Pendulum, double> controller(s, {0.3, 1.0, 0.0});
  Plant<Pendulum> plant;
  plant.p = {0.5, 2.0, 0.1};
  sampled_run(controller, plant, 120.0, 1.0, 2);
  EXPECT_NEAR(controller.estimate()[0], 0.5, 0.025);
  EXPECT_NEAR(controller.estimate()[1], 2.0, 0.1);
  EXPECT_NEAR(controller.estimate()[2], 0.1, 0.02);
}

// A payload-like change on the Kraft arm (the forearm's mass moments grow): adaptation moves
// the estimate towards the truth and tracks better than the fixed (wrong) model.
TEST(SlotineLiKraft, AdaptationBeatsTheFixedModelAfterAParameterChange) {
  SlotineLiController<KraftPlantModel, double>::Settings s;
  s.period = 1.0 / 200;
  for (auto& g : s.gamma_inverse) g = 0.2;
  std::array<double, 19> nominal{}, truth{};
  for (int b = 0; b < 19; ++b) nominal[b] = truth[b] = Kraft::nominal_parameters[b];
  truth[4] *= 1.5;   // MX3R: first moment of the forearm
  truth[11] *= 1.3;  // ZZ3R
  double fixed_rms = 0, adaptive_rms = 0;
  std::array<double, 19> adapted{};
  for (const bool adapt : {false, true}) {
    SlotineLiController<KraftPlantModel, double> controller(s, nominal);
    controller.set_adaptation(adapt);
    Plant<KraftPlantModel> plant;
    plant.p = truth;
    const double rms = sampled_run(controller, plant, 60.0, 10.0, 4);
    (adapt ? adaptive_rms : fixed_rms) = rms;
    if (adapt) adapted = controller.estimate();
  }
  EXPECT_LT(adaptive_rms, 0.5 * fixed_rms) << "fixed " << fixed_rms << ", adaptive " << adaptive_rms;
  EXPECT_LT(std::abs(adapted[4] - truth[4]), 0.5 * std::abs(nominal[4] - truth[4]))
      << "MX3R " << nominal[4] << " -> " << adapted[4] << " (truth " << truth[4] << ")";
}

// The Cholesky solve the plants use: M x = b for random symmetric positive definite M = A A^T + I,
// and a refusal (x untouched) for an indefinite M.
TEST(SmallMatrix, SolvesPositiveDefiniteSystems) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    runtime::Matrix<double, 4> a{}, m{};
    runtime::Vector<double, 4> b{}, x{};
    for (auto& v : a) v = u(random);
    for (auto& v : b) v = u(random);
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        for (int k = 0; k < 4; ++k) m[i * 4 + j] += a[i * 4 + k] * a[j * 4 + k];
      }
      m[i * 4 + i] += 1.0;
    }
    ASSERT_TRUE((runtime::solve_positive_definite<double, 4>(m, b, x)));
    const auto mx = runtime::multiply<double, 4>(m, x);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(mx[i], b[i], 1e-12);
  }
  const runtime::Matrix<double, 2> indefinite{1.0, 2.0, 2.0, 1.0};
  runtime::Vector<double, 2> x{5.0, 5.0};
  EXPECT_FALSE((runtime::solve_positive_definite<double, 2>(indefinite, {1.0, 1.0}, x)));
  EXPECT_EQ(x[0], 5.0);
}

TEST(SlotineLiSafeguards, SwitchDeadZoneBoxAndPositiveDefiniteness) {
  const std::array<double, 1> q{0.3}, qd{0.2}, zero{};
  {  // adaptation off: the estimate does not move
    SlotineLiController<Pendulum, double> c(pendulum_settings(), {0.3, 1.0, 0.0});
    c.set_adaptation(false);
    const auto step = c.step(q, qd, zero, zero, zero);
    EXPECT_FALSE(step.adapted);
    EXPECT_EQ(c.estimate()[1], 1.0);
  }
  {  // inside the dead zone: no adaptation; outside: adaptation
    auto s = pendulum_settings();
    s.dead_zone = 10.0;
    SlotineLiController<Pendulum, double> c(s, {0.3, 1.0, 0.0});
    EXPECT_FALSE(c.step(q, qd, zero, zero, zero).adapted);
    s.dead_zone = 1e-3;
    SlotineLiController<Pendulum, double> d(s, {0.3, 1.0, 0.0});
    EXPECT_TRUE(d.step(q, qd, zero, zero, zero).adapted);
    EXPECT_NE(d.estimate()[1], 1.0);
  }
  {  // the box holds every update
    auto s = pendulum_settings();
    s.gamma_inverse = {100.0, 100.0, 100.0};
    s.bounded = true;
    s.lower = {0.2, 0.5, 0.0};
    s.upper = {0.4, 1.5, 0.2};
    SlotineLiController<Pendulum, double> c(s, {0.3, 1.0, 0.1});
    for (int i = 0; i < 200; ++i) c.step({std::sin(0.1 * i)}, {std::cos(0.1 * i)}, zero, zero, zero);
    for (int b = 0; b < 3; ++b) {
      EXPECT_GE(c.estimate()[b], s.lower[b]);
      EXPECT_LE(c.estimate()[b], s.upper[b]);
    }
  }
  {  // an update that would make H^ = J^ non-positive is rejected
    auto s = pendulum_settings();
    s.gamma_inverse = {1e6, 0.0, 0.0};
    SlotineLiController<Pendulum, double> c(s, {0.01, 1.0, 0.0});
    // eps = 2.5 > 0 and a = qdd_r = 10 - 4 * 0.5 = 8 > 0 push J^ down by period * 1e6 * a * eps.
    const auto step = c.step({0.5}, {0.5}, zero, zero, {10.0});
    EXPECT_TRUE(step.rejected);
    EXPECT_EQ(c.estimate()[0], 0.01);
  }
}

TEST(SlotineLiKraft, SimplifiedControllerIgnoresVelocityTerms) {
  SlotineLiController<KraftPlantModel, double>::Settings s;
  s.simplified = true;
  std::array<double, 19> p{};
  for (int b = 0; b < 19; ++b) p[b] = Kraft::nominal_parameters[b];
  SlotineLiController<KraftPlantModel, double> c(s, p);
  const std::array<double, 3> q{0.1, 0.2, 0.3}, zero{};
  // Two measured rates, same position error and desired motion: identical torques, and the
  // friction parameters do not adapt (their regressor columns vanish).
  const auto slow = c.evaluate(q, {0.0, 0.0, 0.0}, zero, zero, zero);
  const auto fast = c.evaluate(q, {0.0, 0.0, 0.0}, zero, zero, zero);
  for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(slow.tau[k], fast.tau[k]);
  const auto moving = c.evaluate(q, {1.0, -2.0, 1.5}, q, {1.0, -2.0, 1.5}, zero);
  for (int b = 13; b < 19; ++b) EXPECT_EQ(moving.ytE[b], 0.0) << Kraft::parameter_names[b];
  s.simplified = false;
  SlotineLiController<KraftPlantModel, double> full(s, p);
  const auto full_moving = full.evaluate(q, {1.0, -2.0, 1.5}, q, {1.0, -2.0, 1.5}, zero);
  double difference = 0;
  for (int k = 0; k < 3; ++k) difference += std::abs(full_moving.tau[k] - moving.tau[k]);
  EXPECT_GT(difference, 1e-3) << "the full controller does use the velocity terms";
}

TEST(PositionEstimator, DifferentiatesQuantisedNoisyPositionsAt81Hz) {
  const double period = 1.0 / 81, quantum = 2e-3;
  runtime::PositionEstimator<1, double> estimator(period, 16.0);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 5e-4);
  double sum = 0;
  int count = 0;
  for (int i = 0; i < 81 * 20; ++i) {
    const double t = i * period;
    const double truth = 0.6 * std::sin(1.5 * t), rate = 0.9 * std::cos(1.5 * t);
    const double measured = quantum * std::round((truth + noise(rng)) / quantum);
    estimator.update({measured});
    if (t > 3.0) {
      sum += (estimator.velocity()[0] - rate) * (estimator.velocity()[0] - rate);
      ++count;
    }
  }
  const double rms = std::sqrt(sum / count);
  EXPECT_LT(rms, 0.05 * 0.9) << "velocity RMS error " << rms;
}

}  // namespace
}  // namespace dyncc::test
