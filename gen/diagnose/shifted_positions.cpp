#include "diagnose/shifted_positions.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <span>
#include <vector>

#include "diagnose/model_batch.hpp"
#include "diagnose/signals.hpp"

namespace dyncc::diagnose {
namespace {

constexpr double kLinearShift = 0.01;   // rad: below it the tangent is as good as the secant
constexpr double kVelocityStep = 1e-6;  // rad/s, for the torque's derivative by a velocity
constexpr double kLargestShift = 1.0;   // rad: a fit beyond this is not a shift of the positions
// rad: a delay's phase at the filter's cut-off below which its tangent is as good as the secant
// (the cubic term left out is under 0.5^2 / 6 = 4 % of the shift even at the cut-off)
constexpr double kLinearPhase = 0.5;

// The nominal model's torque without its friction. The drive's friction acts at the motor's
// velocity, which is what the log's positions give, so the log and the model have the same
// friction and it cancels in the residual; left in, a shift of the velocity moved where the model's
// friction turns over, by a few mrad/s around a reversal, and through the smoothed sign's slope
// made spikes at every reversal of a swinging torque's joint, larger than the rest of the column.
class ModelTorque {
 public:
  explicit ModelTorque(const pipeline::Derivation& derivation)
      : model_(*derivation.numeric), nominal_(model_.nominal_standard_values()) {}
  ModelTorque(const dyn::NumericModel& model, Eigen::VectorXd values) : model_(model), nominal_(std::move(values)) {}
  // The same model with other standard parameter values (a load's alone: its torque).
  [[nodiscard]] ModelTorque with_values(const Eigen::VectorXd& values) const { return {model_, values}; }
  // At many states (v = qd), in one batch; masses, if asked for, their H.
  [[nodiscard]] std::vector<Eigen::VectorXd> at(std::span<const dyn::State> states,
                                                std::vector<Eigen::MatrixXd>* masses = nullptr) const {
    const std::vector<dyn::Evaluation> all = model_.evaluate(states, nominal_, false);
    std::vector<Eigen::VectorXd> out;
    out.reserve(all.size());
    for (const dyn::Evaluation& e : all) {
      out.emplace_back(e.tau - e.friction);
      if (masses != nullptr) masses->push_back(e.H);
    }
    return out;
  }

 private:
  const dyn::NumericModel& model_;
  Eigen::VectorXd nominal_;
};

// (model at the positions shifted back by theta w_j) - (model), over theta: S*n x 1.
Eigen::VectorXd secant(const Dataset& d, const ModelTorque& model, const Shift& shift, const Eigen::MatrixXd& tau,
                       Eigen::Index j, double theta) {
  const Eigen::Index n = d.n;
  Eigen::VectorXd column(d.samples() * n);
  for (Eigen::Index chunk = 0; chunk < d.samples(); chunk += kModelRowsPerBatch) {
    const Eigen::Index rows = std::min(kModelRowsPerBatch, d.samples() - chunk);
    std::vector<dyn::State> states;
    for (Eigen::Index s = chunk; s < chunk + rows; ++s) {
      dyn::State x{d.q.row(s).transpose(), d.qd.row(s).transpose(), {}, d.qdd.row(s).transpose()};
      x.q[j] -= theta * shift.w(s, j);  // measured = link + theta w
      x.qd[j] -= theta * shift.wd(s, j);
      x.a[j] -= theta * shift.wdd(s, j);
      x.v = x.qd;
      states.push_back(std::move(x));
    }
    const std::vector<Eigen::VectorXd> shifted = model.at(states);
    for (Eigen::Index s = chunk; s < chunk + rows; ++s) {
      column.segment(s * n, n) = (shifted[static_cast<std::size_t>(s - chunk)] - tau.row(s).transpose()) / theta;
    }
  }
  return column;
}

// The cubic Hermite interpolant at u in [0, 1] between values p0 and p1 with slopes m0 and m1 (per
// unit of u).
double hermite(double p0, double m0, double p1, double m1, double u) {
  const double u2 = u * u, u3 = u2 * u;
  return (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * p1 + (u3 - u2) * m1;
}

// Column j of `values` (one segment's rows at `rate`) at the time of row s plus `lead` seconds,
// by cubic Hermite interpolation with the column's time derivative `slope`; held at the ends.
double shifted_in_time(const Eigen::MatrixXd& values, const Eigen::MatrixXd& slope, Eigen::Index begin,
                       Eigen::Index end, double rate, Eigen::Index s, Eigen::Index j, double lead) {
  const double position = static_cast<double>(s - begin) + lead * rate;
  const double last = static_cast<double>(end - begin - 1);
  if (position <= 0) return values(begin, j);
  if (position >= last) return values(end - 1, j);
  const auto k = static_cast<Eigen::Index>(std::floor(position));
  const double h = 1.0 / rate;
  return hermite(values(begin + k, j), slope(begin + k, j) * h, values(begin + k + 1, j), slope(begin + k + 1, j) * h,
                 position - static_cast<double>(k));
}

// The columns' weighted least-squares coefficients on the residual, with the fits' weights.
Eigen::VectorXd weighted_fit(const Dataset& d, const Eigen::MatrixXd& columns) {
  const Eigen::VectorXd weights = stacked_weights(torque_weights(analysis_torque_rms(d)), columns.rows());
  return (weights.asDiagonal() * columns).colPivHouseholderQr().solve(weights.asDiagonal() * d.residual);
}

// What a shift effect's columns are made from, kept with the effect (Effect::secant_at) so that
// the selection can make a column again at the theta of its joint fit.
struct ShiftSecants {
  const Dataset& d;
  ModelTorque model;
  Shift shift;
  Eigen::MatrixXd tau;       // S x n: the model's torque without its friction
  Eigen::MatrixXd tangents;  // conditioned, one column per joint
  Eigen::VectorXd reach;     // per joint, the largest |w_j|
  // Where the largest shift theta w_j is beyond where the tangent serves and still a shift.
  [[nodiscard]] bool needs_secant(Eigen::Index j, double theta) const {
    const double largest = std::abs(theta) * reach[j];
    return largest > kLinearShift && largest < kLargestShift;
  }
  // Joint j's secant column at theta, conditioned, with each of `changes` (a load) moved by the
  // shift as the model is: the load's torque is computed from the measured positions too.
  [[nodiscard]] Eigen::VectorXd secant_at(Eigen::Index j, double theta,
                                          const std::vector<StandardChange>& changes = {}) const {
    Eigen::MatrixXd column = secant(d, model, shift, tau, j, theta);
    for (const StandardChange& change : changes) {
      const Eigen::VectorXd stacked = d.standard * change.values;  // the load's torque, unshifted
      const Eigen::MatrixXd load_tau = Eigen::Map<const Eigen::MatrixXd>(stacked.data(), d.n, d.samples()).transpose();
      const Eigen::MatrixXd moved = secant(d, model.with_values(change.values), shift, load_tau, j, theta);
      column += change.gate ? change.gate(moved) : moved;
    }
    return d.condition(column).col(0);
  }
};

}  // namespace

Shift filtered_shift(const Dataset& d, const Eigen::MatrixXd& raw) {
  Shift out{Eigen::MatrixXd(raw.rows(), raw.cols()), Eigen::MatrixXd(raw.rows(), raw.cols()),
            Eigen::MatrixXd(raw.rows(), raw.cols())};
  for (const Dataset::Segment& g : d.segments) {
    const Eigen::Index count = g.end - g.begin;
    for (Eigen::Index j = 0; j < raw.cols(); ++j) {
      const Eigen::VectorXd w = zero_phase_lowpass(raw.block(g.begin, j, count, 1), d.cutoff, g.rate);
      const Eigen::VectorXd wd = derivative(w, 1.0 / g.rate);
      out.w.block(g.begin, j, count, 1) = w;
      out.wd.block(g.begin, j, count, 1) = wd;
      out.wdd.block(g.begin, j, count, 1) = derivative(wd, 1.0 / g.rate);
    }
  }
  return out;
}

ModelSensitivity model_sensitivity(const Dataset& d, const pipeline::Derivation& derivation) {
  const ModelTorque model(derivation);
  const Eigen::Index n = d.n, samples = d.samples();
  ModelSensitivity m;
  m.tau.resize(samples, n);
  m.transmitted.resize(samples, n);
  for (Eigen::Index chunk = 0; chunk < samples; chunk += kModelRowsPerBatch) {
    // Each row's state, then the same with one joint's velocity faster, joint by joint: the
    // torque is quadratic in the velocity, so a short forward difference is its derivative.
    const Eigen::Index rows = std::min(kModelRowsPerBatch, samples - chunk);
    std::vector<dyn::State> states, faster;
    for (Eigen::Index s = chunk; s < chunk + rows; ++s) {
      const dyn::State x{d.q.row(s).transpose(), d.qd.row(s).transpose(), d.qd.row(s).transpose(),
                         d.qdd.row(s).transpose()};
      for (Eigen::Index j = 0; j < n; ++j) {
        dyn::State y = x;
        y.qd[j] += kVelocityStep;
        y.v = y.qd;
        faster.push_back(std::move(y));
      }
      states.push_back(x);
    }
    std::vector<Eigen::MatrixXd> masses;
    const std::vector<Eigen::VectorXd> at = model.at(states, &masses);
    const std::vector<Eigen::VectorXd> at_faster = model.at(faster);
    for (Eigen::Index s = chunk; s < chunk + rows; ++s) {
      const auto k = static_cast<std::size_t>(s - chunk);
      const Eigen::VectorXd& tau = at[k];
      m.tau.row(s) = tau.transpose();
      m.transmitted.row(s) = d.tau.row(s) - d.model_friction.row(s);
      m.by_qdd.push_back(masses[k]);  // the torque is H qdd + ...
      Eigen::MatrixXd by_qd(n, n);
      for (Eigen::Index j = 0; j < n; ++j) {
        by_qd.col(j) = (at_faster[k * static_cast<std::size_t>(n) + static_cast<std::size_t>(j)] - tau) / kVelocityStep;
      }
      m.by_qd.push_back(by_qd);
    }
  }
  return m;
}

Eigen::MatrixXd shift_tangents(const Dataset& d, const ModelSensitivity& m, const Shift& shift) {
  const Eigen::Index n = d.n, samples = d.samples();
  Eigen::MatrixXd tangent(samples * n, n);
  for (Eigen::Index s = 0; s < samples; ++s) {
    const auto i = static_cast<std::size_t>(s);
    for (Eigen::Index j = 0; j < n; ++j) {  // d/dtheta of the model at positions - theta w
      tangent.block(s * n, j, n, 1) = -(d.dtau_dq[i].col(j) * shift.w(s, j) + m.by_qd[i].col(j) * shift.wd(s, j) +
                                        m.by_qdd[i].col(j) * shift.wdd(s, j));
    }
  }
  return tangent;
}

void fit_shift_columns(const Dataset& d, const pipeline::Derivation& derivation, const ModelSensitivity& m,
                       const Shift& shift, Effect& effect) {
  const Eigen::Index n = d.n;
  const auto made = std::make_shared<const ShiftSecants>(
      ShiftSecants{d, ModelTorque(derivation), shift, m.tau, d.condition(shift_tangents(d, m, shift)),
                   shift.w.cwiseAbs().colwise().maxCoeff().transpose()});
  effect.columns = made->tangents;
  for (int pass = 0; pass < 2; ++pass) {
    const Eigen::VectorXd theta = weighted_fit(d, effect.columns);
    std::vector<Eigen::Index> shifted;
    for (Eigen::Index j = 0; j < n; ++j) {
      if (made->needs_secant(j, theta[j])) shifted.push_back(j);
    }
    if (shifted.empty()) break;
    for (const Eigen::Index j : shifted) effect.columns.col(j) = made->secant_at(j, theta[j]);
  }
  effect.secant_at = [made](int joint, double theta, const BesideEffects& beside) -> Eigen::VectorXd {
    const auto j = static_cast<Eigen::Index>(joint);
    // Beside a load the secant also where the tangent would serve: the tangent is the model's alone.
    const bool moves_a_load =
        !beside.loads.empty() && theta != 0 && made->reach[j] > 0 && std::abs(theta) * made->reach[j] < kLargestShift;
    if (moves_a_load || made->needs_secant(j, theta)) return made->secant_at(j, theta, beside.loads);
    return made->tangents.col(j);
  };
}

bool delay_needs_secant(const Dataset& d, double delay) {
  return std::isfinite(delay) && std::abs(delay) * 2 * std::numbers::pi * d.cutoff >= kLinearPhase;
}

Eigen::MatrixXd delay_secant(const Dataset& d, double delay) {
  const Eigen::Index n = d.n;
  Eigen::MatrixXd secant(d.samples() * n, 1);
  for (const Dataset::Segment& g : d.segments) {
    for (Eigen::Index s = g.begin; s < g.end; ++s) {
      for (Eigen::Index j = 0; j < n; ++j) {
        const double later = shifted_in_time(d.model_tau, d.model_tau_rate, g.begin, g.end, g.rate, s, j, delay);
        secant(s * n + j, 0) = (later - d.model_tau(s, j)) / delay;
      }
    }
  }
  return d.condition(secant);
}

Eigen::VectorXd advanced_in_time(const Dataset& d, const Eigen::VectorXd& column, double lead) {
  const Eigen::Index n = d.n;
  Eigen::VectorXd out = column;
  Eigen::Index first = 0;  // the segment's first analysis row
  for (const Dataset::Segment& g : d.segments) {
    const auto rows = static_cast<Eigen::Index>(g.keep.size());
    if (rows >= 2) {
      const double step = static_cast<double>(g.keep[1] - g.keep[0]) / g.rate;
      auto value = [&](Eigen::Index k, Eigen::Index j) { return column[(first + k) * n + j]; };
      auto slope = [&](Eigen::Index k, Eigen::Index j) {  // per row
        const Eigen::Index before = std::max<Eigen::Index>(k - 1, 0), after = std::min(k + 1, rows - 1);
        return (value(after, j) - value(before, j)) / static_cast<double>(after - before);
      };
      for (Eigen::Index k = 0; k < rows; ++k) {
        const double position = static_cast<double>(k) + lead / step;
        if (position < 0 || position > static_cast<double>(rows - 1)) continue;
        const auto at = std::min(static_cast<Eigen::Index>(std::floor(position)), rows - 2);
        const double u = position - static_cast<double>(at);
        for (Eigen::Index j = 0; j < n; ++j) {
          out[(first + k) * n + j] = hermite(value(at, j), slope(at, j), value(at + 1, j), slope(at + 1, j), u);
        }
      }
    }
    first += rows;
  }
  return out;
}

void fit_delay_column(const Dataset& d, Effect& effect) {
  const Eigen::VectorXd tangent = effect.columns.col(0);
  for (int pass = 0; pass < 2; ++pass) {
    const double delay = weighted_fit(d, effect.columns)[0];
    if (!delay_needs_secant(d, delay)) break;
    effect.columns = delay_secant(d, delay);
  }
  // Made again beside the other effects, the column is the lag of all that the positions drive:
  // theirs too, advanced by the delay along the analysis rows (settle.cpp, relinearise_secants).
  effect.secant_at = [&d, tangent](int, double delay, const BesideEffects& beside) -> Eigen::VectorXd {
    Eigen::VectorXd column = delay_needs_secant(d, delay) ? Eigen::VectorXd(delay_secant(d, delay).col(0)) : tangent;
    const Eigen::VectorXd& theirs = beside.from_positions;
    if (theirs.size() > 0 && delay != 0) column += (advanced_in_time(d, theirs, delay) - theirs) / delay;
    return column;
  };
}

}  // namespace dyncc::diagnose
