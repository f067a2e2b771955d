#include "diagnose/report_figures.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "diagnose/signal_analysis.hpp"
#include "diagnose/velocity_curve.hpp"

namespace dyncc::diagnose {
namespace {

// A scatter of more samples than this is thinned evenly: beyond it the dots only cover each
// other and the SVG grows.
constexpr Eigen::Index kMaxScatter = 4000;
constexpr int kCurvePoints = 241;
constexpr double kStepHalfWidth = 0.3;  // of a stage in the waterfall, in stages
constexpr int kJointPanelHeight = 190;

struct Rows {
  Eigen::Index begin = 0, end = 0;  // analysis rows of one log
};

Rows analysis_rows(const Dataset& d, int log) {
  const auto first = std::find(d.analysis_log.begin(), d.analysis_log.end(), log);
  const auto last = std::find_if(first, d.analysis_log.end(), [log](int l) { return l != log; });
  return {first - d.analysis_log.begin(), last - d.analysis_log.begin()};
}

// Analysis rows of one log are evenly spaced (every stride-th evaluation row).
double analysis_rate(const Dataset& d, const Rows& rows) {
  const Eigen::Index count = rows.end - rows.begin;
  if (count < 2) return 0;
  return static_cast<double>(count - 1) / (d.analysis_t[rows.end - 1] - d.analysis_t[rows.begin]);
}

// Joint j's rows of a stacked (row s*n + j) vector, over samples [begin, end).
Eigen::VectorXd joint_part(const Eigen::VectorXd& stacked, Eigen::Index n, Eigen::Index j, const Rows& rows) {
  Eigen::VectorXd out(rows.end - rows.begin);
  for (Eigen::Index s = rows.begin; s < rows.end; ++s) out[s - rows.begin] = stacked[s * n + j];
  return out;
}

std::vector<double> to_vector(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

// "nominal", or "nominal, log 2" when there are several logs.
std::string labelled(const std::string& what, const Dataset& d, std::size_t log) {
  return d.logs.size() > 1 ? fmt::format("{}, log {}", what, log + 1) : what;
}

plot::Figure joint_figure(const Dataset& d, const std::string& title, const std::string& x_label,
                          const std::string& y_label) {
  plot::Figure f;
  f.title = title;
  f.x_label = x_label;
  f.panel_height = kJointPanelHeight;
  for (Eigen::Index j = 0; j < d.n; ++j) {
    plot::Panel p;
    p.title = fmt::format("joint {}", j + 1);
    p.y_label = y_label;
    f.panels.push_back(std::move(p));
  }
  return f;
}

}  // namespace

plot::Figure velocity_figure(const Dataset& d, const SelectedResiduals& residuals) {
  plot::Figure f =
      joint_figure(d, "Residual against velocity, with the fitted friction", "velocity (rad/s or m/s)", "N m");
  // What the friction curves claim to explain: the residual less every other selected effect.
  Eigen::VectorXd partial = residuals.nominal;
  bool others = false;
  for (const EffectFit& e : residuals.effects) {
    if (has_velocity_curve(e.effect)) continue;
    partial -= e.contribution;
    others = true;
  }
  const Eigen::Index rows = d.rows();
  const Eigen::Index stride = std::max<Eigen::Index>(1, (rows + kMaxScatter - 1) / kMaxScatter);
  for (Eigen::Index j = 0; j < d.n; ++j) {
    plot::Series scatter;
    scatter.label = others ? "residual less the other selected effects" : "residual";
    scatter.markers = true;
    for (Eigen::Index s = 0; s < rows; s += stride) {
      scatter.x.push_back(d.analysis_qd(s, j));
      scatter.y.push_back(partial[s * d.n + j]);
    }
    plot::Panel& panel = f.panels[static_cast<std::size_t>(j)];
    panel.series.push_back(std::move(scatter));

    std::vector<const EffectFit*> curves;
    std::string names;
    for (const EffectFit& e : residuals.effects) {
      const bool here = std::find(e.joints.begin(), e.joints.end(), static_cast<int>(j) + 1) != e.joints.end();
      if (!has_velocity_curve(e.effect) || !here) continue;
      curves.push_back(&e);
      names += (names.empty() ? "" : " + ") + e.effect;
    }
    if (curves.empty() || rows == 0) continue;
    plot::Series line;
    line.label = "fitted " + names;
    const double lo = d.analysis_qd.col(j).minCoeff(), hi = d.analysis_qd.col(j).maxCoeff();
    for (int i = 0; i < kCurvePoints; ++i) {
      const double v = lo + (hi - lo) * i / (kCurvePoints - 1);
      double torque = 0;
      for (const EffectFit* e : curves) torque += velocity_curve(*e, j, v);
      line.x.push_back(v);
      line.y.push_back(torque);
    }
    panel.series.push_back(std::move(line));
  }
  return f;
}

plot::Figure spectrum_figure(const Dataset& d, const SelectedResiduals& residuals) {
  plot::Figure f = joint_figure(d, "Amplitude spectrum of the residual", "frequency (Hz)", "N m");
  const double top = 2 * d.cutoff;
  for (std::size_t l = 0; l < d.logs.size(); ++l) {
    const Rows rows = analysis_rows(d, static_cast<int>(l));
    const double rate = analysis_rate(d, rows);
    for (Eigen::Index j = 0; j < d.n; ++j) {
      std::vector<std::pair<std::string, const Eigen::VectorXd*>> signals{{"nominal", &residuals.nominal}};
      if (!residuals.effects.empty()) signals.emplace_back("after selected", &residuals.heldout);
      for (const auto& [what, stacked] : signals) {
        const Spectrum s = amplitude_spectrum(joint_part(*stacked, d.n, j, rows), rate);
        plot::Series series;
        series.label = labelled(what, d, l);
        for (Eigen::Index k = 0; k < s.frequency.size() && s.frequency[k] <= top; ++k) {
          series.x.push_back(s.frequency[k]);
          series.y.push_back(s.amplitude[k]);
        }
        f.panels[static_cast<std::size_t>(j)].series.push_back(std::move(series));
      }
    }
  }
  return f;
}

plot::Figure correlation_figure(const Dataset& d) {
  plot::Figure f = joint_figure(d, "Cross-correlation with the logged torque", "lag (s)", "correlation");
  for (std::size_t l = 0; l < d.segments.size(); ++l) {
    const Dataset::Segment& g = d.segments[l];
    // The rows the analysis keeps: the filter's start-up transient at either end left out.
    const Eigen::Index begin = g.begin + g.keep.front(), count = g.keep.back() - g.keep.front() + 1;
    for (Eigen::Index j = 0; j < d.n; ++j) {
      const Eigen::VectorXd logged = d.tau.col(j).segment(begin, count);
      const Eigen::VectorXd model = d.model_tau.col(j).segment(begin, count);
      const Correlation delay = cross_correlation(logged, model, g.rate, kCorrelationLag);
      const Correlation residual = cross_correlation(logged - model, logged, g.rate, kCorrelationLag);
      plot::Panel& panel = f.panels[static_cast<std::size_t>(j)];
      if (l == 0) {
        // Rounded first, so that a lag of a few microseconds reads +0 rather than -0.
        const double ms = std::round(1e3 * peak_lag(delay));
        panel.title = fmt::format("joint {} (logged vs model torque peaks at {:+.0f} ms)", j + 1, ms == 0 ? 0.0 : ms);
      }
      panel.series.push_back({labelled("logged vs model torque", d, l), to_vector(delay.lag), to_vector(delay.value)});
      plot::Series r{labelled("residual vs logged torque", d, l), to_vector(residual.lag), to_vector(residual.value)};
      r.dashed = true;
      panel.series.push_back(std::move(r));
    }
  }
  return f;
}

plot::Figure residual_figure(const Dataset& d, const Diagnosis& diagnosis, const SelectedResiduals& residuals,
                             int log) {
  plot::Figure f =
      joint_figure(d,
                   d.logs.size() > 1 ? fmt::format("Residual over time, log {} (shaded: flagged windows)", log + 1)
                                     : std::string("Residual over time (shaded: flagged windows)"),
                   "time (s)", "N m");
  const Rows rows = analysis_rows(d, log);
  std::vector<std::pair<double, double>> shaded;
  for (const Window& w : diagnosis.gap.windows) {
    if (w.log == log) shaded.emplace_back(w.start, w.end);
  }
  const std::vector<double> t = to_vector(d.analysis_t.segment(rows.begin, rows.end - rows.begin));
  for (Eigen::Index j = 0; j < d.n; ++j) {
    plot::Panel& panel = f.panels[static_cast<std::size_t>(j)];
    panel.shaded = shaded;
    panel.series.push_back({"nominal", t, to_vector(joint_part(residuals.nominal, d.n, j, rows))});
    if (!residuals.effects.empty()) {
      panel.series.push_back({"after selected", t, to_vector(joint_part(residuals.heldout, d.n, j, rows))});
    }
  }
  return f;
}

plot::Figure waterfall_figure(const Dataset& d, const Diagnosis& diagnosis) {
  plot::Figure f;
  f.title = "Held-out gap after each selected effect";
  f.x_label = "";
  f.x_ticks.emplace_back(0, "nominal");
  for (std::size_t k = 0; k < diagnosis.selected.size(); ++k) {
    f.x_ticks.emplace_back(static_cast<double>(k + 1), "+ " + diagnosis.selected[k].effect);
  }
  const auto stages = static_cast<double>(diagnosis.selected.size());
  // A step line: each stage a level over its tick, joined to the next stage's level.
  auto steps = [](const std::string& label, const std::vector<double>& levels) {
    plot::Series s;
    s.label = label;
    for (std::size_t k = 0; k < levels.size(); ++k) {
      for (const double side : {-kStepHalfWidth, kStepHalfWidth}) {
        s.x.push_back(static_cast<double>(k) + side);
        s.y.push_back(levels[k]);
      }
    }
    return s;
  };

  // Each selected effect's shrink is of the weighted squared error left by the ones before it,
  // so the RMS left after k effects is the product of the square roots.
  plot::Panel all;
  all.title = "all joints (torque-weighted)";
  all.y_label = "% of nominal";
  std::vector<double> weighted{100};
  for (const RankedEffect& r : diagnosis.selected)
    weighted.push_back(weighted.back() * std::sqrt(std::max(0.0, 1 - r.shrink)));
  all.series.push_back(steps("held-out RMS", weighted));
  const double alone = 100 * std::sqrt(std::max(0.0, 1 - diagnosis.within_model.shrink));
  plot::Series reference{"inertial_parameters alone", {-kStepHalfWidth, stages + kStepHalfWidth}, {alone, alone}};
  reference.dashed = true;
  all.series.push_back(std::move(reference));

  plot::Panel joints;
  joints.title = "per joint";
  joints.y_label = "% of torque RMS";
  for (Eigen::Index j = 0; j < d.n; ++j) {
    const double scale = 100 / std::max(diagnosis.gap.torque_rms[j], 1e-12);
    std::vector<double> levels{scale * diagnosis.gap.residual_rms[j]};
    for (const RankedEffect& r : diagnosis.selected) levels.push_back(scale * r.after[j]);
    // The last stage is the joint refit of every selected effect, what the diagnosis reports.
    if (diagnosis.final_after.size() == d.n) levels.back() = scale * diagnosis.final_after[j];
    joints.series.push_back(steps(fmt::format("joint {}", j + 1), levels));
  }
  f.panels = {std::move(all), std::move(joints)};
  return f;
}

}  // namespace dyncc::diagnose
