// Baselines of the speed comparison, per call, for the PUMA 560, the Panda and the Kraft arm:
//   <Quantity>/Eigen/<robot>    plain Eigen CRBA / RNEA (eigen_rbd.hpp)
//   <Quantity>/MuJoCo/<robot>   MuJoCo 2.2 on the MJCF from `dyncc export` (mujoco_baseline.hpp
//                               says which mj_* calls one call makes)
// Quantities: MassMatrix (H at q), InverseDynamics (tau = H qdd + C qd + g), and, MuJoCo only,
// Forward (mj_forward: the whole forward-dynamics pipeline including the equality constraints of
// the Kraft arm's parallelogram; not the same quantity, shown for scale).
// The Kraft arm is a closed chain: both baselines compute on its five-joint tree and project
// onto the three coordinates (H = G^T M G, tau = G^T tau_tree), which is included in the time.
// Each iteration takes the next of 64 fixed random states, so the timed inputs vary.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "baselines.hpp"

namespace {

using dyncc::bench::Baselines;

constexpr int kStates = 64;

struct States {
  std::vector<Eigen::VectorXd> q, qd, qdd;
};

States random_states(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(-3.0, 3.0), rate(-2.0, 2.0);
  States s;
  for (int k = 0; k < kStates; ++k) {
    Eigen::VectorXd q(n), qd(n), qdd(n);
    for (int i = 0; i < n; ++i) {
      q[i] = angle(rng);
      qd[i] = rate(rng);
      qdd[i] = rate(rng);
    }
    s.q.push_back(q);
    s.qd.push_back(qd);
    s.qdd.push_back(qdd);
  }
  return s;
}

template <typename Call>
void time_calls(benchmark::State& state, Baselines& b, Call call) {
  const int n = static_cast<int>(b.robot.coordinates.size());
  const States s = random_states(n, 20261122);
  Eigen::VectorXd out(n * n);
  int k = 0;
  for (auto _ : state) {
    call(b, s.q[k], s.qd[k], s.qdd[k], out.data());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
    k = (k + 1) % kStates;
  }
  state.counters["dof"] = n;
}

void register_robot(const std::string& name, Baselines& b) {
  using V = Eigen::VectorXd;
  benchmark::RegisterBenchmark(("MassMatrix/Eigen/" + name).c_str(), [&b](benchmark::State& st) {
    time_calls(st, b,
               [](Baselines& x, const V& q, const V&, const V&, double* out) { x.eigen->mass_matrix(q.data(), out); });
  });
  benchmark::RegisterBenchmark(("MassMatrix/MuJoCo/" + name).c_str(), [&b](benchmark::State& st) {
    time_calls(st, b,
               [](Baselines& x, const V& q, const V&, const V&, double* out) { x.mujoco->mass_matrix(q.data(), out); });
  });
  benchmark::RegisterBenchmark(("InverseDynamics/Eigen/" + name).c_str(), [&b](benchmark::State& st) {
    time_calls(st, b, [](Baselines& x, const V& q, const V& qd, const V& qdd, double* out) {
      x.eigen->inverse_dynamics(q.data(), qd.data(), qdd.data(), out);
    });
  });
  benchmark::RegisterBenchmark(("InverseDynamics/MuJoCo/" + name).c_str(), [&b](benchmark::State& st) {
    time_calls(st, b, [](Baselines& x, const V& q, const V& qd, const V& qdd, double* out) {
      x.mujoco->inverse_dynamics(q.data(), qd.data(), qdd.data(), out);
    });
  });
  benchmark::RegisterBenchmark(("Forward/MuJoCo/" + name).c_str(), [&b](benchmark::State& st) {
    time_calls(st, b, [](Baselines& x, const V& q, const V& qd, const V&, double*) {
      x.mujoco->forward(q.data(), qd.data());
    });
  });
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path robots = std::filesystem::path(DYNCC_SOURCE_DIR) / "robots";
  std::vector<std::pair<std::string, Baselines>> loaded;
  loaded.reserve(3);
  for (const char* name : {"puma560", "panda", "kraft"}) {
    try {
      loaded.emplace_back(name, dyncc::bench::load_baselines(robots / (std::string(name) + ".yaml")));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "baseline_bench: %s\n", e.what());
      return 2;
    }
  }
  for (auto& [name, b] : loaded) register_robot(name, b);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
