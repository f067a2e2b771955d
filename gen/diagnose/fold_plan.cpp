#include "diagnose/fold_plan.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <utility>
#include <vector>

namespace dyncc::diagnose {
namespace {

constexpr int kGridSteps = 10;  // an edge moves on a grid of 1/20 of an even block, up to half of one
constexpr Eigen::Index kGridDivisions = Eigen::Index{2} * kGridSteps;

// The shortest block allowed: kShortestBlock of an even one.
Eigen::Index shortest_block(Eigen::Index samples) {
  const Eigen::Index block = samples / kFolds;
  return static_cast<Eigen::Index>(kShortestBlock * static_cast<double>(block));
}

// The rows' bursts: running sums of their energy (so a block's is two reads) and which rows lie
// within kBurstMargin of one (where an edge would cut through a burst).
struct Bursts {
  std::vector<double> running;  // samples + 1: energy of the burst rows before each row
  std::vector<bool> near;       // samples
  double energy = 0, residual_energy = 0;
  [[nodiscard]] double in(Eigen::Index begin, Eigen::Index end) const {
    return running[static_cast<std::size_t>(end)] - running[static_cast<std::size_t>(begin)];
  }
  [[nodiscard]] double largest_share(const Folds& folds) const {
    double largest = 0;
    for (int f = 0; f < kFolds; ++f) largest = std::max(largest, in(folds.begin_of(f), folds.end_of(f)));
    return largest / energy;
  }
  [[nodiscard]] bool cuts(Eigen::Index edge) const {
    return near[static_cast<std::size_t>(edge - 1)] && near[static_cast<std::size_t>(edge)];
  }
};

Bursts find_bursts(const Eigen::VectorXd& residual, const Eigen::VectorXd& weight, Eigen::Index n, double step) {
  const Eigen::Index samples = residual.size() / n;
  Eigen::VectorXd energy = Eigen::VectorXd::Zero(samples);
  for (Eigen::Index s = 0; s < samples; ++s) {
    for (Eigen::Index j = 0; j < n; ++j) energy[s] += std::pow(weight[j] * residual[s * n + j], 2);
  }
  std::vector<double> sorted(energy.data(), energy.data() + samples);
  const auto middle = sorted.begin() + samples / 2;
  std::nth_element(sorted.begin(), middle, sorted.end());
  const double threshold = std::max(kBurstOverMedian * *middle, kBurstOfPeak * energy.maxCoeff());
  Bursts b;
  b.running.assign(static_cast<std::size_t>(samples) + 1, 0.0);
  b.near.assign(static_cast<std::size_t>(samples), false);
  b.residual_energy = energy.sum();
  const auto margin = static_cast<Eigen::Index>(kBurstMargin / step);
  const auto longest = static_cast<Eigen::Index>(kLongestBurst / step);
  // Rows over the threshold closer than the margin are one burst (a touch's rows dip below the
  // threshold and rise again). A burst longer than kLongestBurst is a stretch, not a touch: not
  // counted.
  std::vector<std::pair<Eigen::Index, Eigen::Index>> bursts;  // [first, last] rows
  for (Eigen::Index s = 0; s < samples; ++s) {
    if (energy[s] <= threshold) continue;
    if (!bursts.empty() && s - bursts.back().second <= margin) {
      bursts.back().second = s;
    } else {
      bursts.emplace_back(s, s);
    }
  }
  std::vector<double> counted(static_cast<std::size_t>(samples), 0.0);
  for (const auto& [first, last] : bursts) {
    if (last - first > longest) continue;
    for (Eigen::Index s = first; s <= last; ++s) {
      if (energy[s] > threshold) counted[static_cast<std::size_t>(s)] = energy[s];
    }
    // Widened by the margin: an edge there would cut through the burst or its filtered tail.
    for (Eigen::Index s = std::max<Eigen::Index>(0, first - margin); s <= std::min(samples - 1, last + margin); ++s) {
      b.near[static_cast<std::size_t>(s)] = true;
    }
  }
  for (Eigen::Index s = 0; s < samples; ++s) {
    b.running[static_cast<std::size_t>(s) + 1] =
        b.running[static_cast<std::size_t>(s)] + counted[static_cast<std::size_t>(s)];
  }
  b.energy = b.running.back();
  return b;
}

// The edges on the grid (every combination) that share the bursts best without cutting through
// one; of equal shares, the one that moves the edges least.
Folds between_bursts(const Bursts& bursts, const Folds& even, Eigen::Index samples) {
  const Eigen::Index block = samples / kFolds, shortest = shortest_block(samples);
  Folds best = even;
  double best_share = bursts.largest_share(even), best_moved = 0;
  std::array<int, kFolds - 1> offset{};
  offset.fill(-kGridSteps);
  for (;;) {
    Folds folds = even;
    int moved = 0;
    bool valid = true;
    for (int f = 1; f < kFolds && valid; ++f) {
      const int o = offset[static_cast<std::size_t>(f - 1)];
      folds.begin[static_cast<std::size_t>(f)] = even.begin_of(f) + o * block / kGridDivisions;
      moved += std::abs(o);
      valid = folds.begin_of(f) - folds.begin_of(f - 1) >= shortest && (o == 0 || !bursts.cuts(folds.begin_of(f)));
    }
    if (valid && folds.end_of(kFolds - 1) - folds.begin_of(kFolds - 1) >= shortest) {
      const double share = bursts.largest_share(folds);
      if (share < best_share - 1e-9 || (share < best_share + 1e-9 && moved < best_moved)) {
        best = folds;
        best_share = share;
        best_moved = moved;
      }
    }
    std::size_t k = 0;  // the next combination (an odometer over the edges' offsets)
    while (k < offset.size() && offset[k] == kGridSteps) offset[k++] = -kGridSteps;
    if (k == offset.size()) break;
    ++offset[k];
  }
  return best;
}

// From `start`, twice: the single edge move (to any row) that lowers the largest share the most;
// of equal shares, the shortest move.
Folds through_a_burst(const Bursts& bursts, const Folds& start, Eigen::Index samples) {
  const Eigen::Index shortest = shortest_block(samples);
  Folds best = start;
  double best_share = bursts.largest_share(start);
  for (int round = 0; round < 2; ++round) {
    Folds next = best;
    Eigen::Index least_moved = 0;
    for (int f = 1; f < kFolds; ++f) {
      Folds folds = best;
      for (Eigen::Index edge = best.begin_of(f - 1) + shortest; edge <= best.end_of(f) - shortest; ++edge) {
        folds.begin[static_cast<std::size_t>(f)] = edge;
        const double share = bursts.largest_share(folds);
        const Eigen::Index moved = std::abs(edge - best.begin_of(f));
        if (share < best_share - 1e-9 || (share < best_share + 1e-9 && moved < least_moved)) {
          next = folds;
          best_share = share;
          least_moved = moved;
        }
      }
    }
    best = next;
  }
  return best;
}

}  // namespace

Folds folds_sharing_bursts(const Eigen::VectorXd& residual, const Eigen::VectorXd& weight, Eigen::Index n,
                           double step) {
  const Eigen::Index samples = residual.size() / n;
  const Folds even = Folds::even(samples);
  if (samples < Eigen::Index{2} * kFolds) return even;
  const Bursts bursts = find_bursts(residual, weight, n, step);
  if (bursts.energy <= 0 || bursts.energy < kBurstsOfResidual * bursts.residual_energy ||
      bursts.largest_share(even) <= kBurstShareLimit) {
    return even;
  }
  const Folds between = between_bursts(bursts, even, samples);
  if (bursts.largest_share(between) <= kSingleBurst) return between;
  return through_a_burst(bursts, between, samples);
}

}  // namespace dyncc::diagnose
