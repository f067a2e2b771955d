// The selection judged together once its steps are taken: profile points chosen again beside
// each other, effects the others explain dropped, one effect for two steps, the joint refit (with
// parameters read in applied torque beside a gain, free of the torque's noise for a spring, and
// the systematic error between regimes), the steps restated in order, and each named alternative
// fitted in the place of the effect it ties with.
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <numeric>
#include <optional>

#include "diagnose/crossval.hpp"
#include "diagnose/long_rests.hpp"
#include "diagnose/payload.hpp"
#include "diagnose/plausibility.hpp"
#include "diagnose/regime_error.hpp"
#include "diagnose/selection.hpp"

namespace dyncc::diagnose {
namespace {

// Held-out mean square near zero velocity over that away from it, after the effects' joint fit,
// beyond which a joint's rows near zero hold a static friction rather than noise: any excess.
// At 2 (until the tenth session) the base joint of a tele-operated Kraft on the MuJoCo plant,
// whose rows near zero read 1.1-1.5 times worse, kept them, and its static friction took up part
// of a payload's coupling torques: 10 g read 3.2-3.8 % low (seeds 59 case 33, 89 case 57), now
// 0.5-2.2 %.
constexpr double kStaticFrictionRatio = 1.0;
// Standard errors (the folds' spread) by which a Stribeck friction's static excess must exceed
// zero to be one (holds_an_excess).
constexpr double kExcessErrors = 2.0;

// Whether the joint fit `cv` of `effects` reads the static excess of effects[k] (a Stribeck
// friction) above zero on some joint, by more than two of its standard errors: the folds' spread
// and how far slow and fast motion disagree (`systematic`, regime_error), as the parameters are
// reported. An excess the folds do not tell from zero is not evidence of the effect (seed 83 case
// 39, below: fs1 0.0008 +- 0.0005 once the static-friction rule dropped joint 1's rows at rest);
// nor is one that slow and fast motion read differently by more than itself: blind seed 211 case
// 54, a rigid-plant Coulomb friction of the Kraft's joint 1 beside a gain of that joint, was named
// a Stribeck friction with fs1 0.0049 +- 0.013 (the folds' error alone a few times smaller).
bool holds_an_excess(const std::vector<Effect>& effects, std::size_t k, const CrossValidation& cv,
                     const Eigen::VectorXd& systematic) {
  Eigen::Index at = 0;
  for (std::size_t i = 0; i < k; ++i) at += effects[i].columns.cols();
  const Effect& e = effects[k];
  for (std::size_t c = 0; c < e.parameters.size(); ++c) {
    const Eigen::Index column = at + static_cast<Eigen::Index>(c);
    const double error = std::hypot(cv.theta_error[column], systematic[column]);
    if (e.parameters[c].rfind("fs", 0) == 0 && cv.theta[column] > kExcessErrors * error) return true;
  }
  return false;
}

// A Stribeck friction whose static excess the joint fit of every accepted effect reads as zero or
// less (within two standard errors) on each of its joints is the Coulomb friction of those joints: its excess stood in,
// at the step that accepted it, for an effect accepted later (seed 83 case 39: a Coulomb friction of the Kraft's joint
// 1 beside a 12 ms delay, fs1 -0.0009 once the delay was in). So is one whose scale is chosen
// again within the band near zero velocity (kTurnOverBand): its excess fades before the velocity
// leaves the band, so it explains only how the friction turns over, which a friction is not judged
// by (acceptable); the plant's friction turns over more sharply than the model's (blind seed 179
// case 49: a PUMA Coulomb friction of 2.76 N m, an exact sign at 81 Hz, read as a Stribeck friction
// with fs1 0.72 at 0.02 rad/s).
void coulomb_where_no_excess(Diagnosis& out, std::size_t k, const Eigen::VectorXd& r0, const Eigen::VectorXd& weight,
                             Eigen::Index n, const std::vector<RegimeSplit>& splits) {
  const Effect& stribeck = out.accepted_effects[k];
  if (stribeck.name != "stribeck_friction") return;
  if (stribeck.profile > kTurnOverBand &&
      holds_an_excess(out.accepted_effects, k,
                      fit_together(out.accepted_effects, r0, weight, out.folds, out.away, out.far, n),
                      regime_error(out.accepted_effects, r0, weight, out.folds, out.away, out.far, n, splits))) {
    return;
  }
  Effect coulomb = kept_columns(stribeck, [&](std::size_t c) { return stribeck.parameters[c].rfind("fc", 0) == 0; });
  coulomb.name = coulomb.family = "coulomb_friction";
  coulomb.profile_name.clear();
  coulomb.profile = 0;
  out.accepted_effects[k] = std::move(coulomb);
  RankedEffect& r = out.selected[k];
  r.effect = r.family = "coulomb_friction";
  r.profile_name.clear();
  r.profile = 0;
}

// Whether every accepted friction reads plausibly in the joint fit `cv` (no friction of a joint
// whose total, the description's and the fitted, is below zero).
bool frictions_plausible(const Diagnosis& out, const CrossValidation& cv, const pipeline::Derivation& derivation,
                         Eigen::Index n) {
  Candidate joint;
  joint.cv = cv;
  joint.after = joint_rms(cv.heldout, n);
  Eigen::Index at = 0;
  for (const Effect& e : out.accepted_effects) {
    joint.effect = &e;
    if (is_friction(e) &&
        !plausible(describe(joint, out.gap.residual_rms, at, out.gap.torque_rms), derivation, out.gap))
      return false;
    at += e.columns.cols();
  }
  return true;
}

// Effects[k]'s profile point chosen again beside the other accepted effects (rechoose_points),
// among the points at which the joint fit reads every friction plausibly (where the chosen point
// does): blind seed 881 case 24, a Stribeck excess of the Kraft's joint 2 (closed loop, rigid
// plant) chosen at 0.1 rad/s, with a viscous friction of joints 1 and 2 accepted after it, moved
// to 0.33 rad/s beside a viscous friction of joint 2 of -0.47 N m s/rad (a friction that falls as
// the joint speeds up: the excess's fading, which the larger scale let it take up), lost its
// excess in the joint fit and was named a Coulomb friction.
void rechoose_point(Diagnosis& out, std::size_t k, const std::deque<Effect>& effects, const Eigen::VectorXd& r0,
                    const Eigen::VectorXd& weight, Eigen::Index n, const pipeline::Derivation& derivation) {
  const Effect chosen = out.accepted_effects[k];
  auto joint_fit = [&]() { return fit_together(out.accepted_effects, r0, weight, out.folds, out.away, out.far, n); };
  // The joint fit's held-out error on the rows away from zero velocity.
  auto away_error = [&](const CrossValidation& cv) {
    return score(cv.heldout, weight, n, 0, r0.size() / n, &out.away);
  };
  const CrossValidation at_chosen = joint_fit();
  const bool plausible_only = frictions_plausible(out, at_chosen, derivation, n);
  double least = away_error(at_chosen);
  Effect best = chosen;
  for (const Effect& point : effects) {
    if (point.name != chosen.name || point.profile == chosen.profile) continue;
    Effect mine = kept_columns(point, [&](std::size_t c) {
      return std::find(chosen.parameters.begin(), chosen.parameters.end(), point.parameters[c]) !=
             chosen.parameters.end();
    });
    if (mine.columns.cols() != chosen.columns.cols()) continue;
    out.accepted_effects[k] = std::move(mine);
    const CrossValidation cv = joint_fit();
    if (plausible_only && !frictions_plausible(out, cv, derivation, n)) continue;
    const double e = away_error(cv);
    if (e < least) {
      least = e;
      best = out.accepted_effects[k];
    }
  }
  out.accepted_effects[k] = best;
  out.selected[k].profile = best.profile;
}

// Each accepted friction profile's point (a Stribeck scale) chosen again beside all the accepted
// effects, by the joint fit's held-out error on the rows away from zero velocity (as the search
// chose it): a scale picked before the viscous friction of its joint was fitted is bent to mimic
// that friction (seed 53 case 9: fs2 0.449 for 0.350 beside a viscous 0.201). Where no excess is
// left at the chosen scale, the Stribeck friction is a Coulomb friction (coulomb_where_no_excess). Not a contact's
// surface: chosen again among its grid's points beside a payload, it moved the payload's mass by 5 %
// (seed 23 case 54).
void rechoose_points(Diagnosis& out, const std::deque<Effect>& effects, const Eigen::VectorXd& r0,
                     const Eigen::VectorXd& weight, Eigen::Index n, const std::vector<RegimeSplit>& splits,
                     const pipeline::Derivation& derivation) {
  for (std::size_t k = 0; k < out.accepted_effects.size(); ++k) {
    const Effect chosen = out.accepted_effects[k];
    if (chosen.profile_name.empty() || !is_friction(chosen)) continue;
    // Alone, a friction's point is where the search left it; whether its excess holds is asked
    // all the same (until the twenty-first session only beside another effect).
    if (out.accepted_effects.size() >= 2) rechoose_point(out, k, effects, r0, weight, n, derivation);
    coulomb_where_no_excess(out, k, r0, weight, n, splits);
  }
}

// `effects` fitted together as the final joint fit fits the selection, with what that removes of
// the nominal model's held-out error (`shrink`, its interval and its folds).
Candidate fitted_together(const Diagnosis& out, const std::vector<Effect>& effects, const Eigen::VectorXd& r0,
                          const Eigen::VectorXd& weight, Eigen::Index n) {
  Candidate c;
  c.cv = fit_together(effects, r0, weight, out.folds, out.away, out.far, n);
  set_shrink(c, r0, weight, n, &out.scored);
  return c;
}

// The names a selected "A or B or ..." gives beside A.
std::vector<std::string> alternative_names(const std::string& named) {
  std::vector<std::string> names;
  std::size_t from = named.find(kOr);
  while (from != std::string::npos) {
    const std::size_t next = named.find(kOr, from + kOr.size());
    names.push_back(named.substr(from + kOr.size(), next == std::string::npos ? next : next - from - kOr.size()));
    from = next;
  }
  return names;
}

// "A or B or ..." with only the alternatives that are per-joint effects (a family among
// `candidates` whose effects are per_joint) not selected at a step other than k.
std::string with_per_joint_alternatives(const std::string& named, const std::deque<Effect>& candidates,
                                        const std::vector<Effect>& selected, std::size_t k) {
  std::string out = named.substr(0, named.find(kOr));
  for (const std::string& name : alternative_names(named)) {
    bool taken = false;
    for (std::size_t i = 0; i < selected.size(); ++i) taken = taken || (i != k && selected[i].family == name);
    const bool per_joint_family = std::any_of(candidates.begin(), candidates.end(),
                                              [&](const Effect& e) { return e.name == name && per_joint(e); });
    if (!taken && per_joint_family) out += std::string(kOr) + name;
  }
  return out;
}

// A load accepted at a step before the other effects was placed (its point, and whether and when
// it was carried) against a residual that still held them; it is placed again beside all of them,
// and the placing whose joint fit removes most of the held-out error takes its place. Blind seed
// 1051 case 14 (the Panda, open loop at 1 kHz): a 100 g load carried from 15.2 to 32.3 s beside a
// 0.177 rad offset of joint 6 was placed first as a load over the whole log, which beside the
// offset explained nothing more and was dropped; the offset alone read 0.136.
void place_loads_again(Diagnosis& out, const std::deque<Effect>& candidates, const Dataset& d,
                       const pipeline::Derivation& derivation, const Eigen::VectorXd& r0, const Eigen::VectorXd& weight,
                       Eigen::Index n, std::vector<Eigen::VectorXd>& parts) {
  if (out.accepted_effects.size() < 2) return;
  std::optional<PayloadPlacer> placer;
  for (std::size_t k = 0; k < out.accepted_effects.size(); ++k) {
    if (out.accepted_effects[k].family != "payload") continue;
    Eigen::Index width = 0;
    for (std::size_t i = 0; i < out.accepted_effects.size(); ++i) {
      if (i != k) width += out.accepted_effects[i].columns.cols();
    }
    Eigen::MatrixXd others(r0.size(), width);
    Eigen::Index at = 0;
    for (std::size_t i = 0; i < out.accepted_effects.size(); ++i) {
      const Eigen::MatrixXd& columns = out.accepted_effects[i].columns;
      if (i == k) continue;
      others.middleCols(at, columns.cols()) = columns;
      at += columns.cols();
    }
    if (!placer) placer.emplace(d, derivation, in_long_rests(d, out.away));
    std::vector<Effect> placed;
    placer->add_effects(r0, others, placed);
    // (Placed again, a load moves a little beside the others; it is a new placing where it removes
    // 1 % more of the held-out error.)
    double most = fitted_together(out, out.accepted_effects, r0, weight, n).shrink + 0.01;
    // Where the load's coefficients sit in the joint fit: the effects before k keep their columns.
    Eigen::Index offset = 0;
    for (std::size_t i = 0; i < k; ++i) offset += out.accepted_effects[i].columns.cols();
    for (Effect& load : placed) {
      std::vector<Effect> in_place = out.accepted_effects;
      in_place[k] = load;
      const Candidate fit = fitted_together(out, in_place, r0, weight, n);
      if (!(fit.shrink > most)) continue;
      most = fit.shrink;
      parts[k] = load.columns * fit.cv.theta.segment(offset, load.columns.cols());
      // The alternatives named at its step tied with the load as placed then: those of the whole
      // arm go (a contact that stood in for a load over the whole log is no alternative to it
      // while carried); a per-joint one not selected at another step stays, read in its place
      // (fit_alternatives_in_place) for the user to judge.
      out.selected[k].effect = with_per_joint_alternatives(out.selected[k].effect, candidates, out.accepted_effects, k);
      out.accepted_effects[k] = std::move(load);
    }
  }
}

// The fitted torque gain of each joint that has one (joints from 0), from a joint fit's coefficients.
std::map<int, double> fitted_gains(const CrossValidation& cv, const std::vector<Effect>& effects) {
  std::map<int, double> gain_of;
  Eigen::Index at = 0;
  for (const Effect& e : effects) {
    for (Eigen::Index k = 0; k < e.columns.cols() && e.family == "torque_gain"; ++k) {
      const double g = physical(Reading::gain, cv.theta[at + k]);
      if (std::isfinite(g) && g > 0) gain_of[e.joint_of[static_cast<std::size_t>(k)]] = g;
    }
    at += e.columns.cols();
  }
  return gain_of;
}

// A torque gain g of joint j: the arm applies g times the logged torque, so every other column of
// joint j is fitted in logged torque and its coefficient is the applied one over g (a viscous
// friction of 0.190 beside a gain of 1.11 on the same joint read 0.170; seed 79 case 39). Per
// column of the joint fit: g for a per-joint torque column of a joint with a fitted gain, else 1.
// A shift of the positions is no torque: its rows are put in logged torque instead
// (arm_rows_in_logged_torque), and its coefficient is the shift per unit of its pattern. A
// spring's pattern is the logged torque of its joint, 1/g of what the spring carries, so its
// compliance is the coefficient over g (blind seed 907 case 29: a Panda spring of joint 4 of
// 189.7 N m/rad beside a gain of 1.055 of that joint read 170.7, the gain applied twice over).
Eigen::VectorXd applied_torque_scale(const CrossValidation& cv, const std::vector<Effect>& effects) {
  const std::map<int, double> gain_of = fitted_gains(cv, effects);
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(cv.theta.size());
  Eigen::Index at = 0;
  for (const Effect& e : effects) {
    for (Eigen::Index k = 0; k < e.columns.cols() && e.family != "torque_gain"; ++k) {
      const auto gain = gain_of.find(e.joint_of[static_cast<std::size_t>(k)]);
      if (gain == gain_of.end()) continue;
      if (e.family == "joint_elasticity") {
        scale[at + k] = 1.0 / gain->second;
      } else if (!shifts_positions(e)) {
        scale[at + k] = gain->second;
      }
    }
    at += e.columns.cols();
  }
  return scale;
}

// The same for an effect of the whole arm (a payload, a contact, a delay, the inertial
// parameters) or a shift of the positions: its columns have rows on several joints, so no factor
// on a coefficient says it; instead its rows of a joint with a gain g are divided by g (the logged
// torque is what the arm applies over g) and the joint fit repeated, twice, the gains moving a
// little as it does (seed 137 case 9: a 29 g Kraft payload beside a gain of 1.0275 on joint 2,
// 81 Hz, read 3.0 % light: the payload's torque on joint 2 was fitted as applied and logged at
// once).
template <class Fit>
void arm_rows_in_logged_torque(std::vector<Effect>& effects, CrossValidation& cv, const Fit& fit, Eigen::Index n) {
  std::vector<std::size_t> arm;
  for (std::size_t k = 0; k < effects.size(); ++k) {
    if (!per_joint(effects[k]) || shifts_positions(effects[k])) arm.push_back(k);
  }
  if (arm.empty() || fitted_gains(cv, effects).empty()) return;
  std::vector<Eigen::MatrixXd> as_applied;
  as_applied.reserve(arm.size());
  for (const std::size_t k : arm) as_applied.push_back(effects[k].columns);
  for (int pass = 0; pass < 2; ++pass) {
    Eigen::VectorXd gain_of = Eigen::VectorXd::Ones(n);  // per joint: its gain, or 1
    for (const auto& [joint, gain] : fitted_gains(cv, effects)) gain_of[joint] = gain;
    const Eigen::ArrayXd row_gain = gain_of.replicate(as_applied.front().rows() / n, 1).array();
    for (std::size_t i = 0; i < arm.size(); ++i) {
      effects[arm[i]].columns = (as_applied[i].array().colwise() / row_gain).matrix();
    }
    cv = fit();
  }
}

// How much of `part` (stacked rows, weighted per joint) the columns of `e` reproduce: the share of
// its weighted square that their least-squares fit to it takes up.
double share_reproduced(const Eigen::VectorXd& part, const Effect& e, const Eigen::VectorXd& weight, Eigen::Index n) {
  Eigen::VectorXd w(part.size());
  for (Eigen::Index r = 0; r < part.size(); ++r) w[r] = weight[r % n];
  const Eigen::VectorXd target = w.cwiseProduct(part);
  const Eigen::MatrixXd columns = w.asDiagonal() * e.columns;
  const double total = target.squaredNorm();
  if (total <= 0 || columns.cols() == 0) return 0.0;
  const Eigen::VectorXd fitted = columns * columns.colPivHouseholderQr().solve(target);
  return fitted.squaredNorm() / total;
}

// An effect that the later ones explain all of (`gone`) stood in, at its step, for one of them: the
// later effect that stays, acts on a joint of it and reproduces most of what it fitted at its step
// (`parts`) takes its place in the order, so the verdict names what the first step saw (seed 109
// case 34: a PUMA torque gain of 1.22 on joint 1, whose torque is mostly friction, was read at the
// first step as the Coulomb friction of joint 1, which the gain took over at the third step;
// dropped, it left the verdict to a viscous friction of joint 5 half the gain's size; seed 127 case
// 4: a PUMA gain of joint 4 and a viscous friction of the same joint both followed a Coulomb
// friction of joint 4, whose sign the gain's column, the joint's torque, reproduces better; seed 43
// case 11: a Panda contact, whose touches fall in one or two folds, was as good as a payload by the
// folds' spread, the payload was accepted first with a mass of 1 +- 1.3 g, and the contact beside
// it explains all the payload did).
void hand_places_to_successors(Diagnosis& out, std::vector<bool>& gone, std::vector<Eigen::VectorXd>& parts,
                               const Eigen::VectorXd& weight, Eigen::Index n) {
  for (std::size_t k = 0; k < gone.size(); ++k) {
    if (!gone[k]) continue;
    std::vector<std::size_t> successors;
    for (std::size_t later = k + 1; later < gone.size(); ++later) {
      if (!gone[later] && share_a_joint(out.selected[k].joints, out.selected[later].joints))
        successors.push_back(later);
    }
    if (successors.empty()) continue;
    std::size_t later = successors.front();
    if (successors.size() > 1) {
      double most = -1;
      for (const std::size_t j : successors) {
        const double share = share_reproduced(parts[k], out.accepted_effects[j], weight, n);
        if (share > most) {
          most = share;
          later = j;
        }
      }
    }
    // Rotate [k, later] right by one: the successor at k, the gone one and those between after it.
    const auto at = static_cast<std::ptrdiff_t>(k), to = static_cast<std::ptrdiff_t>(later) + 1;
    std::rotate(out.accepted_effects.begin() + at, out.accepted_effects.begin() + to - 1,
                out.accepted_effects.begin() + to);
    std::rotate(out.selected.begin() + at, out.selected.begin() + to - 1, out.selected.begin() + to);
    std::rotate(parts.begin() + at, parts.begin() + to - 1, parts.begin() + to);
    for (std::size_t i = later; i > k; --i) gone[i] = gone[i - 1];
    gone[k] = false;
    ++k;  // the gone one is now at k + 1
  }
}

// Whether effects[k], an effect of the whole arm (a payload, a contact, the inertial parameters),
// is explained by the others: beside all of them (`with`, the joint fit) it no longer removes
// kAcceptShrink of the held-out error, or not significantly over the folds, the test that accepted
// it at its step. (A per-joint effect is narrowed to the joints its own columns still carry
// instead; a whole-arm effect's columns are too entangled for that: a load's mass and moments
// are each within their errors of zero where together they are not.)
bool explained_by_the_others(const std::vector<Effect>& effects, std::size_t k, const CrossValidation& with,
                             const Eigen::VectorXd& r0, const Eigen::VectorXd& weight, const Folds& folds,
                             const Eigen::VectorXd& away, const Eigen::VectorXd& far, const Eigen::VectorXd& scored,
                             Eigen::Index n) {
  std::vector<Effect> others = effects;
  others.erase(others.begin() + static_cast<std::ptrdiff_t>(k));
  Candidate mine;
  mine.cv = with;
  set_shrink(mine, fit_together(others, r0, weight, folds, away, far, n).heldout, weight, n, &scored);
  return mine.shrink < kAcceptShrink || mine.low <= 0.0;
}

// The accepted effects where `gone`, dropped, each one's place in the order to its successor.
void drop_gone(Diagnosis& out, std::vector<bool>& gone, std::vector<Eigen::VectorXd>& parts,
               const Eigen::VectorXd& weight, Eigen::Index n) {
  hand_places_to_successors(out, gone, parts, weight, n);
  for (std::size_t k = gone.size(); k-- > 0;) {
    if (!gone[k]) continue;
    out.accepted_effects.erase(out.accepted_effects.begin() + static_cast<std::ptrdiff_t>(k));
    out.selected.erase(out.selected.begin() + static_cast<std::ptrdiff_t>(k));
    parts.erase(parts.begin() + static_cast<std::ptrdiff_t>(k));
  }
}

// The effects of the whole arm that the others explain (explained_by_the_others), judged in the
// order they were accepted, each beside the effects still kept: of two that explain the same
// (the inertial parameters and a delay, seed 37 case 9), the first goes and the other stays.
void drop_arm_effects_the_others_explain(Diagnosis& out, const Eigen::VectorXd& r0, const Eigen::VectorXd& weight,
                                         Eigen::Index n, std::vector<Eigen::VectorXd>& parts) {
  std::vector<bool> gone(out.accepted_effects.size(), false);
  for (std::size_t k = 0; k < out.accepted_effects.size(); ++k) {
    if (per_joint(out.accepted_effects[k])) continue;
    std::vector<Effect> kept;
    std::size_t mine = 0;
    for (std::size_t i = 0; i < out.accepted_effects.size(); ++i) {
      if (gone[i]) continue;
      if (i == k) mine = kept.size();
      kept.push_back(out.accepted_effects[i]);
    }
    if (kept.size() < 2) break;
    const CrossValidation with = fit_together(kept, r0, weight, out.folds, out.away, out.far, n);
    gone[k] = explained_by_the_others(kept, mine, with, r0, weight, out.folds, out.away, out.far, out.scored, n);
  }
  drop_gone(out, gone, parts, weight, n);
}

// One per-joint effect that two steps both name as an alternative ("coulomb_friction or torque_gain"
// on joint 7, then "payload or torque_gain" on joint 7) and that alone, on the first step's joints,
// explains what the two steps' effects do together (the joint fit not clearly worse) is the
// explanation of both: it takes the first step's place and the later step goes. Each step judged
// alone cannot see it: a gain of 1.22 on the Panda's joint 7, whose torque is mostly the drive's
// friction, ties with a Coulomb friction there, and what is left (the gain's share of the rest of
// the torque) then reads as a payload (blind seed 139 case 59). Not where the later step's leader
// is that effect itself: the first step chose its own leader over it, and the later step found it
// needed beside that leader (the TX40's viscous friction of every joint, with Coulomb as its
// alternative, then a Coulomb friction of joints 3, 4 and 6: read as Coulomb friction alone, fc1
// 27 N m for an a priori 6.8, standing in for the viscous part too).
void one_effect_for_two_steps(Diagnosis& out, const std::vector<std::vector<StepAlternative>>& step_alternatives,
                              const Eigen::VectorXd& r0, const Eigen::VectorXd& weight, Eigen::Index n,
                              std::vector<Eigen::VectorXd>& parts) {
  const std::size_t steps = out.accepted_effects.size();
  if (steps < 2 || step_alternatives.size() != steps) return;
  Candidate all;
  bool fitted = false;
  for (std::size_t i = 0; i < steps; ++i) {
    for (const StepAlternative& named_first : step_alternatives[i]) {
      const Effect& alternative = named_first.effect;
      for (std::size_t k = i + 1; k < steps; ++k) {
        const RankedEffect& later = out.selected[k];
        const std::vector<int>& first_joints = out.selected[i].joints;
        const bool within = std::all_of(later.joints.begin(), later.joints.end(), [&](int j) {
          return std::find(first_joints.begin(), first_joints.end(), j) != first_joints.end();
        });
        const bool named_later =
            std::any_of(step_alternatives[k].begin(), step_alternatives[k].end(),
                        [&](const StepAlternative& a) { return a.effect.family == alternative.family; });
        if (!within || !named_later || alternative.columns.cols() == 0) continue;
        if (!fitted) {
          all = fitted_together(out, out.accepted_effects, r0, weight, n);
          fitted = true;
        }
        std::vector<Effect> merged = out.accepted_effects;
        merged[i] = alternative;
        merged.erase(merged.begin() + static_cast<std::ptrdiff_t>(k));
        const Candidate one = fitted_together(out, merged, r0, weight, n);
        if (clearly_more(all, one) || one.low <= 0.0) continue;
        Eigen::Index at = 0;
        for (std::size_t e = 0; e < i; ++e) at += merged[e].columns.cols();
        parts[i] = alternative.columns * one.cv.theta.segment(at, alternative.columns.cols());
        out.accepted_effects[i] = alternative;
        out.selected[i] = named_first.described;
        std::vector<bool> gone(steps, false);
        gone[k] = true;
        drop_gone(out, gone, parts, weight, n);
        return;  // one merge: the steps' alternatives are indexed by the order before it
      }
    }
  }
}

// The joint fit's coefficients read free of the logged torque's noise where a selected effect's
// columns are made from it (a spring: torque_noise.hpp), into `joint`'s read_theta and read_error.
// What the fit explains, and so which joints each effect keeps, stays the plain least-squares
// fit's: from noisy columns it is the better predictor, the corrected one the unbiased reading
// of the parameters (97/21: a soft Kraft spring of 17.81 N m/rad read 20.58, a rotor inertia
// beside it taking up the difference).
void read_free_of_torque_noise(const std::vector<Effect>& effects, Candidate& joint, const Eigen::VectorXd& r0,
                               const Eigen::VectorXd& weight, const Folds& folds, const Eigen::VectorXd& away,
                               const Eigen::VectorXd& far, Eigen::Index n) {
  if (std::none_of(effects.begin(), effects.end(), [](const Effect& e) { return e.torque_noise != nullptr; })) return;
  const CrossValidation unbiased = fit_together(effects, r0, weight, folds, away, far, n, nullptr, true);
  joint.read_theta = unbiased.theta;
  joint.read_error = unbiased.theta_error;
}

// The held-out residual after each step when `effects` are added in `order`, one at a time.
std::vector<CrossValidation> steps_in_order(const std::vector<Effect>& effects, const std::vector<std::size_t>& order,
                                            const Eigen::VectorXd& r0, const Eigen::VectorXd& weight,
                                            const Diagnosis& out, Eigen::Index n) {
  std::vector<Effect> so_far;
  std::vector<CrossValidation> fits;
  for (const std::size_t k : order) {
    so_far.push_back(effects[k]);
    fits.push_back(fit_together(so_far, r0, weight, out.folds, out.away, out.far, n));
  }
  return fits;
}

// The selection's steps stated again once they are all taken (with the effects as the joint refit
// has narrowed or dropped them): each step's figures are what it removes held out beside the steps
// before it, and a step that removes more than an earlier one comes first (the steps in the order
// accepted, stated again, then ordered by what each removed). A step can come after one that
// removes less where a rule of the selection put the other first: a PUMA contact whose touches
// fall in few folds (75 % [47, 103]) was "as good" as a sensor delay with another effect beside
// it, the delay led, and the contact then removed three times what the delay had (blind seed 229
// case 4). A step's
// figures were those of the effect as accepted: blind seed 211 case 14 accepted a Coulomb friction
// of the Panda's joints 1 and 7 first, whose joint 7 was a torque gain's; narrowed to joint 1 it
// still carried joint 7's gap (0.0498 -> 0.0034 N m) in its figures and in the verdict, and the
// gain's step almost nothing. (Ordered by what each removes alone, a payload beside a torque gain
// of the Kraft's joint 2, which alone it partly mimics, went first: seed 79 case 24.)
// Returns the fit of every effect together in the new order (the joint fit).
CrossValidation restate_steps(Diagnosis& out, const Eigen::VectorXd& r0, const Eigen::VectorXd& weight,
                              Eigen::Index n) {
  const std::size_t m = out.accepted_effects.size();
  const Eigen::Index samples = r0.size() / n;
  auto removed = [&](const std::vector<CrossValidation>& fits) {
    std::vector<double> out_of(fits.size());
    double before = score(r0, weight, n, 0, samples, &out.scored);
    for (std::size_t s = 0; s < fits.size(); ++s) {
      const double after = score(fits[s].heldout, weight, n, 0, samples, &out.scored);
      out_of[s] = before - after;
      before = after;
    }
    return out_of;
  };
  std::vector<std::size_t> order(m);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::vector<CrossValidation> fits = steps_in_order(out.accepted_effects, order, r0, weight, out, n);
  const std::vector<double> as_accepted = removed(fits);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return as_accepted[a] > as_accepted[b]; });
  if (!std::is_sorted(order.begin(), order.end())) {
    std::vector<CrossValidation> reordered = steps_in_order(out.accepted_effects, order, r0, weight, out, n);
    // Kept only where the steps, stated in the new order, still remove less at each step: two
    // effects of one joint that partly cancel (a torque gain and a spring of the Panda's joint 2)
    // each remove much beside the other and little alone, and the later one, moved up, removed
    // 7 % where it had removed more than the gain (blind seed 229 case 29).
    const std::vector<double> as_reordered = removed(reordered);
    if (std::is_sorted(as_reordered.rbegin(), as_reordered.rend())) {
      fits = std::move(reordered);
    } else {
      std::iota(order.begin(), order.end(), std::size_t{0});
    }
  }
  std::vector<Effect> effects;
  std::vector<RankedEffect> steps;
  Eigen::VectorXd baseline = r0;
  for (std::size_t s = 0; s < m; ++s) {
    effects.push_back(out.accepted_effects[order[s]]);
    Candidate c;
    c.cv = fits[s];
    set_shrink(c, baseline, weight, n, &out.scored);
    RankedEffect r = out.selected[order[s]];
    r.before = joint_rms(baseline, n);
    r.after = joint_rms(c.cv.heldout, n);
    r.shrink = c.shrink;
    r.shrink_low = c.low;
    r.shrink_high = c.high;
    steps.push_back(std::move(r));
    baseline = c.cv.heldout;
  }
  out.accepted_effects = std::move(effects);
  out.selected = std::move(steps);
  return std::move(fits.back());
}

// The torque the other selected effects explain (their joint fit's part) that a sensor delay lags
// as it lags the model's: every effect made from the measured positions, not a spring's or a dead
// band's, which the logged torque drives.
Eigen::VectorXd torque_the_positions_lag(const std::vector<Effect>& effects, const Eigen::VectorXd& theta) {
  Eigen::VectorXd part = Eigen::VectorXd::Zero(effects.empty() ? 0 : effects.front().columns.rows());
  Eigen::Index at = 0;
  for (const Effect& e : effects) {
    const bool from_positions = e.family != "sensor_delay" && e.family != "joint_elasticity" && e.family != "backlash";
    for (Eigen::Index c = 0; from_positions && c < e.columns.cols(); ++c) {
      if (std::isfinite(theta[at + c])) part += theta[at + c] * e.columns.col(c);
    }
    at += e.columns.cols();
  }
  return part;
}

// An effect not linear in its parameter (a long delay, a large shift of the positions) has
// columns that are its secants at the value fitted alone (fit_delay_column, fit_shift_columns),
// exact there and a chord elsewhere: read beside the other selected effects, which take up part of
// what it alone stood in for, the value moves off that point and the chord bends it back toward
// it. So the columns are made again at the joint fit's values, twice (the second pass moved a
// delay by 0.03 ms). A 45 ms delay beside a viscous friction of joint 1 (MuJoCo Fourier log at
// 1 kHz: blind seed 443 case 39) was fitted alone at 31 ms, and the joint fit read the secant made
// there as 43.5 ms, 1.4 samples short (now 44.15).
// A delay's column is made again as the lag of all that the positions drive: the model's torque and
// the other effects' fitted part (torque_the_positions_lag), both advanced by the fitted delay. With
// the model's alone, a rotor inertia's lag (ia times the delay times the jerk) had only the delay's
// column on its joint to go to: a 17.3 ms delay beside a rotor inertia of the PUMA's joint 6 read
// 18.45 ms and the inertia 1.9 % light (seed 379 case 4; now 17.42 ms and -0.1 %), the same pair
// at 1 kHz 1.24 samples long (seed 509 case 4; now 0.02). Over the 66 logs of 20 benches where a
// delay is read beside another effect, the delay's mean error went from +0.031 samples to -0.002
// and its mean size from 0.090 to 0.063.
// A shift's column (an offset, a spring, a dead band) is likewise made again with the selected
// loads moved by the shift as the model is: their torque is computed from the measured positions
// too (Effect::standard_change). With the model's change alone, the load's went to the shift: an
// offset of the PUMA's joint 2 beside a 117 g load read +5.4 % (blind seed 563 case 19; now
// +0.01 %), a 0.173 rad offset of the Kraft's joint 2 beside a 47 g load +7.7 % (439/24; now
// -0.04 %, the load +1.6 % -> +0.2 %), a 154 g PUMA load beside a spring of joint 3 +3.0 % (383/19;
// now +0.25 %).
void relinearise_secants(Diagnosis& out, const Eigen::VectorXd& r0, const Eigen::VectorXd& weight, Eigen::Index n) {
  const bool any = std::any_of(out.accepted_effects.begin(), out.accepted_effects.end(),
                               [](const Effect& e) { return static_cast<bool>(e.secant_at); });
  for (int pass = 0; any && pass < 2; ++pass) {
    const Eigen::VectorXd theta = fit_together(out.accepted_effects, r0, weight, out.folds, out.away, out.far, n).theta;
    BesideEffects beside{torque_the_positions_lag(out.accepted_effects, theta), {}};
    Eigen::Index at = 0;
    for (const Effect& e : out.accepted_effects) {
      const Eigen::VectorXd mine = theta.segment(at, e.columns.cols());
      if (e.standard_change && mine.allFinite()) beside.loads.push_back(e.standard_change(mine));
      at += e.columns.cols();
    }
    at = 0;
    for (Effect& e : out.accepted_effects) {
      for (Eigen::Index c = 0; e.secant_at && c < e.columns.cols(); ++c) {
        if (std::isfinite(theta[at + c]))
          e.columns.col(c) = e.secant_at(e.joint_of[static_cast<std::size_t>(c)], theta[at + c], beside);
      }
      at += e.columns.cols();
    }
  }
}

// Whether, stated in order beside the effects before them (restate_steps), some later steps make
// the held-out gap larger: those are dropped (true: the rest must be fitted again). Accepted where
// each step was judged, an effect can lose what it explained once the selection settles: a
// Stribeck friction of the PUMA's joint 6, accepted after a rotor inertia of that joint for how
// the friction turns over at reversals (38 % of what was left), held no excess in the joint fit
// and became its Coulomb friction, which then added 0.2 % to the gap, a torque gain after it 2.4
// %; beside them the rotor inertia read 0.0272 for 0.0314, alone 0.0309 (blind seed 569 case 7,
// open loop at 200 Hz: the one log of 1,500 stored where a step was stated so).
bool drop_steps_that_add_error(Diagnosis& out) {
  bool any = false;
  for (std::size_t k = out.selected.size(); k-- > 1;) {
    if (!(out.selected[k].shrink < 0)) continue;
    out.accepted_effects.erase(out.accepted_effects.begin() + static_cast<std::ptrdiff_t>(k));
    out.selected.erase(out.selected.begin() + static_cast<std::ptrdiff_t>(k));
    any = true;
  }
  return any;
}

// The per-joint parameters the selected effects other than step k fit ("fc2", ...): an effect
// fitted in k's place leaves them out (an alternative's column of the same name is theirs already:
// a Stribeck friction's fc2 beside a selected Coulomb friction of joint 2).
std::vector<std::string> parameters_of_others(const Diagnosis& out, std::size_t k) {
  std::vector<std::string> others;
  for (std::size_t i = 0; i < out.accepted_effects.size(); ++i) {
    if (i == k) continue;
    const Effect& e = out.accepted_effects[i];
    for (std::size_t c = 0; c < e.parameters.size(); ++c) {
      if (e.joint_of[c] >= 0) others.push_back(e.parameters[c]);
    }
  }
  return others;
}

// An effect fitted in a selected step's place, beside every other selected effect (`fit.effect`
// is left for the holder to point at `effect`).
struct InPlace {
  Candidate fit;
  Effect effect;
};

// The effect named `name` (at each of its profile points) narrowed to `joints` (0-based) and
// fitted in step k's place beside the other selected effects, as the joint fit fits step k: the
// point that removes most of the held-out error. None where it has no column there.
std::optional<InPlace> best_in_place(const Diagnosis& out, const std::deque<Effect>& effects, std::size_t k,
                                     const std::string& name, const std::vector<int>& joints, const Eigen::VectorXd& r0,
                                     const Eigen::VectorXd& weight, Eigen::Index n) {
  const std::vector<std::string> others = parameters_of_others(out, k);
  std::optional<InPlace> best;
  for (const Effect& whole : effects) {  // each profile point of the family
    if (whole.name != name || !per_joint(whole)) continue;
    Effect mine = without_fitted(narrowed(whole, joints), others);
    if (mine.columns.cols() == 0) continue;
    std::vector<Effect> in_place = out.accepted_effects;
    in_place[k] = mine;
    Candidate c = fitted_together(out, in_place, r0, weight, n);
    if (!best || c.shrink > best->fit.shrink) best = InPlace{std::move(c), std::move(mine)};
  }
  return best;
}

// The joints (0-based) an effect's per-joint columns act on.
std::vector<int> joints_of(const Effect& e) {
  std::vector<int> joints;
  for (const int j : e.joint_of) {
    if (j >= 0 && std::find(joints.begin(), joints.end(), j) == joints.end()) joints.push_back(j);
  }
  std::sort(joints.begin(), joints.end());
  return joints;
}

// A per-joint step that the joint fit narrowed (it had stood in, on the joints it lost, for a
// later step) was chosen at its step for all of its joints, beside rivals that were judged there
// without that later step; on the joints it keeps, another per-joint effect of a family not
// selected may explain more in its place. The one that removes most beside every other selected
// effect, by more than 1 % of the held-out error and read plausibly, takes the step; the narrowed
// effect is named beside it ("B or A") unless the new one explains clearly more. Blind seed 1033
// case 9 (a MuJoCo tele-operation log of the Kraft): a torque gain of joints 1 and 2 led, its
// joint 2 standing in for an offset of joint 2 found next; narrowed to joint 1 it read 0.907,
// where a rotor inertia of joint 1, not significant at the first step beside no offset, removes
// 79.5 % with the offset (the gain 77.6 %) and reads 0.0624 (truth 0.0604).
void take_rivals_of_narrowed_steps(Diagnosis& out, const std::deque<Effect>& effects,
                                   const std::vector<bool>& narrowed_steps, const Eigen::VectorXd& r0,
                                   const Eigen::VectorXd& weight, Eigen::Index n,
                                   const pipeline::Derivation& derivation) {
  std::optional<Candidate> named;  // the joint fit as named (once, where needed)
  Eigen::Index at = 0;
  for (std::size_t k = 0; k < out.accepted_effects.size(); ++k) {
    const Eigen::Index width = out.accepted_effects[k].columns.cols();
    const Effect& mine = out.accepted_effects[k];
    if (!narrowed_steps[k] || !per_joint(mine)) {
      at += width;
      continue;
    }
    if (!named) named = fitted_together(out, out.accepted_effects, r0, weight, n);
    const std::vector<int> joints = joints_of(mine);
    std::vector<std::string> tried;
    std::optional<InPlace> best;
    for (const Effect& e : effects) {
      if (!per_joint(e) || std::find(tried.begin(), tried.end(), e.name) != tried.end()) continue;
      tried.push_back(e.name);
      const bool selected = std::any_of(out.accepted_effects.begin(), out.accepted_effects.end(),
                                        [&](const Effect& s) { return s.family == e.family; });
      if (selected) continue;
      std::optional<InPlace> rival = best_in_place(out, effects, k, e.name, joints, r0, weight, n);
      if (!rival || !(rival->fit.shrink > named->shrink + 0.01)) continue;
      if (best && rival->fit.shrink <= best->fit.shrink) continue;
      rival->fit.effect = &rival->effect;
      rival->fit.after = joint_rms(rival->fit.cv.heldout, n);
      const RankedEffect read = describe(rival->fit, out.selected[k].before, at, out.gap.torque_rms);
      if (read.joints.empty() || !plausible(read, derivation, out.gap)) continue;
      best = std::move(rival);
    }
    if (best) {
      RankedEffect& r = out.selected[k];
      const std::string former = mine.name;
      const bool clearly = clearly_more(best->fit, *named);
      r.family = best->effect.family;
      r.effect = best->effect.name + (clearly ? std::string() : std::string(kOr) + former);
      r.profile_name = best->effect.profile_name;
      r.profile = best->effect.profile;
      r.columns = static_cast<std::size_t>(best->effect.columns.cols());
      r.alternatives_if_narrowed.clear();
      out.accepted_effects[k] = std::move(best->effect);
      named.reset();  // the joint fit has changed
    }
    at += out.accepted_effects[k].columns.cols();
  }
}

// Once every effect is in: all of them fitted together, each per-joint effect narrowed once more
// to the joints its own columns still carry (an offset of joint 3 that only stood in for a gain
// of joint 5 until the gain came in is dropped), and every effect's parameters read from that
// joint fit rather than from the step that accepted it; one whose own columns carry nothing any
// more is dropped. The stated errors add to the folds' spread how far the fit moves between
// regimes of the motion (regime_error); the parameters are read in applied torque and, a spring's,
// free of the logged torque's noise (read_free_of_torque_noise).
void refit_together(Diagnosis& out, const std::deque<Effect>& effects, const Eigen::VectorXd& r0,
                    const Eigen::VectorXd& weight, Eigen::Index n, const std::vector<RegimeSplit>& splits,
                    std::vector<Eigen::VectorXd> parts, const pipeline::Derivation& derivation) {
  if (out.accepted_effects.empty()) return;
  const std::size_t accepted = out.accepted_effects.size();
  drop_arm_effects_the_others_explain(out, r0, weight, n, parts);
  auto fit = [&]() { return fit_together(out.accepted_effects, r0, weight, out.folds, out.away, out.far, n); };
  Candidate joint;
  joint.cv = fit();
  joint.after = joint_rms(joint.cv.heldout, n);
  bool narrowed_any = false;
  Eigen::Index at = 0;
  std::vector<bool> gone(out.accepted_effects.size(), false);
  std::vector<bool> narrowed_steps(out.accepted_effects.size(), false);
  for (std::size_t k = 0; k < out.accepted_effects.size(); ++k) {
    Effect& e = out.accepted_effects[k];
    const Eigen::Index width = e.columns.cols();
    if (per_joint(e)) {
      joint.effect = &e;
      const std::vector<int> joints = own_joints(joint, at, out.gap.torque_rms);
      if (joints.empty()) {  // the later effects explain all it did
        gone[k] = true;
        narrowed_any = true;
      } else if (joints.size() < out.selected[k].joints.size()) {
        std::vector<int> kept;
        kept.reserve(joints.size());
        for (const int j : joints) kept.push_back(j - 1);
        e = narrowed(e, kept);
        narrowed_any = true;
        narrowed_steps[k] = true;
      }
    }
    at += width;
  }
  for (std::size_t k = gone.size(); k-- > 0;) {
    if (gone[k]) narrowed_steps.erase(narrowed_steps.begin() + static_cast<std::ptrdiff_t>(k));
  }
  drop_gone(out, gone, parts, weight, n);
  if (out.accepted_effects.empty()) {
    out.final_after = joint_rms(r0, n);
    return;
  }
  take_rivals_of_narrowed_steps(out, effects, narrowed_steps, r0, weight, n, derivation);
  // (A step left alone once the others are dropped is stated again too: its figures were those
  // of its step, beside them.)
  if (narrowed_any || out.accepted_effects.size() >= 2 || out.accepted_effects.size() < accepted) {
    joint.cv = restate_steps(out, r0, weight, n);
  }
  if (drop_steps_that_add_error(out)) {
    joint.cv = out.accepted_effects.size() >= 2 ? restate_steps(out, r0, weight, n) : fit();
  }
  arm_rows_in_logged_torque(out.accepted_effects, joint.cv, fit, n);
  joint.after = joint_rms(joint.cv.heldout, n);
  read_free_of_torque_noise(out.accepted_effects, joint, r0, weight, out.folds, out.away, out.far, n);
  joint.systematic = regime_error(out.accepted_effects, r0, weight, out.folds, out.away, out.far, n, splits);
  joint.applied_scale = applied_torque_scale(joint.cv, out.accepted_effects);
  at = 0;
  for (std::size_t k = 0; k < out.accepted_effects.size(); ++k) {
    joint.effect = &out.accepted_effects[k];
    const RankedEffect refitted = describe(joint, out.selected[k].before, at, out.gap.torque_rms);
    if (per_joint(out.accepted_effects[k])) out.selected[k].joints = refitted.joints;
    out.selected[k].parameters = refitted.parameters;
    at += out.accepted_effects[k].columns.cols();
  }
  out.final_after = joint_rms(joint.cv.heldout, n);
}

}  // namespace

// Per joint, whether the held-out mean square on its rows at rest is over kStaticFrictionRatio
// times that on its rows away from zero velocity (`away` 1): a static friction held at rest. The
// rows at rest are those near zero velocity (`away` 0), or only the holds among them where `rests`
// is given (in_long_rests).
std::vector<bool> worse_at_rest(const Eigen::VectorXd& heldout, const Eigen::VectorXd& away,
                                const Eigen::VectorXd* rests, Eigen::Index n) {
  Eigen::VectorXd moving_square = Eigen::VectorXd::Zero(n), rest_square = moving_square;
  Eigen::VectorXd moving_rows = moving_square, rest_rows = moving_square;
  for (Eigen::Index r = 0; r < heldout.size(); ++r) {
    if (away[r] > 0) {
      moving_square[r % n] += heldout[r] * heldout[r];
      moving_rows[r % n] += 1;
    } else if (rests == nullptr || (*rests)[r] > 0) {
      rest_square[r % n] += heldout[r] * heldout[r];
      rest_rows[r % n] += 1;
    }
  }
  std::vector<bool> worse(static_cast<std::size_t>(n), false);
  for (Eigen::Index j = 0; j < n; ++j) {
    worse[static_cast<std::size_t>(j)] =
        moving_rows[j] > 0 && rest_rows[j] > 0 &&
        rest_square[j] / rest_rows[j] > kStaticFrictionRatio * moving_square[j] / moving_rows[j];
  }
  return worse;
}

namespace {

// 1 on every row but those of a joint worse at rest (judged on `away`) that `clear` marks 0: the
// rows the band near zero velocity reaches (`away` itself, or `far`, which lies within it; see
// fit_together).
Eigen::VectorXd rows_without_static_friction(const Eigen::VectorXd& heldout, const Eigen::VectorXd& away,
                                             const Eigen::VectorXd& clear, Eigen::Index n) {
  const std::vector<bool> holds = worse_at_rest(heldout, away, nullptr, n);
  Eigen::VectorXd kept = Eigen::VectorXd::Ones(heldout.size());
  for (Eigen::Index r = 0; r < heldout.size(); ++r) {
    if (clear[r] == 0 && holds[static_cast<std::size_t>(r % n)]) kept[r] = 0;
  }
  return kept;
}

// Every row of a sample where some column acts (above kActing of its largest value) kept.
void keep_rows_where_acting(const Eigen::MatrixXd& columns, Eigen::Index n, Eigen::VectorXd& kept) {
  constexpr double kActing = 0.01;
  for (Eigen::Index k = 0; k < columns.cols(); ++k) {
    const double largest = columns.col(k).cwiseAbs().maxCoeff();
    for (Eigen::Index s = 0; s < columns.rows() / n; ++s) {
      if (columns.col(k).segment(s * n, n).cwiseAbs().maxCoeff() > kActing * largest) kept.segment(s * n, n).setOnes();
    }
  }
}

// The torque noise of the effects' columns made from the logged torque (Effect::torque_noise), as
// NoiseDraws of the joint fit's columns, masked where each is fitted (`fitted`, 0 or 1).
NoiseDraws torque_noise_of(const std::vector<Effect>& effects, const Eigen::MatrixXd& fitted) {
  NoiseDraws out;
  Eigen::Index at = 0;
  std::vector<std::pair<const Effect*, Eigen::Index>> noisy;  // effect, its first column
  for (const Effect& e : effects) {
    if (e.torque_noise != nullptr) noisy.emplace_back(&e, at);
    at += e.columns.cols();
  }
  if (noisy.empty()) return out;
  const std::size_t draws = noisy.front().first->torque_noise->columns.size();
  for (const auto& [e, first] : noisy) {
    for (Eigen::Index k = 0; k < e->columns.cols(); ++k) out.at.push_back(first + k);
  }
  out.target = noisy.front().first->torque_noise->target;  // one log's noise: the same draws for all
  for (std::size_t m = 0; m < draws; ++m) {
    Eigen::MatrixXd columns(fitted.rows(), static_cast<Eigen::Index>(out.at.size()));
    Eigen::Index c = 0;
    for (const auto& [e, first] : noisy) {
      const NoiseDraws& own = *e->torque_noise;
      for (Eigen::Index k = 0; k < e->columns.cols(); ++k, ++c) {
        const auto joint = static_cast<std::size_t>(e->joint_of[static_cast<std::size_t>(k)]);
        columns.col(c) = own.columns[m].col(static_cast<Eigen::Index>(joint)).cwiseProduct(fitted.col(first + k));
      }
    }
    out.columns.push_back(std::move(columns));
  }
  return out;
}

}  // namespace

FittedColumns fitted_columns(const std::vector<Effect>& effects, const Eigen::VectorXd& away) {
  Eigen::Index columns = 0;
  for (const Effect& e : effects) columns += e.columns.cols();
  FittedColumns out{Eigen::MatrixXd(away.size(), columns), Eigen::MatrixXd::Ones(away.size(), columns)};
  Eigen::Index at = 0;
  for (const Effect& e : effects) {
    out.all.middleCols(at, e.columns.cols()) = e.columns;
    if (is_friction(e)) out.fitted.middleCols(at, e.columns.cols()).array().colwise() *= away.array();
    at += e.columns.cols();
  }
  return out;
}

CrossValidation fit_together(const std::vector<Effect>& effects, const Eigen::VectorXd& residual,
                             const Eigen::VectorXd& weight, const Folds& folds, const Eigen::VectorXd& away,
                             const Eigen::VectorXd& far, Eigen::Index n, const Eigen::VectorXd* rows, bool unbiased) {
  auto [all, fitted] = fitted_columns(effects, away);
  if (rows != nullptr) fitted.array().colwise() *= rows->array();
  Eigen::MatrixXd fitted_on = all.cwiseProduct(fitted);
  // Then again without the rows near zero velocity of a joint whose held-out residual there is
  // larger (in mean square) than what it is away from zero after a first fit: there the joint's
  // torque balance holds a static friction anywhere within +-fc (the description's Coulomb
  // friction has the sign of a velocity estimate that is noise), not noise but a bias that takes
  // up part of a load held at rest. An arm that rests most of the time (tele-operation: 75 % of a
  // Kraft log's rows) fitted through it read a payload's mass 22 % low (seed 23 case 57: 0.0081
  // kg for 0.0104; now 0.01046) and a joint's offset 11 % (seed 47 case 9). Where the effects
  // explain the rows near zero as well as the others (a load or a contact held at rest in a
  // model-plant log), they stay: dropped, a payload beside a contact read 8 % low (seed 23 case 54).
  // The rows around them go too, as far as the filter spreads what the joint holds there (`far`,
  // kStaticFrictionLeak): a 10 g MuJoCo tele-operation load at 1 kHz read 4.6 % light when only
  // the rows the band reaches by over 5 % went (blind seed 443 case 57: -6.6 %; now -1.9 %). Not
  // beside a friction effect, whose own evidence is in those rows, where its columns turn over:
  // without them three Stribeck frictions of 15-30 % read `unknown` and one excess 27 % low
  // (blind seeds 97, 257, 379 and 439).
  // Nor do the rows where a contact acts: a hook held on a table is at rest, and without its rows
  // the contact's fit was left to the rows where it barely acts (seed 41 case 33: a push of -4.9 N
  // +- 1e12).
  CrossValidation first = cross_validate(residual, all, n, weight, folds, &fitted_on);
  const bool friction = std::any_of(effects.begin(), effects.end(), [](const Effect& e) { return is_friction(e); });
  Eigen::VectorXd kept = rows_without_static_friction(first.heldout, away, friction ? away : far, n);
  for (const Effect& e : effects) {
    if (e.family == "contact") keep_rows_where_acting(e.columns, n, kept);
  }
  if (kept.minCoeff() < 1) {
    fitted.array().colwise() *= kept.array();
    fitted_on.array().colwise() *= kept.array();
  }
  const NoiseDraws noise = unbiased ? torque_noise_of(effects, fitted) : NoiseDraws{};
  if (kept.minCoeff() == 1 && noise.at.empty()) return first;
  return cross_validate(residual, all, n, weight, folds, &fitted_on, &noise);
}

namespace {

// The per-joint effects a selected "A or B" names beside A, each fitted in A's place (narrowed to
// the joints where A acts: a per-joint A's own, where an effect of the whole arm shrinks the gap;
// at its best profile point) beside every other selected effect, as the final joint fit fits A. The log cannot tell
// them from A, so the user is shown what each would read: a torque gain of 0.834 on the PUMA's joint 1, whose torque is
// mostly the drive's own Coulomb friction, is a Coulomb friction of 5.47 N m there (seed 47 case 34, where that is the
// truth: 5.53). Their errors are the folds' spread alone (no regime split, no correction for the torque's noise): a
// reading for comparison, not a selected effect's full statement.
void fit_alternatives_in_place(Diagnosis& out, const std::deque<Effect>& effects, const Eigen::VectorXd& r0,
                               const Eigen::VectorXd& weight, Eigen::Index n, const pipeline::Derivation& derivation) {
  std::optional<double> named_shrink;  // the selection's joint fit as named (once, where needed)
  Eigen::Index at = 0;
  for (std::size_t k = 0; k < out.selected.size(); ++k) {
    RankedEffect& r = out.selected[k];
    const Eigen::Index width = out.accepted_effects[k].columns.cols();
    std::vector<int> joints;  // 0-based
    for (const int j : r.joints) joints.push_back(j - 1);
    for (const std::string& name : joints.empty() ? std::vector<std::string>{} : alternative_names(r.effect)) {
      std::optional<InPlace> best = best_in_place(out, effects, k, name, joints, r0, weight, n);
      if (!best) continue;
      if (!named_shrink) named_shrink = fitted_together(out, out.accepted_effects, r0, weight, n).shrink;
      best->fit.effect = &best->effect;
      best->fit.after = joint_rms(best->fit.cv.heldout, n);
      const RankedEffect read = describe(best->fit, r.before, at, out.gap.torque_rms);
      r.alternatives.push_back(
          {name, read.parameters, best->fit.shrink, *named_shrink, plausible(read, derivation, out.gap)});
    }
    at += width;
  }
}

// A step's alternatives are judged on the joints where its effect acts at that step; one as good
// on some of those joints only is not an alternative there, but it is once the joint fit narrows
// the effect to those joints, and is then named beside it ("A or B"). A rotor inertia of the
// Kraft's base joint on a MuJoCo tele-operation log at 200 Hz (ia1 0.0303 for 0.03, as good and
// plausible) was read as a spring chosen on joints 1 and 2, which the joint fit narrowed to joint
// 1: the verdict was the spring alone (`dyncc excite` seeds 903, 906 and 909).
void name_alternatives_on_final_joints(Diagnosis& out) {
  for (RankedEffect& r : out.selected) {
    for (const auto& alternative : r.alternatives_if_narrowed) {
      const std::string& name = alternative.first;
      // (Not an effect the selection names at a step of its own.)
      const bool selected = std::any_of(out.selected.begin(), out.selected.end(),
                                        [&](const RankedEffect& other) { return other.family == name; });
      if (alternative.second != r.joints || selected) continue;
      const std::string named = std::string(kOr) + name;
      if (r.effect.find(named) == std::string::npos) r.effect += named;
    }
  }
}

}  // namespace

// The selection's steps judged together once they are all taken: the profile points chosen again
// beside each other, one effect for two steps where it explains both, the joint refit, and the
// named alternatives fitted in the place of the effect they tie with.
void settle_selection(Diagnosis& out, const Dataset& d, const std::deque<Effect>& effects,
                      const std::vector<std::vector<StepAlternative>>& step_alternatives,
                      std::vector<Eigen::VectorXd> step_parts, const pipeline::Derivation& derivation) {
  const Eigen::Index n = d.n;
  const Eigen::VectorXd& r0 = d.residual;
  const std::vector<RegimeSplit> splits = regime_splits(d, out.away);
  rechoose_points(out, effects, r0, out.weight, n, splits, derivation);
  place_loads_again(out, effects, d, derivation, r0, out.weight, n, step_parts);
  one_effect_for_two_steps(out, step_alternatives, r0, out.weight, n, step_parts);
  relinearise_secants(out, r0, out.weight, n);
  refit_together(out, effects, r0, out.weight, n, splits, std::move(step_parts), derivation);
  // Judged again as the joint fit reads them (a step judged each beside the effects before it
  // only): a payload that stood in for a torque gain read 0.09 g at 17 m beside a Stribeck
  // friction accepted after it (blind seed 229 case 9). Stated, not dropped.
  for (RankedEffect& r : out.selected) r.plausible = plausible(r, derivation, out.gap);
  name_alternatives_on_final_joints(out);
  fit_alternatives_in_place(out, effects, r0, out.weight, n, derivation);
}

}  // namespace dyncc::diagnose
