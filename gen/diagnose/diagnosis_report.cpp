#include "diagnose/diagnosis_report.hpp"

#include <fmt/format.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "diagnose/diagnosis_output.hpp"
#include "diagnose/report_figures.hpp"
#include "diagnose/residuals.hpp"
#include "html.hpp"
#include "plot.hpp"

namespace dyncc::diagnose {
namespace {

using plot::html_escape;

std::string number(const nlohmann::json& v) { return v.is_number() ? fmt::format("{:.4g}", v.get<double>()) : "-"; }

std::string percent(const nlohmann::json& v) {
  return v.is_number() ? fmt::format("{:.1f}&nbsp;%", 100 * v.get<double>()) : "-";
}

std::string list(const nlohmann::json& values) {
  std::string out;
  for (const auto& v : values) out += (out.empty() ? "" : ", ") + number(v);
  return out.empty() ? "-" : out;
}

std::string joints(const nlohmann::json& values) {
  std::string out;
  for (const auto& v : values) out += (out.empty() ? "" : ", ") + std::to_string(v.get<int>());
  return out.empty() ? "-" : out;
}

std::string shrink(const nlohmann::json& effect) {
  return fmt::format("{} [{}, {}]", percent(effect["shrink"]), percent(effect["shrink_interval"][0]),
                     percent(effect["shrink_interval"][1]));
}

std::string verdict_html(const nlohmann::json& v) {
  const std::string effect = v["effect"].get<std::string>();
  std::string why;
  if (v.contains("why")) {
    why = fmt::format(" ({})", html_escape(v["why"].get<std::string>()));
  } else if (effect == "none") {
    why = " (the gap is immaterial or at the noise floor)";
  } else if (effect == "unknown") {
    why = " (a material gap above the noise floor that no effect of the library explains)";
  }
  return fmt::format("<p class=\"verdict\">Verdict: <b>{}</b> on joints {}, confidence {:.2f}{}</p>\n",
                     html_escape(effect), joints(v["joints"]), v["confidence"].get<double>(), why);
}

std::string gap_html(const nlohmann::json& gap) {
  std::string html =
      "<table><tr><th>joint</th><th>torque RMS (N m)</th><th>held-out gap (N m)</th><th>% of torque RMS</th>"
      "<th>noise floor (N m)</th><th>positions' noise floor (N m)</th><th>after the selected effects (N m)</th>"
      "<th>% of torque RMS</th></tr>\n";
  for (std::size_t j = 0; j < gap["torque_rms"].size(); ++j) {
    const double torque = gap["torque_rms"][j].get<double>(),
                 after = gap["heldout_rms_after_selected"][j].get<double>();
    html += fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{}</td><td>{:.1f}</td><td>{}</td><td>{}</td><td>{}</td><td>{:.1f}</td></tr>\n",
        j + 1, number(gap["torque_rms"][j]), number(gap["heldout_rms"][j]),
        gap["percent_of_torque_rms"][j].get<double>(), number(gap["noise_floor"][j]),
        number(gap["position_noise_floor"][j]), number(gap["heldout_rms_after_selected"][j]),
        torque > 0 ? 100 * after / torque : 0.0);
  }
  html += "</table>\n";
  if (gap["windows"].empty()) {
    html += "<p>No time window stands out (none has over twice the usual residual).</p>\n";
  } else {
    html += "<p>Flagged windows (residual over twice its usual level):</p>\n<ul>\n";
    for (const auto& w : gap["windows"]) {
      html += fmt::format("<li>{}: {:.1f}&ndash;{:.1f} s, {:.1f}&times; the usual residual</li>\n",
                          html_escape(w["log"].get<std::string>()), w["start"].get<double>(), w["end"].get<double>(),
                          w["rms_ratio"].get<double>());
    }
    html += "</ul>\n";
  }
  html +=
      "<p>By regime (held-out RMS per joint, N m; share of the samples):</p>\n<table><tr><th>regime</th>"
      "<th>RMS</th><th>share</th></tr>\n";
  for (const auto& [name, r] : gap["regimes"].items()) {
    html += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td></tr>\n", html_escape(name), list(r["rms"]),
                        list(r["share"]));
  }
  return html + "</table>\n";
}

std::string ranking_html(const nlohmann::json& ranking) {
  std::string html =
      "<table><tr><th>effect</th><th>joints</th><th>held-out RMS before (N m, per joint)</th>"
      "<th>after</th><th>shrink [95 % interval]</th><th></th></tr>\n";
  for (const auto& r : ranking) {
    const char* note = !r["plausible"].get<bool>() ? "implausible fit" : "";
    html += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                        html_escape(r["effect"].get<std::string>()), joints(r["joints"]), list(r["heldout_rms_before"]),
                        list(r["heldout_rms_after"]), shrink(r), note);
  }
  return html + "</table>\n";
}

std::string parameters_html(const nlohmann::json& effect) {
  std::string html =
      "<table><tr><th>parameter</th><th>value</th><th>&plusmn; error</th><th>95&nbsp;% interval</th></tr>\n";
  for (const auto& p : effect["parameters"]) {
    std::string interval = "-";  // not fitted over the folds (a search's resolution)
    if (p.contains("interval95")) {
      const auto& i = p["interval95"];
      interval = fmt::format("{} to {}", i[0].is_null() ? "&minus;&infin;" : number(i[0]),
                             i[1].is_null() ? "&infin;" : number(i[1]));
    }
    html += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                        html_escape(p["name"].get<std::string>()), number(p["value"]), number(p["error"]), interval);
  }
  return html + "</table>\n";
}

std::string selected_html(const nlohmann::json& j) {
  std::string html;
  if (j["selected"].empty()) html += "<p>No effect was accepted.</p>\n";
  int k = 0;
  for (const auto& s : j["selected"]) {
    html += fmt::format("<h3>{}. {} on joints {}: shrink {}</h3>\n", ++k, html_escape(s["effect"].get<std::string>()),
                        joints(s["joints"]), shrink(s));
    if (s.contains("velocity_scale")) {
      html += fmt::format("<p>velocity scale {} rad/s</p>\n", number(s["velocity_scale"]));
    }
    html += parameters_html(s);
    if (s.contains("alternatives")) {
      for (const auto& a : s["alternatives"]) {
        html += fmt::format(
            "<p>or {} in its place: all selected effects then remove {} held out ({} as named){}; its errors "
            "are the folds' spread alone</p>\n",
            html_escape(a["effect"].get<std::string>()), percent(a["selection_shrink"]),
            percent(a["named_selection_shrink"]), a["plausible"].get<bool>() ? "" : ", an implausible fit");
        html += parameters_html(a);
      }
    }
  }
  const nlohmann::json& within = j["inertial_parameters"];
  html += fmt::format(
      "<h3>Within the model: the rigid-body base parameters re-identified alone, shrink {}</h3>\n"
      "<details><summary>{} parameters</summary>\n{}</details>\n",
      shrink(within), within["parameters"].size(), parameters_html(within));
  return html;
}

std::string audit_html(const nlohmann::json& j) {
  std::string html;
  for (const auto& a : j["audit"]) {
    html += fmt::format(
        "<p>{}: {} samples, {:.1f} s at {:.1f} Hz (jitter {:.1f} %, largest gap {:.1f}&times; the median "
        "interval)</p>\n<table><tr><th>joint</th><th>position quantum</th><th>position noise</th>"
        "<th>torque noise</th></tr>\n",
        html_escape(a["log"].get<std::string>()), a["samples"].get<long>(), a["duration_s"].get<double>(),
        a["rate_hz"].get<double>(), 100 * a["jitter"].get<double>(), a["largest_gap"].get<double>());
    int joint = 0;
    for (const auto& q : a["joints"]) {
      const bool quantised = q["quantum"].get<double>() > 0;
      html += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n", ++joint,
                          quantised ? number(q["quantum"]) : std::string("none found"), number(q["position_noise"]),
                          number(q["torque_noise"]));
    }
    html += "</table>\n";
  }
  const nlohmann::json& filter = j["filter"];
  html +=
      fmt::format("<p>Zero-phase filter at {:.2f} Hz; {} analysis rows, {:.3f} s apart.</p>\n",
                  filter["cutoff_hz"].get<double>(), filter["rows"].get<long>(), filter["row_spacing_s"].get<double>());
  return html;
}

struct Shown {
  std::string name, heading, caption;
};

std::string figure_html(const Shown& f) {
  return fmt::format("<h2>{}</h2>\n<p><img src=\"{}.svg\" alt=\"{}\"></p>\n<p class=\"caption\">{}</p>\n", f.heading,
                     f.name, f.name, f.caption);
}

}  // namespace

void write_diagnosis_report(const Dataset& data, const pipeline::Derivation& derivation, const Diagnosis& diagnosis,
                            const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  const SelectedResiduals residuals = selected_residuals(data, diagnosis);
  const nlohmann::json j = diagnosis_json(data, diagnosis);

  std::vector<std::pair<plot::Figure, Shown>> figures;
  figures.emplace_back(
      waterfall_figure(data, diagnosis),
      Shown{"waterfall", "Gap explained per effect",
            "The held-out RMS of the residual (each of five blocks in time predicted by a fit on the other four) "
            "after each selected effect, in the order the selection added them. Dashed: the description's "
            "rigid-body parameters re-identified alone, what the model's own structure can explain."});
  figures.emplace_back(
      velocity_figure(data, residuals),
      Shown{"velocity", "Residual against velocity",
            "One dot per analysis row; the line is the friction the selected effects fitted on that joint. Rows "
            "near a reversal lie between the two branches: the zero-phase filter smooths the step of the sign "
            "alike in the logged torque and in the fitted columns."});
  for (std::size_t l = 0; l < data.logs.size(); ++l) {
    const std::string name = data.logs.size() > 1 ? fmt::format("residual-log{}", l + 1) : "residual";
    figures.emplace_back(
        residual_figure(data, diagnosis, residuals, static_cast<int>(l)),
        Shown{name, data.logs.size() > 1 ? fmt::format("Residual over time, log {}", l + 1) : "Residual over time",
              "Nominal: the logged torque less the model's, both through the same zero-phase filter. After "
              "selected: what is left of each block when the fit on the other blocks predicts it. Shaded: windows "
              "of about 2 s with over twice the usual residual."});
  }
  figures.emplace_back(
      spectrum_figure(data, residuals),
      Shown{"spectrum", "Residual spectrum",
            "Hann-windowed amplitude spectrum of the residual (a sinusoid of amplitude A reads A). Peaks at the "
            "harmonics of the motion are model errors that follow the trajectory; a peak elsewhere is a "
            "disturbance of its own, such as a resonance."});
  figures.emplace_back(
      correlation_figure(data),
      Shown{"correlation", "Cross-correlation with the logged torque",
            "Solid: the logged torque against the model torque computed from the logged positions, correlated at "
            "each lag; the peak is the lag by which the model is late: 0 without a delay, +d when the positions "
            "are logged d late, negative when the torque is. A delay shifts every joint alike; an effect on one "
            "joint (a rotor inertia, friction) can shift that joint's peak too. Dashed: the residual against the "
            "logged torque; a delay makes the residual follow the torque's rate, which crosses zero near lag 0 and "
            "peaks off it."});
  for (const auto& [figure, shown] : figures) plot::write_figure(figure, dir / shown.name);

  std::string logs;
  for (const std::string& log : data.logs) logs += (logs.empty() ? "" : ", ") + html_escape(log);
  std::string html = fmt::format(
      "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>dyncc diagnose: {}</title>\n"
      "<style>body{{font-family:sans-serif;max-width:1000px;margin:auto}}img{{width:100%}}"
      "td,th{{padding:2px 8px;text-align:left;vertical-align:top}}table{{border-collapse:collapse}}"
      "tr:nth-child(even){{background:#f4f4f4}}.verdict{{font-size:1.3em}}.caption{{color:#444;font-size:0.9em}}"
      "</style></head><body>\n<h1>Diagnosis of {} against its logs</h1>\n<p>Logs: {}. The numbers are also in "
      "<a href=\"diagnosis.json\">diagnosis.json</a> and <a href=\"summary.txt\">summary.txt</a>.</p>\n",
      html_escape(derivation.robot.name), html_escape(derivation.robot.name), logs);
  html += verdict_html(j["verdict"]);
  html += "<h2>Gap per joint</h2>\n" + gap_html(j["gap"]);
  html += figure_html(figures.front().second);
  html += "<h2>Candidates at the first step (held out)</h2>\n" + ranking_html(j["ranking"]);
  html += "<h2>Selected effects and their fitted parameters</h2>\n" + selected_html(j);
  for (std::size_t f = 1; f < figures.size(); ++f) html += figure_html(figures[f].second);
  html += "<h2>Audit of the logs</h2>\n" + audit_html(j);
  html += "</body></html>\n";

  const std::filesystem::path page = dir / "report.html";
  std::ofstream out(page);
  out << html;
  if (!out) throw std::runtime_error(page.string() + ": cannot write");
}

}  // namespace dyncc::diagnose
