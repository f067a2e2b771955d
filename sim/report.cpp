#include "report.hpp"

#include <fmt/format.h>

#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>

#include "html.hpp"
#include "plot.hpp"
#include "summary.hpp"

namespace dyncc::sim {
namespace {

using plot::Figure;
using plot::Panel;
using plot::Series;
using plot::write_figure;
using Pick = std::function<double(const Sample&)>;

Series series(const Run& run, const std::string& label, const Pick& pick, bool dashed = false) {
  Series s;
  s.label = label;
  s.dashed = dashed;
  s.x.reserve(run.samples.size());
  s.y.reserve(run.samples.size());
  for (const Sample& sample : run.samples) {
    s.x.push_back(sample.t);
    s.y.push_back(pick(sample));
  }
  return s;
}

// Time intervals where the hook touches the table, shaded in every panel.
std::vector<std::pair<double, double>> contact_intervals(const Run& run) {
  std::vector<std::pair<double, double>> out;
  double start = -1;
  for (const Sample& s : run.samples) {
    if (s.contact && start < 0) start = s.t;
    if (!s.contact && start >= 0) {
      out.emplace_back(start, s.t);
      start = -1;
    }
  }
  if (start >= 0) out.emplace_back(start, run.samples.back().t);
  return out;
}

std::string mode(const Run& run) {
  return fmt::format("{}{}, {} kg, {} plant", run.settings.adaptation ? "adaptive" : "fixed model",
                     run.settings.simplified ? " (simplified)" : "", run.settings.payload,
                     run.settings.plant == PlantKind::mujoco ? "MuJoCo" : "dyncc");
}

Figure angles(const Run& run) {
  Figure f;
  f.title = fmt::format("Joint angles, {} (shaded: hook on the table)", mode(run));
  for (int k = 0; k < kDof; ++k) {
    Panel p;
    p.title = fmt::format("joint {}", k + 1);
    p.y_label = "rad";
    p.series.push_back(series(
        run, "master", [k](const Sample& s) { return s.master[static_cast<std::size_t>(k)]; }, true));
    p.series.push_back(series(run, "slave", [k](const Sample& s) { return s.slave[static_cast<std::size_t>(k)]; }));
    p.shaded = contact_intervals(run);
    f.panels.push_back(std::move(p));
  }
  return f;
}

// s_i of several runs on the same axes (Fig. 6 puts adaptive and fixed together).
Figure errors(const std::vector<std::pair<const Run*, std::string>>& runs, const std::string& title,
              const std::vector<int>& joints) {
  Figure f;
  f.title = title;
  for (const int k : joints) {
    Panel p;
    p.title = fmt::format("s{}", k + 1);
    p.y_label = "rad/s";
    bool first = true;
    for (const auto& [run, label] : runs) {
      p.series.push_back(series(
          *run, label, [k](const Sample& s) { return s.s[static_cast<std::size_t>(k)]; }, !first));
      if (first) p.shaded = contact_intervals(*run);
      first = false;
    }
    f.panels.push_back(std::move(p));
  }
  return f;
}

Figure estimates(const std::vector<std::pair<const Run*, std::string>>& runs, const std::string& title) {
  Figure f;
  f.title = title;
  const std::pair<char, const char*> groups[] = {{'M', "first moments (kg m)"}, {'F', "friction (N m, N m s)"}};
  for (const auto& [initial, name] : groups) {
    Panel p;
    p.title = name;
    bool first = true;
    for (const auto& [run, label] : runs) {
      for (int b = 0; b < kParameters; ++b) {
        if (Kraft::parameter_names[b][0] != initial) continue;
        p.series.push_back(series(
            *run, label.empty() ? Kraft::parameter_names[b] : fmt::format("{} {}", Kraft::parameter_names[b], label),
            [b](const Sample& s) { return s.estimate[static_cast<std::size_t>(b)]; }, !first));
      }
      if (first) p.shaded = contact_intervals(*run);
      first = false;
    }
    f.panels.push_back(std::move(p));
  }
  Panel rest;
  rest.title = "second moments (kg m^2)";
  for (int b = 0; b < kParameters; ++b) {
    const char c = Kraft::parameter_names[b][0];
    if (c == 'M' || c == 'F') continue;
    rest.series.push_back(series(*runs.front().first, Kraft::parameter_names[b],
                                 [b](const Sample& s) { return s.estimate[static_cast<std::size_t>(b)]; }));
  }
  f.panels.push_back(std::move(rest));
  return f;
}

using plot::html_escape;

std::string plant_name(PlantKind p) { return p == PlantKind::mujoco ? "mujoco" : "dyncc"; }

}  // namespace

void write_run_figures(const Run& run, const std::filesystem::path& dir) {
  write_figure(angles(run), dir / "angles");
  write_figure(errors({{&run, run.settings.adaptation ? "adaptive" : "fixed"}},
                      fmt::format("Tracking errors, {}", mode(run)), {0, 1, 2}),
               dir / "errors");
  write_figure(estimates({{&run, ""}}, fmt::format("Parameter estimates, {}", mode(run))), dir / "estimates");
}

void write_report(const std::vector<PaperRuns>& plants, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  std::string html =
      "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>dyncc: the Kraft tele-operation "
      "experiments</title>\n"
      "<style>body{font-family:sans-serif;max-width:1000px;margin:auto}img{width:100%}pre{font-size:11px;overflow-x:"
      "auto}"
      "td,th{padding:2px 8px;text-align:left;vertical-align:top}.ok{color:#070}.no{color:#b00}</style></head><body>\n"
      "<h1>Adaptive vs fixed-model tele-operation of the Kraft arm</h1>\n"
      "<p>Carignan, Tarrant, Mosier: <i>An adaptive controller for enhancing operator performance during "
      "teleoperation</i>, section 4, reproduced in simulation. The slave is the Slotine&ndash;Li controller of "
      "<code>runtime/</code> on the generated Kraft model at 81 Hz, starting from the paper's initial estimate; the "
      "true arm has the description's nominal parameters. Errors s = q&#771;' + &lambda;q&#771; as in the paper's "
      "Figs. 6&ndash;8. Shaded: the hook on the table.</p>\n";
  for (const PaperRuns& p : plants) {
    const std::string name = plant_name(p.plant);
    const std::filesystem::path sub = dir / name;
    std::filesystem::create_directories(sub);
    const Run& adaptive = p.run("paper-0.5kg", true);
    const Run& fixed = p.run("paper-0.5kg", false);
    write_figure(angles(adaptive), sub / "fig4-angles-adaptive");
    write_figure(angles(fixed), sub / "fig5-angles-fixed");
    write_figure(errors({{&adaptive, "adaptive"}, {&fixed, "fixed"}}, "Fig. 6: tracking errors with the 0.5 kg payload",
                        {0, 1, 2}),
                 sub / "fig6-errors");
    write_figure(errors({{&p.run("paper-1kg", true), "adaptive 1 kg"}, {&adaptive, "adaptive 0.5 kg"}},
                        "Fig. 7: joint 3 tracking error, adaptive, 1 kg payload", {2}),
                 sub / "fig7-1kg");
    write_figure(errors({{&p.run("paper-simplified", true), "simplified"}, {&adaptive, "full"}},
                        "Fig. 8: joint 3 tracking error without the velocity terms", {2}),
                 sub / "fig8-simplified");
    write_figure(estimates({{&adaptive, "adapting"}, {&p.run("paper-contact", true), "frozen in contact"}},
                           "Estimates while pressing on the table: adapting vs frozen in contact"),
                 sub / "contact-estimates");
    write_figure(errors({{&adaptive, "adapting in contact"}, {&p.run("paper-contact", true), "frozen in contact"}},
                        "Tracking errors: adapting vs frozen in contact", {1, 2}),
                 sub / "contact-errors");

    html += fmt::format("<h2>Plant: {}</h2>\n<table><tr><th></th><th>finding</th><th>measured</th></tr>\n",
                        name == "mujoco" ? "MuJoCo (exported MJCF, its own contact and friction)"
                                         : "dyncc (generated model, RK4)");
    for (const Finding& f : paper_findings(p)) {
      html += fmt::format("<tr><td class=\"{}\">({}) {}</td><td>{}</td><td>{}</td></tr>\n", f.holds ? "ok" : "no", f.id,
                          f.holds ? "holds" : "does not hold", html_escape(f.claim), html_escape(f.evidence));
    }
    html += "</table>\n<h3>Summary</h3>\n<pre>" + html_escape(summary_table(p.summaries)) + "</pre>\n";
    html += "<h3>Final estimates</h3>\n<pre>" + html_escape(estimate_table(p.summaries)) + "</pre>\n";
    for (const char* fig : {"fig4-angles-adaptive", "fig5-angles-fixed", "fig6-errors", "fig7-1kg", "fig8-simplified",
                            "contact-estimates", "contact-errors"}) {
      html += fmt::format("<p><img src=\"{}/{}.svg\" alt=\"{}\"></p>\n", name, fig, fig);
    }
  }
  html += "</body></html>\n";
  std::ofstream out(dir / "index.html");
  out << html;
  if (!out) throw std::runtime_error((dir / "index.html").string() + ": cannot write");
}

}  // namespace dyncc::sim
