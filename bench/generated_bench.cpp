// Per-call time of the generated code (generated/<robot>/) beside the baselines a user would
// pick, in the same process and run: plain Eigen CRBA + RNEA (eigen_rbd.hpp) and MuJoCo 2.2 on
// the exported MJCF (mujoco_baseline.hpp), for the Kraft arm, the PUMA 560 and the Panda.
//   <Quantity>/<implementation>/<robot>
// Quantities: MassMatrix, InverseDynamics (tau = H qdd + C qd + g, with friction for dyncc),
// Gravity; dyncc only: Coriolis (the Christoffel matrix), Regressor (Slotine-Li Y),
// ControlStep (fused Y p and Y^T e, the adaptive controller's kernel), in double and float.
// Inputs cycle through 64 fixed random states so nothing is hoisted out of the loop.
// bench/run_speed_comparison.sh turns the output into the ratio table of docs/performance.md.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "baselines.hpp"
#include "kraft/model.hpp"
#include "panda/model.hpp"
#include "puma560/model.hpp"

namespace {

constexpr int kStates = 64;

template <typename S, int N, int R>
struct Inputs {
  std::array<std::array<S, N>, kStates> q, qd, v, a, e;
  std::array<S, R> p;
  explicit Inputs(const double* nominal) {
    std::mt19937_64 rng(20261122);
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

// Registers the generated functions of one model namespace, for scalar S.
template <typename S, typename Fns>
void register_generated(const std::string& robot, const std::string& suffix) {
  using In = Inputs<S, Fns::n, Fns::r>;
  auto add = [&](const std::string& quantity, auto body) {
    benchmark::RegisterBenchmark((quantity + "/dyncc" + suffix + "/" + robot).c_str(), [body](benchmark::State& st) {
      In in(Fns::nominal());
      std::array<S, Fns::n * Fns::r> out{};
      std::array<S, Fns::r> out2{};
      int k = 0;
      for (auto _ : st) {
        body(in, k, out.data(), out2.data());
        benchmark::DoNotOptimize(out.data());
        benchmark::DoNotOptimize(out2.data());
        benchmark::ClobberMemory();
        k = (k + 1) % kStates;
      }
    });
  };
  add("MassMatrix", [](In& in, int k, S* o, S*) { Fns::mass_matrix(in.q[k].data(), in.p.data(), o); });
  add("InverseDynamics", [](In& in, int k, S* o, S*) {
    Fns::inverse_dynamics(in.q[k].data(), in.qd[k].data(), in.a[k].data(), in.p.data(), o);
  });
  add("Gravity", [](In& in, int k, S* o, S*) { Fns::gravity_torque(in.q[k].data(), in.p.data(), o); });
  add("Coriolis",
      [](In& in, int k, S* o, S*) { Fns::coriolis_matrix(in.q[k].data(), in.qd[k].data(), in.p.data(), o); });
  add("Regressor", [](In& in, int k, S* o, S*) {
    Fns::regressor(in.q[k].data(), in.qd[k].data(), in.v[k].data(), in.a[k].data(), o);
  });
  add("ControlStep", [](In& in, int k, S* o, S* o2) {
    Fns::control_step(in.q[k].data(), in.qd[k].data(), in.v[k].data(), in.a[k].data(), in.p.data(), in.e[k].data(), o,
                      o2);
  });
}

#define DYNCC_GENERATED_FUNCTIONS(NS, S)                                                                            \
  struct NS##_##S {                                                                                                 \
    static constexpr int n = dyncc::generated::NS::kDof;                                                            \
    static constexpr int r = dyncc::generated::NS::kBaseParameters;                                                 \
    static const double* nominal() { return dyncc::generated::NS::kNominalBaseParameters; }                         \
    static void mass_matrix(const S* q, const S* p, S* H) { dyncc::generated::NS::mass_matrix(q, p, H); }           \
    static void inverse_dynamics(const S* q, const S* qd, const S* qdd, const S* p, S* t) {                         \
      dyncc::generated::NS::inverse_dynamics(q, qd, qdd, p, t);                                                     \
    }                                                                                                               \
    static void gravity_torque(const S* q, const S* p, S* g) { dyncc::generated::NS::gravity_torque(q, p, g); }     \
    static void coriolis_matrix(const S* q, const S* qd, const S* p, S* C) {                                        \
      dyncc::generated::NS::coriolis_matrix(q, qd, p, C);                                                           \
    }                                                                                                               \
    static void regressor(const S* q, const S* qd, const S* v, const S* a, S* Y) {                                  \
      dyncc::generated::NS::regressor(q, qd, v, a, Y);                                                              \
    }                                                                                                               \
    static void control_step(const S* q, const S* qd, const S* v, const S* a, const S* p, const S* e, S* t, S* y) { \
      dyncc::generated::NS::control_step(q, qd, v, a, p, e, t, y);                                                  \
    }                                                                                                               \
  };

DYNCC_GENERATED_FUNCTIONS(kraft_right, double)
DYNCC_GENERATED_FUNCTIONS(kraft_right, float)
DYNCC_GENERATED_FUNCTIONS(puma560, double)
DYNCC_GENERATED_FUNCTIONS(panda, double)

struct States {
  std::vector<Eigen::VectorXd> q, qd, qdd;
};

States random_states(int n) {
  std::mt19937_64 rng(20261122);
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

void register_baselines(const std::string& robot, dyncc::bench::Baselines& b) {
  using dyncc::bench::Baselines;
  using V = Eigen::VectorXd;
  auto add = [&](const std::string& name, auto call) {
    benchmark::RegisterBenchmark(name.c_str(), [&b, call](benchmark::State& st) {
      const int n = static_cast<int>(b.robot.coordinates.size());
      const States s = random_states(n);
      V out(n * n);
      int k = 0;
      for (auto _ : st) {
        call(b, s.q[k], s.qd[k], s.qdd[k], out.data());
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
        k = (k + 1) % kStates;
      }
    });
  };
  add("MassMatrix/Eigen/" + robot,
      [](Baselines& x, const V& q, const V&, const V&, double* o) { x.eigen->mass_matrix(q.data(), o); });
  add("MassMatrix/MuJoCo/" + robot,
      [](Baselines& x, const V& q, const V&, const V&, double* o) { x.mujoco->mass_matrix(q.data(), o); });
  add("InverseDynamics/Eigen/" + robot, [](Baselines& x, const V& q, const V& qd, const V& qdd, double* o) {
    x.eigen->inverse_dynamics(q.data(), qd.data(), qdd.data(), o);
  });
  add("InverseDynamics/MuJoCo/" + robot, [](Baselines& x, const V& q, const V& qd, const V& qdd, double* o) {
    x.mujoco->inverse_dynamics(q.data(), qd.data(), qdd.data(), o);
  });
  add("Gravity/Eigen/" + robot,
      [](Baselines& x, const V& q, const V&, const V&, double* o) { x.eigen->gravity_torque(q.data(), o); });
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path robots = std::filesystem::path(DYNCC_SOURCE_DIR) / "robots";
  std::vector<std::pair<std::string, dyncc::bench::Baselines>> loaded;
  loaded.reserve(3);
  for (const char* name : {"kraft", "puma560", "panda"}) {
    try {
      loaded.emplace_back(name, dyncc::bench::load_baselines(robots / (std::string(name) + ".yaml")));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "generated_bench: %s\n", e.what());
      return 2;
    }
  }
  register_generated<double, kraft_right_double>("kraft", "");
  register_generated<float, kraft_right_float>("kraft", "-float");
  register_generated<double, puma560_double>("puma560", "");
  register_generated<double, panda_double>("panda", "");
  for (auto& [name, b] : loaded) register_baselines(name, b);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
