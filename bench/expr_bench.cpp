// Expression-engine benchmark: kinetic energy of a 3- and a 6-link chain (see chain_energy.hpp).
//
// bench/sympy_expr_bench.py does the same tasks in SymPy and bench/run_expr_comparison.sh puts
// both into docs/performance.md. The tasks, per chain size N:
//   Build        build T(q, qd) by link-to-link propagation (unexpanded DAG)
//   BuildExpand  build T and expand it                          -> counter terms = terms of expand(T)
//   Diff         dT/dqd_i for all i, then d/dq_j of those for all i, j (N + N^2 derivatives of the
//                expanded T)                                     -> counter terms = sum of their terms
//   ZeroTest     test_zero(T_body - T_world): the two constructions of T agree only through
//                sin^2 + cos^2 = 1, so this is a trigonometric identity, proved by the normal form
//
// Fresh work. dyncc interns every node in a process-wide pool and never frees it, so building an
// expression a second time is a chain of hash lookups, and expand/diff/test_zero of an already
// seen input only re-create nodes that already exist. To time the work itself, every iteration of
// the *fresh* benchmarks uses a chain whose symbol names carry a new suffix ("q1_r17"): none of its
// nodes are in the pool, as in a generator run that sees a robot for the first time. The input of
// Diff and ZeroTest is built with the timer paused. The pool grows by every iteration's nodes (the
// counter pool_nodes_per_iter says by how much). The *Warm* variants reuse one chain, to show what
// the pool saves; they are not used for the SymPy comparison.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>
#include <vector>

#include "chain_energy.hpp"
#include "sym/diff.hpp"
#include "sym/expand.hpp"
#include "sym/trig_normal_form.hpp"

namespace {

using dyncc::bench::Expr;
using dyncc::bench::Link;
using dyncc::bench::term_count;

std::string fresh_suffix() {
  static int counter = 0;
  return "_r" + std::to_string(++counter);
}

// The N + N^2 derivatives of Lagrange's equations that only need T: dT/dqd_i and d^2T/dq_j dqd_i.
std::size_t lagrange_derivatives(const std::vector<Link>& chain, Expr T) {
  std::vector<dyncc::sym::Differentiator> by_q;
  by_q.reserve(chain.size());
  for (const Link& l : chain) by_q.emplace_back(l.q);
  std::size_t terms = 0;
  for (const Link& li : chain) {
    const Expr dT = dyncc::sym::diff(T, li.qd);
    terms += term_count(dT);
    for (auto& d_dq : by_q) terms += term_count(d_dq(dT));
  }
  return terms;
}

void set_pool_counter(benchmark::State& state, std::size_t pool_before) {
  state.counters["pool_nodes_per_iter"] =
      static_cast<double>(dyncc::sym::pool_size() - pool_before) / static_cast<double>(state.iterations());
}

// Google Benchmark's loop idiom `for (auto _ : state)` is a dead store to the analyzer.
// NOLINTBEGIN(clang-analyzer-deadcode.DeadStores)

void BM_Build(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const std::size_t pool_before = dyncc::sym::pool_size();
  for (auto _ : state) {
    const auto chain = dyncc::bench::make_chain(n, fresh_suffix());
    benchmark::DoNotOptimize(dyncc::bench::kinetic_energy_body(chain));
  }
  set_pool_counter(state, pool_before);
}

void BM_BuildExpand(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const std::size_t pool_before = dyncc::sym::pool_size();
  std::size_t terms = 0;
  for (auto _ : state) {
    const auto chain = dyncc::bench::make_chain(n, fresh_suffix());
    const Expr T = dyncc::sym::expand(dyncc::bench::kinetic_energy_body(chain));
    terms = term_count(T);
  }
  state.counters["terms"] = static_cast<double>(terms);
  set_pool_counter(state, pool_before);
}

void BM_Diff(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::size_t terms = 0;
  std::size_t pool_nodes = 0;
  for (auto _ : state) {
    state.PauseTiming();
    const auto chain = dyncc::bench::make_chain(n, fresh_suffix());
    const Expr T = dyncc::sym::expand(dyncc::bench::kinetic_energy_body(chain));
    const std::size_t before = dyncc::sym::pool_size();
    state.ResumeTiming();
    terms = lagrange_derivatives(chain, T);
    pool_nodes += dyncc::sym::pool_size() - before;
  }
  state.counters["terms"] = static_cast<double>(terms);
  state.counters["pool_nodes_per_iter"] = static_cast<double>(pool_nodes) / static_cast<double>(state.iterations());
}

void BM_ZeroTest(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::size_t pool_nodes = 0;
  for (auto _ : state) {
    state.PauseTiming();
    const auto chain = dyncc::bench::make_chain(n, fresh_suffix());
    const Expr difference = dyncc::bench::kinetic_energy_body(chain) - dyncc::bench::kinetic_energy_world(chain);
    const std::size_t before = dyncc::sym::pool_size();
    state.ResumeTiming();
    const auto result = dyncc::sym::test_zero(difference);
    pool_nodes += dyncc::sym::pool_size() - before;
    if (result.verdict != dyncc::sym::ZeroVerdict::Zero || !result.proved) {
      state.SkipWithError("T_body - T_world was not proved zero");
      break;
    }
  }
  state.counters["pool_nodes_per_iter"] = static_cast<double>(pool_nodes) / static_cast<double>(state.iterations());
}

// ---- warm-pool variants: the same chain every iteration ----

void BM_BuildExpandWarm(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto chain = dyncc::bench::make_chain(n, "_warm");
  benchmark::DoNotOptimize(dyncc::sym::expand(dyncc::bench::kinetic_energy_body(chain)));
  for (auto _ : state) benchmark::DoNotOptimize(dyncc::sym::expand(dyncc::bench::kinetic_energy_body(chain)));
}

void BM_DiffWarm(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto chain = dyncc::bench::make_chain(n, "_warm");
  const Expr T = dyncc::sym::expand(dyncc::bench::kinetic_energy_body(chain));
  benchmark::DoNotOptimize(lagrange_derivatives(chain, T));
  for (auto _ : state) benchmark::DoNotOptimize(lagrange_derivatives(chain, T));
}

void BM_ZeroTestWarm(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto chain = dyncc::bench::make_chain(n, "_warm");
  const Expr difference = dyncc::bench::kinetic_energy_body(chain) - dyncc::bench::kinetic_energy_world(chain);
  for (auto _ : state) benchmark::DoNotOptimize(dyncc::sym::test_zero(difference));
}

// NOLINTEND(clang-analyzer-deadcode.DeadStores)

void chain_sizes(benchmark::internal::Benchmark* b) { b->Arg(3)->Arg(6)->Unit(benchmark::kMillisecond); }

}  // namespace

BENCHMARK(BM_Build)->Apply(chain_sizes);
BENCHMARK(BM_BuildExpand)->Apply(chain_sizes);
BENCHMARK(BM_Diff)->Apply(chain_sizes);
BENCHMARK(BM_ZeroTest)->Apply(chain_sizes);
BENCHMARK(BM_BuildExpandWarm)->Apply(chain_sizes);
BENCHMARK(BM_DiffWarm)->Apply(chain_sizes);
BENCHMARK(BM_ZeroTestWarm)->Apply(chain_sizes);

BENCHMARK_MAIN();
