// `dyncc derive`: the model in readable form, to hold against a paper's appendix.
//
// H, C and g are printed in the BASE parameters (each standard parameter that was regrouped
// is replaced by 0 and each kept one by its base parameter, which the proved regrouping
// identities make exact), each entry in the smaller of its expanded and trigonometric normal
// forms.
#include <fmt/core.h>
#include <fmt/format.h>

#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/robot_input.hpp"
#include "sym/expand.hpp"
#include "sym/print.hpp"
#include "sym/substitute.hpp"
#include "sym/trig_normal_form.hpp"

namespace dyncc::cli {
namespace {

class Presenter {
 public:
  Presenter(const pipeline::Derivation& d, bool latex) : latex_(latex) {
    const sym::Substitution constants = d.robot.constant_values();
    map_ = constants;
    std::vector<bool> kept(d.model.params.list.size(), false);
    for (const auto& b : d.base.list) {
      kept[static_cast<std::size_t>(b.kept)] = true;
      map_[d.model.params.list[static_cast<std::size_t>(b.kept)].symbol] = sym::symbol(b.name);
    }
    for (std::size_t l = 0; l < kept.size(); ++l) {
      if (!kept[l]) map_[d.model.params.list[l].symbol] = sym::Expr(0);
    }
  }

  [[nodiscard]] std::string show(sym::Expr e) const {
    const sym::Expr in_base = sym::substitute(e, map_);
    const sym::Expr expanded = sym::expand(in_base);
    sym::Expr best = expanded;
    try {
      const sym::Expr normal = sym::trig_normal_form(in_base).expr;
      if (sym::to_string(normal).size() < sym::to_string(best).size()) best = normal;
    } catch (const std::overflow_error&) {
      // keep the expanded form
    }
    return latex_ ? sym::to_latex(best) : sym::to_string(best);
  }

  void matrix(const std::string& name, const dyn::Matrix& m, bool symmetric) const {
    heading(name);
    for (std::size_t i = 0; i < m.size(); ++i) {
      for (std::size_t j = symmetric ? i : 0; j < m[i].size(); ++j)
        entry(fmt::format("{}{}{}", name, i + 1, j + 1), m[i][j]);
    }
  }

  void vector(const std::string& name, const std::vector<sym::Expr>& v) const {
    heading(name);
    for (std::size_t i = 0; i < v.size(); ++i) entry(fmt::format("{}{}", name, i + 1), v[i]);
  }

  void entry(const std::string& label, sym::Expr e) const {
    if (latex_) {
      fmt::print("{} &= {} \\\\\n", label, show(e));
    } else {
      fmt::print("  {} = {}\n", label, show(e));
    }
  }

  void text(const std::string& label, const std::string& value) const {
    if (latex_) {
      fmt::print("{} &= \\mathrm{{{}}} \\\\\n", label, value);
    } else {
      fmt::print("  {} = {}\n", label, value);
    }
  }

  void heading(const std::string& text) const {
    if (latex_) {
      fmt::print("% {}\n", text);
    } else {
      fmt::print("\n{}\n", text);
    }
  }

 private:
  bool latex_;
  sym::Substitution map_;
};

}  // namespace

int run_derive(const DeriveOptions& o) {
  const auto d = load_and_derive(o.robot);
  if (!d) return kBadInput;
  const Presenter p(*d, o.latex);
  if (o.latex) fmt::print("\\begin{{align*}}\n");
  if (!o.latex) {
    fmt::print(
        "{}: {} coordinates ({}), {} links, {} standard parameters, {} base parameters\n", d->robot.name,
        d->model.q.size(),
        [&] {
          std::string s;
          for (const auto& q : d->model.q) s += (s.empty() ? "" : ", ") + q.name();
          return s;
        }(),
        d->robot.links.size(), d->model.params.list.size(), d->base.list.size());
    fmt::print("rates: ");
    for (const auto& qd : d->model.qd) fmt::print("{} ", qd.name());
    fmt::print("  (tau = H*qdd + C*qd + g + FC*sgn(qd) + FV*qd)\n");
  }
  p.heading("base parameters (exact regrouping of the standard parameters, constants as numbers)");
  for (const auto& b : d->base.list) {
    if (o.latex) {
      fmt::print("\\mathrm{{{}}} &= {} \\\\\n", b.name, sym::to_latex(b.definition));
    } else {
      fmt::print("  {} = {}\n", b.name, sym::to_string(b.definition));
    }
  }
  p.matrix("H", d->model.H, true);
  p.matrix("C", d->model.C, false);
  p.vector("g", d->model.g);
  p.heading("friction");
  for (std::size_t k = 0; k < d->model.q.size(); ++k) {
    const int fc = d->model.params.coulomb_of[k];
    const int fv = d->model.params.viscous_of[k];
    const std::string qd = d->model.qd[k].name();
    std::vector<std::string> terms;
    if (fc >= 0)
      terms.push_back(fmt::format("{}*sgn({})", d->model.params.list[static_cast<std::size_t>(fc)].name, qd));
    if (fv >= 0) terms.push_back(fmt::format("{}*{}", d->model.params.list[static_cast<std::size_t>(fv)].name, qd));
    const std::string text = terms.empty() ? std::string("0") : fmt::format("{}", fmt::join(terms, " + "));
    if (o.latex) {
      fmt::print("f_{{{}}} &= \\mathrm{{{}}} \\\\\n", k + 1, text);
    } else {
      fmt::print("  f{} = {}\n", k + 1, text);
    }
  }
  p.heading("regressor Y (Slotine-Li: Y(q, qd, v, a) * base = H*a + C*v + g + FC*sgn(qd) + FV*v), non-zero entries");
  for (std::size_t i = 0; i < d->model.q.size(); ++i) {
    for (const auto& b : d->base.list) {
      const auto& sp = d->model.params.list[static_cast<std::size_t>(b.kept)];
      if (sp.kind == dyn::StandardKind::FC) {
        if (sp.coordinate == static_cast<int>(i))
          p.text(fmt::format("Y{}[{}]", i + 1, b.name), fmt::format("sgn({})", d->model.qd[i].name()));
        continue;
      }
      if (sp.kind == dyn::StandardKind::FV) {
        if (sp.coordinate == static_cast<int>(i)) p.text(fmt::format("Y{}[{}]", i + 1, b.name), d->model.v[i].name());
        continue;
      }
      const sym::Expr y = d->regressor.rows[i][static_cast<std::size_t>(b.kept)];
      if (!y.is_zero()) p.entry(fmt::format("Y{}[{}]", i + 1, b.name), y);
    }
  }
  if (o.latex) {
    fmt::print("\\end{{align*}}\n");
    return kSuccess;
  }
  if (d->grouping) {
    fmt::print("\nyour grouping (base_parameters): {} parameters, {}\n", d->grouping->names.size(),
               d->grouping->complete ? "spans the identifiable space" : "incomplete");
    if (!d->grouping->involved.empty()) {
      fmt::print("  ");
      for (std::size_t i = 0; i < d->grouping->involved.size(); ++i)
        fmt::print("{}{}", i ? ", " : "", d->grouping->involved[i]);
      fmt::print(" enter only as ");
      for (std::size_t i = 0; i < d->grouping->effective_combinations.size(); ++i)
        fmt::print("{}{}", i ? ", " : "", d->grouping->effective_combinations[i]);
      fmt::print("\n");
    }
  }
  fmt::print("\ntimings:");
  for (const auto& t : d->timings) fmt::print(" {} {:.1f} ms;", t.stage, t.milliseconds);
  fmt::print(" total {:.1f} ms\n", d->total_milliseconds());
  return kSuccess;
}

}  // namespace dyncc::cli
