// The numbers behind the diagnosis report's figures, checked against what was put into the log:
// the spectrum of a sinusoid peaks at its frequency with its amplitude, a delayed copy correlates
// best at the delay, a sensor delay in a log shows as the lag of the torque correlation, the
// fitted Coulomb curve reaches the injected size at either end of the velocity range (and is the
// same shape as the effect's columns), the waterfall and the residual series agree with the
// diagnosis's own numbers, a disturbance at a known frequency stands out in the residual
// spectrum, flagged windows are the shaded ones; and `dyncc diagnose --out` writes a page whose
// figures are all in its folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "diagnose/crossval.hpp"
#include "diagnose/dataset.hpp"
#include "diagnose/diagnosis.hpp"
#include "diagnose/diagnosis_output.hpp"
#include "diagnose/effects.hpp"
#include "diagnose/report_figures.hpp"
#include "diagnose/residuals.hpp"
#include "diagnose/signal_analysis.hpp"
#include "diagnose/synthetic_log.hpp"
#include "diagnose/velocity_curve.hpp"
#include "dynamics_support.hpp"
#include "temp_path.hpp"

namespace dyncc::test {
namespace {

using diagnose::Injection;

std::filesystem::path temp_file(const std::string& name) { return temp_path(name + ".csv"); }

diagnose::JointLog synthetic_log(const std::vector<Injection>& effects, const std::string& name) {
  const auto path = temp_file(name);
  diagnose::write_synthetic_log(kraft_derivation(), effects, diagnose::SyntheticOptions{}, path);
  diagnose::JointLog log = diagnose::read_joint_log(path.string(), 3);
  std::filesystem::remove(path);
  return log;
}

Injection injection(const char* effect, int joint, double size) {
  Injection i;
  i.effect = effect;
  i.joint = joint;
  i.size = size;
  return i;
}

struct Diagnosed {
  diagnose::Dataset data;
  diagnose::Diagnosis diagnosis;
  diagnose::SelectedResiduals residuals;
};

Diagnosed diagnosed(const diagnose::JointLog& log) {
  Diagnosed out;
  out.data = diagnose::build_dataset({log}, kraft_derivation());
  out.diagnosis = diagnose::diagnose(out.data, kraft_derivation());
  out.residuals = diagnose::selected_residuals(out.data, out.diagnosis);
  return out;
}

// Coulomb friction of 0.15 N m on joint 2 (as in diagnose_effect_test.cpp), diagnosed once.
const Diagnosed& coulomb() {
  static const Diagnosed d = diagnosed(synthetic_log({injection("coulomb_friction", 1, 0.15)}, "coulomb"));
  return d;
}

const plot::Series* find_series(const plot::Panel& panel, const std::string& prefix) {
  for (const plot::Series& s : panel.series) {
    if (s.label.rfind(prefix, 0) == 0) return &s;
  }
  return nullptr;
}

diagnose::Correlation as_correlation(const plot::Series& s) {
  diagnose::Correlation c;
  c.lag = Eigen::Map<const Eigen::VectorXd>(s.x.data(), static_cast<Eigen::Index>(s.x.size()));
  c.value = Eigen::Map<const Eigen::VectorXd>(s.y.data(), static_cast<Eigen::Index>(s.y.size()));
  return c;
}

double rms(const std::vector<double>& v) {
  double sum = 0;
  for (const double x : v) sum += x * x;
  return std::sqrt(sum / static_cast<double>(v.size()));
}

TEST(SignalAnalysis, SpectrumOfASinusoidPeaksAtItsFrequencyWithItsAmplitude) {
  const double rate = 40, frequency = 3.3, amplitude = 0.7;  // 3.3 Hz is not on a bin of 30 s
  Eigen::VectorXd x(1200);
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    x[i] = 0.3 + amplitude * std::sin(2 * std::numbers::pi * frequency * static_cast<double>(i) / rate + 0.4);
  }
  const diagnose::Spectrum s = diagnose::amplitude_spectrum(x, rate);
  ASSERT_GT(s.frequency.size(), 2);
  EXPECT_DOUBLE_EQ(s.frequency[0], 0);
  EXPECT_NEAR(s.frequency[s.frequency.size() - 1], rate / 2, 1e-12) << "up to Nyquist";
  Eigen::Index peak = 0;
  s.amplitude.maxCoeff(&peak);
  const double bin = s.frequency[1] - s.frequency[0];
  EXPECT_NEAR(s.frequency[peak], frequency, bin);
  EXPECT_NEAR(s.amplitude[peak], amplitude, 0.02 * amplitude);
  EXPECT_LT(s.amplitude[0], 1e-3) << "the mean is removed";
  // Away from the line the window leaks (almost) nothing.
  for (Eigen::Index k = 0; k < s.frequency.size(); ++k) {
    if (std::abs(s.frequency[k] - frequency) > 1.0) {
      EXPECT_LT(s.amplitude[k], 1e-3 * amplitude) << s.frequency[k];
    }
  }
}

TEST(SignalAnalysis, DelayedCopyCorrelatesBestAtTheDelay) {
  const double rate = 200;
  std::mt19937 random(3);
  std::uniform_real_distribution<double> phase(0, 2 * std::numbers::pi);
  std::vector<std::pair<double, double>> waves;  // frequency, phase: a band-limited random signal
  for (int k = 1; k <= 8; ++k) waves.emplace_back(0.3 * k, phase(random));
  auto signal = [&](double t) {
    double sum = 0;
    for (const auto& [f, p] : waves) sum += std::sin(2 * std::numbers::pi * f * t + p) / f;
    return sum;
  };
  for (const double delay : {0.037, -0.021, 0.0}) {
    Eigen::VectorXd a(4000), b(4000);
    for (Eigen::Index i = 0; i < a.size(); ++i) {
      const double t = static_cast<double>(i) / rate;
      a[i] = signal(t);
      b[i] = 2.0 * signal(t - delay) + 5.0;  // scale and offset do not matter to a correlation
    }
    const diagnose::Correlation c = diagnose::cross_correlation(a, b, rate, 0.2);
    ASSERT_EQ(c.lag.size(), 81);
    EXPECT_NEAR(c.lag[0], -0.2, 1e-12);
    EXPECT_NEAR(c.lag[80], 0.2, 1e-12);
    EXPECT_NEAR(diagnose::peak_lag(c), delay, 0.5e-3) << "within a tenth of a sample";
    EXPECT_NEAR(c.value.maxCoeff(), 1.0, 1e-3);
  }
}

TEST(DiagnoseReport, SensorDelayIsTheLagOfTheTorqueCorrelation) {
  for (const double delay : {0.03, 0.0}) {
    const std::vector<Injection> effects =
        delay > 0 ? std::vector<Injection>{injection("sensor_delay", 0, delay)} : std::vector<Injection>{};
    const diagnose::Dataset data =
        diagnose::build_dataset({synthetic_log(effects, delay > 0 ? "delay" : "clean")}, kraft_derivation());
    const plot::Figure f = diagnose::correlation_figure(data);
    ASSERT_EQ(f.panels.size(), 3U);
    for (std::size_t j = 0; j < 3; ++j) {
      SCOPED_TRACE("joint " + std::to_string(j + 1) + ", delay " + std::to_string(delay));
      const plot::Series* torque = find_series(f.panels[j], "logged vs model torque");
      const plot::Series* residual = find_series(f.panels[j], "residual vs logged torque");
      ASSERT_NE(torque, nullptr);
      ASSERT_NE(residual, nullptr);
      EXPECT_NEAR(torque->x.front(), -diagnose::kCorrelationLag, 1e-9);
      EXPECT_NEAR(torque->x.back(), diagnose::kCorrelationLag, 1e-9);
      // The evaluation rows are 10 ms apart; the parabola finds the delay well within one.
      EXPECT_NEAR(diagnose::peak_lag(as_correlation(*torque)), delay, 0.004);
      if (delay == 0) continue;
      // The residual is the torque's rate times the delay: uncorrelated with the torque at lag 0,
      // correlated off it.
      const std::size_t zero = residual->x.size() / 2;
      ASSERT_NEAR(residual->x[zero], 0, 1e-9);
      double largest = 0, where = 0;
      for (std::size_t k = 0; k < residual->y.size(); ++k) {
        if (std::abs(residual->y[k]) > largest) {
          largest = std::abs(residual->y[k]);
          where = residual->x[k];
        }
      }
      EXPECT_LT(std::abs(residual->y[zero]), 0.3 * largest);
      EXPECT_GT(std::abs(where), 0.1);
    }
  }
}

void expect_refit_reproduces_the_selection(const Diagnosed& c) {
  ASSERT_FALSE(c.diagnosis.selected.empty()) << "the injected effect is found";
  ASSERT_EQ(c.residuals.effects.size(), c.diagnosis.selected.size());
  const Eigen::VectorXd after = diagnose::joint_rms(c.residuals.heldout, 3);
  for (Eigen::Index j = 0; j < 3; ++j) EXPECT_NEAR(after[j], c.diagnosis.final_after[j], 1e-9 * after[j]) << j;
  EXPECT_EQ(c.residuals.nominal, c.data.residual);
  // The fitted parts add up to what the fit on all rows removes: less than the residual itself.
  Eigen::VectorXd fitted = Eigen::VectorXd::Zero(c.data.residual.size());
  for (const diagnose::EffectFit& e : c.residuals.effects) fitted += e.contribution;
  EXPECT_LT((c.data.residual - fitted).norm(), 0.5 * c.data.residual.norm());
}

TEST(DiagnoseReport, RefitReproducesTheDiagnosisHeldOutGap) {
  expect_refit_reproduces_the_selection(coulomb());
  // A contact's profile point is reported by its surface height alone, which candidates at
  // different points on the link may share (six do on the Kraft arm): the refit must still fit
  // the one selected.
  expect_refit_reproduces_the_selection(diagnosed(synthetic_log({injection("contact", 0, 20.0)}, "contact")));
}

TEST(DiagnoseReport, FittedCoulombCurveReachesTheInjectedSize) {
  const Diagnosed& c = coulomb();
  const plot::Figure f = diagnose::velocity_figure(c.data, c.residuals);
  ASSERT_EQ(f.panels.size(), 3U);
  const plot::Series* scatter = find_series(f.panels[1], "residual");
  ASSERT_NE(scatter, nullptr);
  EXPECT_TRUE(scatter->markers);
  EXPECT_EQ(scatter->x.size(), static_cast<std::size_t>(c.data.rows()));
  const plot::Series* curve = find_series(f.panels[1], "fitted coulomb_friction");
  ASSERT_NE(curve, nullptr) << "joint 2 carries the fitted Coulomb curve";
  EXPECT_FALSE(curve->markers);
  // At either end of the velocity range the smoothed sign is saturated: the curve is -fc and +fc.
  EXPECT_LT(curve->x.front(), -0.1);
  EXPECT_GT(curve->x.back(), 0.1);
  EXPECT_NEAR(curve->y.front(), -0.15, 0.015);
  EXPECT_NEAR(curve->y.back(), 0.15, 0.015);
  // The residual follows the curve: at speed, its mean on either side is the curve's level.
  double plus = 0, minus = 0;
  int n_plus = 0, n_minus = 0;
  for (std::size_t i = 0; i < scatter->x.size(); ++i) {
    if (scatter->x[i] > 0.2) {
      plus += scatter->y[i];
      ++n_plus;
    }
    if (scatter->x[i] < -0.2) {
      minus += scatter->y[i];
      ++n_minus;
    }
  }
  ASSERT_GT(n_plus, 50);
  ASSERT_GT(n_minus, 50);
  EXPECT_NEAR(plus / n_plus, 0.15, 0.03);
  EXPECT_NEAR(minus / n_minus, -0.15, 0.03);
}

TEST(DiagnoseReport, VelocityCurveIsTheShapeOfTheEffectsColumns) {
  // The curve at the evaluation rows' velocities, through the dataset's filter (both passes for a
  // sharp one), is the fitted part of the residual the refit computed from the effect's own columns.
  const Diagnosed& c = coulomb();
  for (const diagnose::EffectFit& fit : c.residuals.effects) {
    if (!diagnose::has_velocity_curve(fit.effect)) continue;
    const Eigen::Index n = c.data.n;
    Eigen::MatrixXd stacked(c.data.samples() * n, 1);
    for (Eigen::Index s = 0; s < c.data.samples(); ++s) {
      for (Eigen::Index j = 0; j < n; ++j) stacked(s * n + j, 0) = diagnose::velocity_curve(fit, j, c.data.qd(s, j));
    }
    const Eigen::VectorXd conditioned = diagnose::conditioned_columns(c.data, fit.effect, stacked).col(0);
    EXPECT_LT((conditioned - fit.contribution).norm(), 1e-9 * fit.contribution.norm()) << fit.effect;
  }
  // And a Stribeck fit: Coulomb plus the excess fading over its scale.
  diagnose::EffectFit stribeck;
  stribeck.effect = "stribeck_friction";
  stribeck.parameters = {"fc1", "fs1"};
  stribeck.joint_of = {0, 0};
  stribeck.values = Eigen::Vector2d(0.2, 0.1);
  stribeck.profile = 0.1;
  EXPECT_NEAR(diagnose::velocity_curve(stribeck, 0, 1.0), 0.2, 1e-9) << "far beyond the scale: Coulomb only";
  EXPECT_NEAR(diagnose::velocity_curve(stribeck, 0, -0.05), -(0.2 + 0.1 * std::exp(-0.25)), 1e-6);
  EXPECT_EQ(diagnose::velocity_curve(stribeck, 1, 0.05), 0) << "another joint";
}

TEST(DiagnoseReport, WaterfallStepsFromTheNominalGapThroughEachSelectedEffect) {
  const Diagnosed& c = coulomb();
  const diagnose::Diagnosis& d = c.diagnosis;
  const plot::Figure f = diagnose::waterfall_figure(c.data, d);
  ASSERT_EQ(f.x_ticks.size(), d.selected.size() + 1);
  EXPECT_EQ(f.x_ticks.front().second, "nominal");
  EXPECT_EQ(f.x_ticks[1].second, "+ " + d.selected.front().effect);
  ASSERT_EQ(f.panels.size(), 2U);
  const plot::Series* weighted = find_series(f.panels[0], "held-out RMS");
  ASSERT_NE(weighted, nullptr);
  ASSERT_EQ(weighted->y.size(), 2 * (d.selected.size() + 1)) << "two points per stage";
  EXPECT_DOUBLE_EQ(weighted->y.front(), 100);
  EXPECT_NEAR(weighted->y[2], 100 * std::sqrt(1 - d.selected.front().shrink), 1e-9);
  EXPECT_LT(weighted->y.back(), 100 * std::sqrt(0.5)) << "the effect removes over half the squared error";
  for (Eigen::Index j = 0; j < 3; ++j) {
    const plot::Series* joint = find_series(f.panels[1], "joint " + std::to_string(j + 1));
    ASSERT_NE(joint, nullptr);
    EXPECT_NEAR(joint->y.front(), d.gap.percent[j], 1e-9);
    EXPECT_NEAR(joint->y.back(), 100 * d.final_after[j] / d.gap.torque_rms[j], 1e-9);
  }
  // Joint 2 carries the friction: its gap falls most.
  const plot::Series* second = find_series(f.panels[1], "joint 2");
  EXPECT_LT(second->y.back(), 0.5 * second->y.front());
}

// A log with a disturbance the library does not know: a 1.5 Hz torque ripple on joint 3 and a
// bump on joint 1 between 20 and 24 s.
diagnose::JointLog disturbed_log() {
  diagnose::JointLog log = synthetic_log({}, "disturbed");
  for (Eigen::Index i = 0; i < log.samples(); ++i) {
    const double t = log.t[i];
    log.tau(i, 2) += 0.05 * std::sin(2 * std::numbers::pi * 1.5 * t);
    if (t > 20 && t < 24) log.tau(i, 0) += 0.3;
  }
  return log;
}

TEST(DiagnoseReport, DisturbanceStandsOutInTheSpectrumAndItsWindowIsShaded) {
  const Diagnosed d = diagnosed(disturbed_log());
  const plot::Figure spectrum = diagnose::spectrum_figure(d.data, d.residuals);
  const plot::Series* nominal = find_series(spectrum.panels[2], "nominal");
  ASSERT_NE(nominal, nullptr);
  EXPECT_LE(nominal->x.back(), 2 * d.data.cutoff + 1e-9);
  const auto peak = std::max_element(nominal->y.begin(), nominal->y.end()) - nominal->y.begin();
  EXPECT_NEAR(nominal->x[static_cast<std::size_t>(peak)], 1.5, 0.05);
  EXPECT_NEAR(nominal->y[static_cast<std::size_t>(peak)], 0.05, 0.01) << "through the filter, nearly unattenuated";

  const plot::Figure over_time = diagnose::residual_figure(d.data, d.diagnosis, d.residuals, 0);
  ASSERT_EQ(over_time.panels.size(), 3U);
  ASSERT_FALSE(d.diagnosis.gap.windows.empty()) << "the bump is flagged";
  bool bump_shaded = false;
  for (const plot::Panel& panel : over_time.panels) {
    ASSERT_EQ(panel.shaded.size(), d.diagnosis.gap.windows.size());
    for (std::size_t w = 0; w < panel.shaded.size(); ++w) {
      EXPECT_DOUBLE_EQ(panel.shaded[w].first, d.diagnosis.gap.windows[w].start);
      EXPECT_DOUBLE_EQ(panel.shaded[w].second, d.diagnosis.gap.windows[w].end);
      bump_shaded = bump_shaded || (panel.shaded[w].first < 23 && panel.shaded[w].second > 21);
    }
  }
  EXPECT_TRUE(bump_shaded);
  const plot::Series* joint1 = find_series(over_time.panels[0], "nominal");
  ASSERT_NE(joint1, nullptr);
  EXPECT_NEAR(rms(joint1->y), d.diagnosis.gap.residual_rms[0], 1e-9);
}

// An `unknown` verdict says why: the first step's best candidate and its interval, and, where
// the residual's flagged windows make one or two bursts of ten times the usual residual or more,
// that such an event cannot be tested on blocks held out in time (blind seed 647 case 12: one
// touch of a table at 0.5-2.5 s, 28.8 times the usual residual). Adjacent windows are one burst;
// bursts in many places, or small ones, are not events; a named effect needs no reason.
TEST(DiagnoseReport, AnUnknownVerdictSaysWhyAndPointsAtARareBurst) {
  diagnose::Diagnosis d;
  d.verdict.effect = "unknown";
  diagnose::RankedEffect best;
  best.effect = "contact";
  best.shrink = 0.001;
  best.shrink_low = -0.504;
  best.shrink_high = 0.506;
  d.ranking.push_back(best);
  d.gap.windows = {{0, 2.5, 4.4, 12.0}, {0, 0.5, 2.4, 28.8}};  // one burst over two windows
  const std::string one = diagnose::why_not_named(d);
  EXPECT_NE(one.find("contact, removes 0.1 % (95 % interval [-50.4, 50.6] %)"), std::string::npos) << one;
  EXPECT_NE(one.find("burst (0.5-4.4 s of log 1, 29x the usual residual) is an event"), std::string::npos) << one;

  d.gap.windows.push_back({0, 30.0, 31.9, 15.0});
  EXPECT_NE(diagnose::why_not_named(d).find("two bursts"), std::string::npos) << diagnose::why_not_named(d);
  d.gap.windows.push_back({0, 50.0, 51.9, 15.0});  // three places: a recurring effect, not an event
  EXPECT_EQ(diagnose::why_not_named(d).find("burst"), std::string::npos) << diagnose::why_not_named(d);
  d.gap.windows = {{0, 0.5, 2.4, 3.0}};  // three times the usual residual: structure, not an event
  EXPECT_EQ(diagnose::why_not_named(d).find("burst"), std::string::npos) << diagnose::why_not_named(d);

  d.verdict.effect = "contact";
  EXPECT_TRUE(diagnose::why_not_named(d).empty());
}

// Blind seed 853 case 9: a 10.4 g load beside an offset, each 5 % or less, below the friction
// sign's floor on every joint, so `none`; yet a load's columns removed 46.3 % held out, [9.8,
// 82.7] %, with an implausible fit. A `none` verdict says the gap is within its floors, and names
// a candidate that still removes part of it significantly, and why it was not named.
TEST(DiagnoseReport, ANoneVerdictSaysTheGapIsWithinItsFloorsAndNamesWhatStillExplainsPartOfIt) {
  diagnose::Diagnosis d;
  d.verdict.effect = "none";
  EXPECT_NE(diagnose::why_not_named(d).find("no joint's held-out gap is both above its floors"), std::string::npos)
      << diagnose::why_not_named(d);
  diagnose::RankedEffect best;
  best.effect = "payload";
  best.shrink = 0.463;
  best.shrink_low = 0.098;
  best.shrink_high = 0.827;
  best.plausible = false;
  d.ranking.push_back(best);
  const std::string why = diagnose::why_not_named(d);
  EXPECT_NE(why.find("yet payload removes 46.3 % of it held out (95 % interval [9.8, 82.7] %), not named because its "
                     "fit is implausible"),
            std::string::npos)
      << why;
  d.ranking.front().shrink = 0.04;  // less than an effect must remove: what such a gap is made of
  d.ranking.front().shrink_low = 0.01;
  EXPECT_EQ(diagnose::why_not_named(d).find("payload"), std::string::npos) << diagnose::why_not_named(d);
  d.ranking.front().shrink = 0.463;
  d.ranking.front().shrink_low = -0.02;  // not significant
  EXPECT_EQ(diagnose::why_not_named(d).find("payload"), std::string::npos) << diagnose::why_not_named(d);
}

TEST(DiagnoseReport, CommandWritesAPageWhoseFiguresAreBesideIt) {
  const auto log = output_path("log.csv");
  diagnose::write_synthetic_log(kraft_derivation(), {injection("coulomb_friction", 1, 0.15)},
                                diagnose::SyntheticOptions{}, log);
  const auto out = output_path("report");
  std::filesystem::remove_all(out);
  const DynccRun run =
      run_dyncc("diagnose " + quoted(robots_dir() / "kraft.yaml") + " " + quoted(log) + " --out " + quoted(out));
  ASSERT_EQ(run.exit_code, 0) << run.errors;
  for (const char* file : {"diagnosis.json", "summary.txt", "report.html"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(out / file)) << file;
  }
  const std::string html = read_text(out / "report.html");
  EXPECT_NE(html.find("Verdict: <b>coulomb_friction</b>"), std::string::npos);
  const std::regex image("<img src=\"([^\"]+)\"");
  std::vector<std::string> sources;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), image); it != std::sregex_iterator(); ++it) {
    sources.push_back((*it)[1].str());
  }
  EXPECT_EQ(sources.size(), 5U) << "waterfall, velocity, residual, spectrum, correlation";
  for (const std::string& source : sources) {
    SCOPED_TRACE(source);
    EXPECT_EQ(source.find('/'), std::string::npos) << "in the page's own folder";
    ASSERT_TRUE(std::filesystem::is_regular_file(out / source));
    EXPECT_GT(std::filesystem::file_size(out / source), 1000U);
    EXPECT_EQ(read_text(out / source).rfind("<?xml", 0), 0U) << "an SVG";
  }
}

}  // namespace
}  // namespace dyncc::test
