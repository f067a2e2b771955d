#include "diagnose/dataset.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "diagnose/column_filter.hpp"
#include "diagnose/model_batch.hpp"

namespace dyncc::diagnose {
namespace {

constexpr double kMaxCutoff = 4.0;         // Hz: arm motion of interest lies below
constexpr double kEvaluationRate = 100.0;  // Hz: at most this many evaluation rows per second
constexpr double kRowsPerCutoff = 8.0;     // analysis rows per 1/cutoff
constexpr double kEdgeTrimPeriods = 2.0;   // filter periods dropped at each end
constexpr double kSensitivityStep = 1e-6;  // rad (or m) for d tau / dq
constexpr unsigned kNoiseSeed = 1;         // the draw of position_noise_torque (fixed: same log, same diagnosis)

// A held command acts over its whole period: it stands for the torque at the period's middle. On
// a uniform grid, interpolating between those middles gives each row the mean torque over the
// period centred on it. The last row's period is taken as long as the one before.
Eigen::VectorXd held_torque_times(const Eigen::VectorXd& t) {
  Eigen::VectorXd middle(t.size());
  for (Eigen::Index i = 0; i + 1 < t.size(); ++i) middle[i] = 0.5 * (t[i] + t[i + 1]);
  const Eigen::Index last = t.size() - 1;
  middle[last] = last > 0 ? t[last] + 0.5 * (t[last] - t[last - 1]) : t[last];
  return middle;
}

struct Conditioned {
  Eigen::VectorXd t;
  Eigen::MatrixXd q, qd, qdd, tau, q_sharp;
  double rate = 0;
};

// Positions filtered and differentiated at the log's own rate, the torque only anti-aliased;
// then every stride-th row, for at most kEvaluationRate rows per second.
Conditioned condition_log(const JointLog& log, const Audit& audit, double cutoff, bool held_torque) {
  const double dt = 1.0 / audit.rate;
  const auto n = static_cast<Eigen::Index>(std::floor((log.t[log.samples() - 1] - log.t[0]) / dt)) + 1;
  const Eigen::VectorXd grid = Eigen::VectorXd::LinSpaced(n, log.t[0], log.t[0] + dt * static_cast<double>(n - 1));
  const Eigen::MatrixXd q = interpolate(log.t, log.q, grid),
                        tau = interpolate(held_torque ? held_torque_times(log.t) : log.t, log.tau, grid);
  const auto stride = std::max<Eigen::Index>(1, static_cast<Eigen::Index>(std::floor(audit.rate / kEvaluationRate)));
  const double rate = audit.rate / static_cast<double>(stride);
  Eigen::MatrixXd qf(n, log.joints()), qd(n, log.joints()), qdd(n, log.joints()), taua(n, log.joints()),
      qa(n, log.joints());
  const Eigen::MatrixXd measured_rate = log.qd ? interpolate(log.t, *log.qd, grid) : Eigen::MatrixXd();
  for (Eigen::Index k = 0; k < log.joints(); ++k) {
    qf.col(k) = zero_phase_lowpass(q.col(k), cutoff, audit.rate);
    // A logged velocity is better than a differentiated position: filter it instead.
    qd.col(k) = log.qd ? zero_phase_lowpass(measured_rate.col(k), cutoff, audit.rate) : derivative(qf.col(k), dt);
    qdd.col(k) = derivative(qd.col(k), dt);
    taua.col(k) = stride > 1 ? zero_phase_lowpass(tau.col(k), 0.4 * rate, audit.rate) : Eigen::VectorXd(tau.col(k));
    qa.col(k) = stride > 1 ? zero_phase_lowpass(q.col(k), 0.4 * rate, audit.rate) : Eigen::VectorXd(q.col(k));
  }
  Conditioned c;
  c.rate = rate;
  const Eigen::Index m = (n + stride - 1) / stride;
  c.t.resize(m);
  c.q.resize(m, log.joints());
  c.qd.resize(m, log.joints());
  c.qdd.resize(m, log.joints());
  c.tau.resize(m, log.joints());
  c.q_sharp.resize(m, log.joints());
  for (Eigen::Index r = 0; r < m; ++r) {
    c.t[r] = grid[r * stride];
    c.q.row(r) = qf.row(r * stride);
    c.qd.row(r) = qd.row(r * stride);
    c.qdd.row(r) = qdd.row(r * stride);
    c.tau.row(r) = taua.row(r * stride);
    c.q_sharp.row(r) = qa.row(r * stride);
  }
  return c;
}

// The model's acceleration is twice a derivative of the positions, so their noise and
// quantisation reach the model torque within the filter's band (the more, the lower the rate and
// the larger the inertia); a closed-loop controller answers the same noise with torque of its
// own. That part of the residual is no missing effect. Measured by drawing fresh noise of the
// size the audit found, conditioning the log again with it and taking the change in the rigid-body
// model torque (the friction sign's share is sign_floor's), through the same filter. One fixed
// draw: the same log gets the same diagnosis.
Eigen::VectorXd position_noise_torque(const std::vector<JointLog>& logs, const Dataset& d,
                                      const dyn::NumericModel& model, const Eigen::VectorXd& nominal,
                                      const Eigen::MatrixXd& rigid) {
  const Eigen::Index n = d.n;
  std::mt19937 random(kNoiseSeed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd change = Eigen::MatrixXd::Zero(d.samples() * n, 1);
  for (std::size_t l = 0; l < logs.size(); ++l) {
    JointLog noisy = logs[l];
    for (Eigen::Index j = 0; j < n; ++j) {
      const double sigma = d.audits[l].joints[static_cast<std::size_t>(j)].position_noise;
      for (Eigen::Index s = 0; s < noisy.samples(); ++s) noisy.q(s, j) += sigma * normal(random);
    }
    const Conditioned c = condition_log(noisy, d.audits[l], d.cutoff, false);  // its torque is not used
    const Dataset::Segment& g = d.segments[l];
    for (Eigen::Index chunk = 0; chunk < c.t.size(); chunk += kModelRowsPerBatch) {
      std::vector<dyn::State> states;
      for (Eigen::Index s = chunk; s < std::min(chunk + kModelRowsPerBatch, c.t.size()); ++s) {
        states.push_back(
            {c.q.row(s).transpose(), c.qd.row(s).transpose(), c.qd.row(s).transpose(), c.qdd.row(s).transpose()});
      }
      const std::vector<dyn::Evaluation> at = model.evaluate(states, nominal, false);
      for (std::size_t k = 0; k < at.size(); ++k) {
        const dyn::Evaluation& e = at[k];
        const Eigen::Index row = g.begin + chunk + static_cast<Eigen::Index>(k);
        for (Eigen::Index j = 0; j < n; ++j) {
          change(row * n + j, 0) = (e.tau[j] - e.friction[j]) - rigid(row, j);
        }
      }
    }
  }
  const Eigen::VectorXd filtered = d.condition(change).col(0);
  Eigen::VectorXd rms = Eigen::VectorXd::Zero(n);
  for (Eigen::Index r = 0; r < filtered.size(); ++r) rms[r % n] += filtered[r] * filtered[r];
  return (rms / static_cast<double>(std::max<Eigen::Index>(1, filtered.size() / n))).cwiseSqrt();
}

// Every column of a stacked (S*n x k) matrix through the zero-phase filter along time, per joint
// and per log; `take(segment, filtered)` gets each log's rows (column c * n + i: joint i of c).
template <typename Take>
void filter_segments(const Dataset& d, const Eigen::MatrixXd& stacked, Take take) {
  const Eigen::Index n = d.n;
  for (const Dataset::Segment& g : d.segments) {
    const Eigen::Index length = g.end - g.begin;
    RowMatrix x(length, stacked.cols() * n);
    for (Eigen::Index s = 0; s < length; ++s) {
      for (Eigen::Index c = 0; c < stacked.cols(); ++c) {
        for (Eigen::Index i = 0; i < n; ++i) x(s, c * n + i) = stacked((g.begin + s) * n + i, c);
      }
    }
    zero_phase_lowpass_rows(x, d.cutoff, g.rate);
    take(g, x);
  }
}

}  // namespace

Eigen::MatrixXd Dataset::condition(const Eigen::MatrixXd& stacked) const {
  Eigen::Index total = 0;
  for (const Segment& g : segments) total += static_cast<Eigen::Index>(g.keep.size());
  Eigen::MatrixXd out(total * n, stacked.cols());
  Eigen::Index row = 0;
  filter_segments(*this, stacked, [&](const Segment& g, const RowMatrix& x) {
    for (std::size_t k = 0; k < g.keep.size(); ++k) {
      for (Eigen::Index c = 0; c < stacked.cols(); ++c) {
        for (Eigen::Index i = 0; i < n; ++i)
          out((row + static_cast<Eigen::Index>(k)) * n + i, c) = x(g.keep[k], c * n + i);
      }
    }
    row += static_cast<Eigen::Index>(g.keep.size());
  });
  return out;
}

Eigen::MatrixXd Dataset::prefilter(const Eigen::MatrixXd& stacked) const {
  Eigen::MatrixXd out(stacked.rows(), stacked.cols());
  filter_segments(*this, stacked, [&](const Segment& g, const RowMatrix& x) {
    for (Eigen::Index s = 0; s < g.end - g.begin; ++s) {
      for (Eigen::Index c = 0; c < stacked.cols(); ++c) {
        for (Eigen::Index i = 0; i < n; ++i) out((g.begin + s) * n + i, c) = x(s, c * n + i);
      }
    }
  });
  return out;
}

Eigen::VectorXd velocity_error(const Dataset& d) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(d.n);
  for (Eigen::Index j = 0; j < d.n; ++j) {
    double position_error = 0;
    for (const Audit& a : d.audits) {
      const JointAudit& ja = a.joints[static_cast<std::size_t>(j)];
      position_error = std::max(position_error, std::hypot(ja.position_noise, ja.quantum / std::sqrt(12.0)));
    }
    out[j] = 2 * std::numbers::pi * d.cutoff * position_error;
  }
  return out;
}

Eigen::VectorXd friction_sign_velocity(const Dataset& d) { return velocity_error(d).cwiseMax(kSignVelocity); }

Eigen::VectorXd away_from_zero_velocity(const Dataset& d, double leak) {
  const Eigen::VectorXd band = (2.0 * velocity_error(d)).cwiseMax(kTurnOverBand);
  Eigen::MatrixXd near_zero = Eigen::MatrixXd::Zero(d.samples() * d.n, 1);
  for (Eigen::Index s = 0; s < d.samples(); ++s) {
    for (Eigen::Index j = 0; j < d.n; ++j) near_zero(s * d.n + j, 0) = std::abs(d.qd(s, j)) < band[j] ? 1.0 : 0.0;
  }
  // Both passes: the band spreads into the residual as the friction's sign does.
  const Eigen::VectorXd spread = d.condition(d.prefilter(near_zero)).col(0);
  return (spread.array().abs() <= leak).cast<double>().matrix();
}

Eigen::VectorXd torque_weights(const Eigen::VectorXd& torque_rms) {
  return torque_rms.cwiseMax(1e-3 * torque_rms.maxCoeff() + 1e-12).cwiseInverse();
}

Eigen::VectorXd stacked_weights(const Eigen::VectorXd& joint_weights, Eigen::Index rows) {
  Eigen::VectorXd w(rows);
  for (Eigen::Index r = 0; r < rows; ++r) w[r] = joint_weights[r % joint_weights.size()];
  return w;
}

Eigen::VectorXd analysis_torque_rms(const Dataset& d) {
  return d.analysis_tau.array().square().colwise().mean().sqrt().transpose();
}

Dataset build_dataset(const std::vector<JointLog>& logs, const pipeline::Derivation& derivation,
                      const ConditioningOptions& options) {
  Dataset d;
  d.n = static_cast<Eigen::Index>(derivation.robot.coordinates.size());
  double lowest_rate = 1e300;
  for (const JointLog& log : logs) {
    d.audits.push_back(audit_log(log));
    d.logs.push_back(log.path);
    lowest_rate = std::min(lowest_rate, d.audits.back().rate);
  }
  d.cutoff = options.cutoff > 0 ? options.cutoff : std::min(lowest_rate / 8.0, kMaxCutoff);
  d.held_torque = options.held_torque;

  std::vector<Conditioned> parts;
  Eigen::Index total = 0;
  for (std::size_t l = 0; l < logs.size(); ++l) {
    parts.push_back(condition_log(logs[l], d.audits[l], d.cutoff, options.held_torque));
    const Conditioned& c = parts.back();
    Dataset::Segment g;
    g.begin = total;
    g.end = total + c.t.size();
    g.rate = c.rate;
    const auto trim = static_cast<Eigen::Index>(kEdgeTrimPeriods * c.rate / d.cutoff);
    const auto stride = std::max<Eigen::Index>(1, static_cast<Eigen::Index>(c.rate / (kRowsPerCutoff * d.cutoff)));
    for (Eigen::Index i = trim; i < c.t.size() - trim; i += stride) g.keep.push_back(i);
    if (static_cast<Eigen::Index>(g.keep.size()) < kMinimumSamples) {
      throw LogError(
          fmt::format("{}: error: {:.1f} s at {:.0f} Hz leaves {} rows after filtering at {:.2f} Hz; the "
                      "diagnosis needs at least {}",
                      logs[l].path, d.audits[l].duration, d.audits[l].rate, g.keep.size(), d.cutoff, kMinimumSamples));
    }
    d.step = std::max(d.step, static_cast<double>(stride) / c.rate);
    d.segments.push_back(g);
    total += c.t.size();
  }
  const Eigen::Index n = d.n;
  d.t.resize(total);
  d.q.resize(total, n);
  d.q_sharp.resize(total, n);
  d.qd.resize(total, n);
  d.qdd.resize(total, n);
  d.tau.resize(total, n);
  d.model_tau.resize(total, n);
  d.model_friction.resize(total, n);
  d.model_tau_rate.resize(total, n);
  const dyn::NumericModel& model = *derivation.numeric;
  const Eigen::VectorXd nominal = model.nominal_standard_values();
  // The description's Coulomb friction per joint (friction at unit rate and zero reference
  // velocity), to replace its sign by the smoothed one.
  const Eigen::VectorXd coulomb = model
                                      .evaluate({Eigen::VectorXd::Zero(n), Eigen::VectorXd::Ones(n),
                                                 Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n)},
                                                nominal, false)
                                      .friction;
  const auto p = static_cast<Eigen::Index>(model.parameter_count());
  d.standard.resize(total * n, p);

  const auto& base = derivation.base;
  std::vector<int> rigid_columns;
  for (const auto& parameter : base.list) {
    const auto kind = derivation.model.params.list[static_cast<std::size_t>(parameter.kept)].kind;
    if (kind == dyn::StandardKind::FC || kind == dyn::StandardKind::FV) continue;  // friction is an effect of its own
    rigid_columns.push_back(parameter.kept);
    d.base_rigid_names.push_back(parameter.name);
  }
  d.base_rigid.resize(total * n, static_cast<Eigen::Index>(rigid_columns.size()));

  Eigen::Index row = 0;
  for (std::size_t l = 0; l < parts.size(); ++l) {
    const Conditioned& c = parts[l];
    for (Eigen::Index chunk = 0; chunk < c.t.size(); chunk += kModelRowsPerBatch) {
      // The model at a batch of rows, and at each row's positions moved by +-step, one joint at a
      // time: state (1 + 2 j) and (2 + 2 j) of row k are states[k * (1 + 2 n) + ...].
      const Eigen::Index rows = std::min(kModelRowsPerBatch, c.t.size() - chunk);
      std::vector<dyn::State> states, moved;
      for (Eigen::Index s = chunk; s < chunk + rows; ++s) {
        const dyn::State state{c.q.row(s).transpose(), c.qd.row(s).transpose(), c.qd.row(s).transpose(),
                               c.qdd.row(s).transpose()};
        states.push_back(state);
        for (Eigen::Index j = 0; j < n; ++j) {
          dyn::State plus = state, minus = state;
          plus.q[j] += kSensitivityStep;
          minus.q[j] -= kSensitivityStep;
          moved.push_back(std::move(plus));
          moved.push_back(std::move(minus));
        }
      }
      const std::vector<dyn::Evaluation> at = model.evaluate(states, nominal);
      const std::vector<dyn::Evaluation> at_moved = model.evaluate(moved, nominal, false);
      for (Eigen::Index s = chunk; s < chunk + rows; ++s, ++row) {
        const auto k = static_cast<std::size_t>(s - chunk);
        d.t[row] = c.t[s];
        d.log_of.push_back(static_cast<int>(l));
        d.q.row(row) = c.q.row(s);
        d.q_sharp.row(row) = c.q_sharp.row(s);
        d.qd.row(row) = c.qd.row(s);
        d.qdd.row(row) = c.qdd.row(s);
        d.tau.row(row) = c.tau.row(s);
        const dyn::Evaluation& e = at[k];
        for (Eigen::Index j = 0; j < n; ++j) {
          const double v = c.qd(s, j), sign = v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0);
          d.model_friction(row, j) = e.friction[j] + coulomb[j] * (smooth_sign(v) - sign);
          d.model_tau(row, j) = e.tau[j] + coulomb[j] * (smooth_sign(v) - sign);
        }
        d.standard.middleRows(row * n, n) = e.Y;
        for (std::size_t b = 0; b < rigid_columns.size(); ++b) {
          d.base_rigid.block(row * n, static_cast<Eigen::Index>(b), n, 1) = e.Y.col(rigid_columns[b]);
        }
        Eigen::MatrixXd sensitivity(n, n);
        for (Eigen::Index j = 0; j < n; ++j) {
          const std::size_t plus = k * static_cast<std::size_t>(2 * n) + static_cast<std::size_t>(2 * j);
          sensitivity.col(j) = (at_moved[plus].tau - at_moved[plus + 1].tau) / (2 * kSensitivityStep);
        }
        d.dtau_dq.push_back(sensitivity);
      }
    }
  }

  auto stack = [&](const Eigen::MatrixXd& m) {
    Eigen::MatrixXd out(m.rows() * n, 1);
    for (Eigen::Index s = 0; s < m.rows(); ++s) out.block(s * n, 0, n, 1) = m.row(s).transpose();
    return out;
  };
  auto unstack = [&](const Eigen::MatrixXd& v) {
    Eigen::MatrixXd out(v.rows() / n, n);
    for (Eigen::Index s = 0; s < out.rows(); ++s) out.row(s) = v.block(s * n, 0, n, 1).transpose();
    return out;
  };
  // The model's first pass (see Dataset::prefilter): its rigid-body torque had it in the
  // positions; its friction, sharp at each reversal, gets it here.
  const Eigen::MatrixXd rigid = d.model_tau - d.model_friction;
  d.model_tau = rigid + unstack(d.prefilter(stack(d.model_friction)));
  for (const Dataset::Segment& g : d.segments) {
    for (Eigen::Index j = 0; j < n; ++j) {
      d.model_tau_rate.block(g.begin, j, g.end - g.begin, 1) =
          derivative(d.model_tau.block(g.begin, j, g.end - g.begin, 1), 1.0 / g.rate);
    }
  }

  // The analysis rows: logged and model torque through the same two passes.
  d.analysis_tau = unstack(d.condition(stack(d.tau)));
  d.analysis_qd = unstack(d.condition(stack(d.qd)));
  d.analysis_qdd = unstack(d.condition(stack(d.qdd)));
  d.residual = d.condition(d.prefilter(stack(d.tau)) - stack(d.model_tau)).col(0);
  for (const Dataset::Segment& g : d.segments) {
    for (const Eigen::Index k : g.keep) {
      d.analysis_log.push_back(d.log_of[static_cast<std::size_t>(g.begin + k)]);
    }
  }
  d.analysis_t.resize(static_cast<Eigen::Index>(d.analysis_log.size()));
  Eigen::Index a = 0;
  for (const Dataset::Segment& g : d.segments) {
    for (const Eigen::Index k : g.keep) d.analysis_t[a++] = d.t[g.begin + k];
  }
  d.position_noise_torque = position_noise_torque(logs, d, model, nominal, rigid);
  return d;
}

}  // namespace dyncc::diagnose
