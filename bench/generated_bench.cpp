// Per-call time of the generated code (generated/<robot>/): H, C, tau_g, the regressor, inverse
// dynamics and the fused control step, in double and float, for every checked-in model.
// Inputs are varied from call to call (a small ring of random states) so nothing is hoisted out
// of the loop; the baselines (Eigen CRBA + RNEA, MuJoCo) live beside this file.
#include <benchmark/benchmark.h>

#include <array>
#include <random>

#include "kraft/model.hpp"
#include "panda/model.hpp"
#include "puma560/model.hpp"

namespace {

template <typename S, int N, int R>
struct Inputs {
  static constexpr int kStates = 64;
  std::array<std::array<S, N>, kStates> q, qd, v, a, e;
  std::array<S, R> p;
  explicit Inputs(const double* nominal) {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> angle(-3.0, 3.0), rate(-2.0, 2.0);
    for (int s = 0; s < kStates; ++s) {
      for (int i = 0; i < N; ++i) {
        q[s][i] = static_cast<S>(angle(rng));
        qd[s][i] = static_cast<S>(rate(rng));
        v[s][i] = static_cast<S>(rate(rng));
        a[s][i] = static_cast<S>(rate(rng));
        e[s][i] = static_cast<S>(rate(rng) * 0.01);
      }
    }
    for (int b = 0; b < R; ++b) p[b] = static_cast<S>(nominal[b]);
  }
};

#define DYNCC_BENCH_MODEL(NS, LABEL, S)                                                                     \
  void LABEL##_mass_matrix_##S(benchmark::State& st) {                                                       \
    namespace M = dyncc::generated::NS;                                                                      \
    Inputs<S, M::kDof, M::kBaseParameters> in(M::kNominalBaseParameters);                                    \
    std::array<S, M::kDof * M::kDof> H{};                                                                    \
    int k = 0;                                                                                               \
    for (auto _ : st) {                                                                                      \
      M::mass_matrix(in.q[k].data(), in.p.data(), H.data());                                                 \
      benchmark::DoNotOptimize(H);                                                                           \
      k = (k + 1) % in.kStates;                                                                              \
    }                                                                                                        \
  }                                                                                                          \
  BENCHMARK(LABEL##_mass_matrix_##S);                                                                        \
  void LABEL##_coriolis_matrix_##S(benchmark::State& st) {                                                   \
    namespace M = dyncc::generated::NS;                                                                      \
    Inputs<S, M::kDof, M::kBaseParameters> in(M::kNominalBaseParameters);                                    \
    std::array<S, M::kDof * M::kDof> C{};                                                                    \
    int k = 0;                                                                                               \
    for (auto _ : st) {                                                                                      \
      M::coriolis_matrix(in.q[k].data(), in.qd[k].data(), in.p.data(), C.data());                            \
      benchmark::DoNotOptimize(C);                                                                           \
      k = (k + 1) % in.kStates;                                                                              \
    }                                                                                                        \
  }                                                                                                          \
  BENCHMARK(LABEL##_coriolis_matrix_##S);                                                                    \
  void LABEL##_gravity_##S(benchmark::State& st) {                                                           \
    namespace M = dyncc::generated::NS;                                                                      \
    Inputs<S, M::kDof, M::kBaseParameters> in(M::kNominalBaseParameters);                                    \
    std::array<S, M::kDof> g{};                                                                              \
    int k = 0;                                                                                               \
    for (auto _ : st) {                                                                                      \
      M::gravity_torque(in.q[k].data(), in.p.data(), g.data());                                              \
      benchmark::DoNotOptimize(g);                                                                           \
      k = (k + 1) % in.kStates;                                                                              \
    }                                                                                                        \
  }                                                                                                          \
  BENCHMARK(LABEL##_gravity_##S);                                                                            \
  void LABEL##_regressor_##S(benchmark::State& st) {                                                         \
    namespace M = dyncc::generated::NS;                                                                      \
    Inputs<S, M::kDof, M::kBaseParameters> in(M::kNominalBaseParameters);                                    \
    std::array<S, M::kDof * M::kBaseParameters> Y{};                                                         \
    int k = 0;                                                                                               \
    for (auto _ : st) {                                                                                      \
      M::regressor(in.q[k].data(), in.qd[k].data(), in.v[k].data(), in.a[k].data(), Y.data());               \
      benchmark::DoNotOptimize(Y);                                                                           \
      k = (k + 1) % in.kStates;                                                                              \
    }                                                                                                        \
  }                                                                                                          \
  BENCHMARK(LABEL##_regressor_##S);                                                                          \
  void LABEL##_inverse_dynamics_##S(benchmark::State& st) {                                                  \
    namespace M = dyncc::generated::NS;                                                                      \
    Inputs<S, M::kDof, M::kBaseParameters> in(M::kNominalBaseParameters);                                    \
    std::array<S, M::kDof> tau{};                                                                            \
    int k = 0;                                                                                               \
    for (auto _ : st) {                                                                                      \
      M::inverse_dynamics(in.q[k].data(), in.qd[k].data(), in.a[k].data(), in.p.data(), tau.data());         \
      benchmark::DoNotOptimize(tau);                                                                         \
      k = (k + 1) % in.kStates;                                                                              \
    }                                                                                                        \
  }                                                                                                          \
  BENCHMARK(LABEL##_inverse_dynamics_##S);                                                                   \
  void LABEL##_control_step_##S(benchmark::State& st) {                                                      \
    namespace M = dyncc::generated::NS;                                                                      \
    Inputs<S, M::kDof, M::kBaseParameters> in(M::kNominalBaseParameters);                                    \
    std::array<S, M::kDof> tau{};                                                                            \
    std::array<S, M::kBaseParameters> yte{};                                                                 \
    int k = 0;                                                                                               \
    for (auto _ : st) {                                                                                      \
      M::control_step(in.q[k].data(), in.qd[k].data(), in.v[k].data(), in.a[k].data(), in.p.data(),         \
                      in.e[k].data(), tau.data(), yte.data());                                               \
      benchmark::DoNotOptimize(tau);                                                                         \
      benchmark::DoNotOptimize(yte);                                                                         \
      k = (k + 1) % in.kStates;                                                                              \
    }                                                                                                        \
  }                                                                                                          \
  BENCHMARK(LABEL##_control_step_##S);

DYNCC_BENCH_MODEL(kraft_right, kraft, double)
DYNCC_BENCH_MODEL(kraft_right, kraft, float)
DYNCC_BENCH_MODEL(puma560, puma560, double)
DYNCC_BENCH_MODEL(panda, panda, double)

}  // namespace

BENCHMARK_MAIN();
