// Which candidate a selection step names: parsimony among equal explanations (the fewest
// columns, the first of a smaller pair that stands in for a large set), the alternatives it
// cannot be told from ("A or B"), and the comparisons where a joint moves that tell a friction,
// a rotor inertia and a gain apart.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include "diagnose/plausibility.hpp"
#include "diagnose/selection.hpp"

namespace dyncc::diagnose {

namespace {
bool closer_where_the_joint_moves(const Candidate& a, const Candidate& b, int joint, const StepState& s);
}  // namespace

// Parsimony over two steps: a large column set (the whole inertial parameter set re-identified)
// that two smaller effects explain together as well as it does alone (a rotor inertia and a
// payload) is not the explanation: the stronger of the pair leads, the next step takes the other.
// Not for a per-joint effect: it is narrowed to the joints where it acts instead (counted with its
// columns on every joint, a Stribeck friction of the PUMA's joint 1 was a set of twelve that a
// delay and a spring stood in for, and the delay was named first: seed 101 case 4).
const Candidate* first_of_a_smaller_pair(const Candidate* chosen, const std::vector<const Candidate*>& order,
                                         const std::map<std::string, Candidate>& best, const CandidateTest& acceptable,
                                         const CandidateTest& can_lead, const Eigen::MatrixXd& accepted,
                                         const Eigen::VectorXd& r0, const Eigen::VectorXd& baseline,
                                         const Eigen::VectorXd& weight, const Folds& folds, Eigen::Index n,
                                         const Eigen::VectorXd& scored) {
  if (per_joint(*chosen->effect)) return chosen;
  const Eigen::Index size = chosen->effect->columns.cols();
  const double as_good = chosen->shrink - 0.5 * (chosen->high - chosen->low);
  for (const Candidate* first : order) {
    const Eigen::Index first_size = first->effect->columns.cols();
    if (first == chosen || !acceptable(first) || first_size >= size) continue;
    Eigen::MatrixXd with_first(accepted.rows(), accepted.cols() + first_size);
    with_first << accepted, first->effect->columns;
    for (const auto& [name, second] : best) {
      if (&second == first || &second == chosen || second.effect->family == first->effect->family ||
          first_size + second.effect->columns.cols() >= size) {
        continue;
      }
      const Candidate pair = evaluate(*second.effect, with_first, r0, baseline, weight, folds, n, &scored);
      if (pair.shrink < as_good || pair.low <= first->shrink) continue;
      // The pair's stronger member leads, even one that gave way to the set before (seed 43 case
      // 49: a PUMA torque gain of joint 2, narrowed, gave way to the inertial parameters, which
      // then gave way to a spring of joint 3 that explains a third as much, paired with it).
      return second.shrink > first->shrink && can_lead(&second) ? &second : first;
    }
  }
  return chosen;
}

// Whether two joint lists have a joint in common.
bool share_a_joint(const std::vector<int>& a, const std::vector<int>& b) {
  return std::any_of(a.begin(), a.end(), [&](int j) { return std::find(b.begin(), b.end(), j) != b.end(); });
}

// Of the usable candidates as good as `top` (as_good_as) that explain some of the same joints,
// the one with the fewest columns. (A candidate as good by the folds' spread that explains other
// joints is not an alternative but the next step's effect: a spring of the Panda's joint 2, 38 %,
// led a Stribeck friction of joint 1, 58 % over a wide interval, by having fewer columns: seed
// 127 case 59.)
const Candidate* simplest_equal(const Candidate* top, const std::vector<const Candidate*>& order,
                                const CandidateTest& usable, const Eigen::VectorXd& before, Eigen::Index offset,
                                const Eigen::VectorXd& torque_rms) {
  const std::vector<int> top_joints = describe(*top, before, offset, torque_rms).joints;
  auto of_the_same_joints = [&](const Candidate* c) {
    const std::vector<int> joints = describe(*c, before, offset, torque_rms).joints;
    return joints.empty() || top_joints.empty() || share_a_joint(joints, top_joints);
  };
  const Candidate* pick = top;
  for (const Candidate* c : order) {
    if (usable(c) && as_good_as(*c, *top) && c->effect->columns.cols() < pick->effect->columns.cols() &&
        of_the_same_joints(c)) {
      pick = c;
    }
  }
  return pick;
}

// " or B or C": the usable candidates as good as the leading one whose columns are not a superset
// of the chosen ones (the same explanation with more freedom) nor more than twice as many. Where
// each spans the other with as many columns (on the chosen joints), the log cannot tell them apart
// and each is the other's alternative: on a Kraft tele-operation log whose base joint's torque is
// nearly all its inertia's, a torque gain's column there is within 5 % of a rotor inertia's, and a
// gain of 1.055 was read as a rotor inertia alone (blind seed 157 case 42). (A Stribeck friction
// whose fade is nearly a sign at its scale spans a Coulomb friction and is spanned by it, but with
// a column more: the same explanation with more freedom still.)
std::string alternatives(const Candidate& chosen, const Candidate& top, const std::vector<const Candidate*>& order,
                         const CandidateTest& usable, Eigen::Index offset, const Eigen::VectorXd& torque_rms,
                         std::vector<const Candidate*>& named, const Decided& decided,
                         std::vector<std::pair<std::string, std::vector<int>>>& if_narrowed) {
  std::string out;
  std::vector<int> joints;  // the chosen per-joint effect's joints (0-based)
  if (per_joint(*chosen.effect)) joints = chosen.effect->joint_of;
  std::sort(joints.begin(), joints.end());
  joints.erase(std::unique(joints.begin(), joints.end()), joints.end());
  for (const Candidate* c : order) {
    if (c == &chosen || !usable(c) || !as_good_as(*c, top) ||
        std::find(decided.begin(), decided.end(), std::make_pair(chosen.effect->family, c)) != decided.end()) {
      continue;
    }
    const bool on_joints = !joints.empty() && per_joint(*c->effect);
    if (spans(c->effect->columns, chosen.effect->columns)) {
      const Eigen::MatrixXd theirs = on_joints ? narrowed(*c->effect, joints).columns : c->effect->columns;
      if (theirs.cols() != chosen.effect->columns.cols() || !spans(chosen.effect->columns, theirs)) continue;
    }
    if (on_joints) {
      // Another per-joint effect is an alternative where it acts on the same joints, counted
      // there: the Coulomb friction of six joints against the torque gain of joint 1 it ties with
      // is one column; Coulomb friction of joints 1-3 is not an alternative to a viscous friction of
      // joint 3 (it explains something else on joints 1 and 2).
      std::vector<int> theirs = own_joints(*c, offset, torque_rms);
      for (int& j : theirs) --j;
      if (!theirs.empty() && theirs.size() < joints.size() &&
          std::includes(joints.begin(), joints.end(), theirs.begin(), theirs.end())) {
        std::vector<int> one_based = theirs;
        for (int& j : one_based) ++j;
        if_narrowed.emplace_back(c->effect->name, std::move(one_based));
      }
      if (theirs != joints || columns_on(*c->effect, joints) > 2 * chosen.effect->columns.cols()) continue;
    } else if (c->effect->columns.cols() > 2 * chosen.effect->columns.cols()) {
      continue;
    }
    out += std::string(kOr) + c->effect->name;
    named.push_back(c);
  }
  return out;
}

// The joints of a per-joint effect where it IS: a joint whose part another per-joint effect
// explains better on its own (viscous friction of joint 3 that Coulomb columns of joint 3 half
// absorb) is left for that effect's turn; the columns of the remaining joints are accepted.
// ... and a joint that a simpler per-joint effect (fewer columns there: Coulomb against
// Stribeck) explains as well is left for that one (`lost_to_simpler` is then set): a Coulomb
// friction of joint 2 is not a Stribeck friction of joints 2 and 5 because joint 5 has one.
std::vector<int> own_joints_of_effect(const Candidate& chosen, const RankedEffect& r, const StepState& s,
                                      const std::deque<Effect>& effects, const std::map<std::string, Candidate>& best,
                                      const std::vector<std::string>& taken, const std::vector<std::string>& fitted,
                                      const Eigen::VectorXd& scored, bool* lost_to_simpler) {
  const Eigen::Index n = s.before.size();
  std::vector<int> kept;
  for (const int joint : r.joints) {
    const Effect mine_effect = narrowed(*chosen.effect, {joint - 1});
    const Candidate mine = evaluate(mine_effect, s.accepted, s.r0, s.baseline, s.weight, s.folds, n, &scored);
    bool beaten = false;
    for (const Effect& e : effects) {
      // An effect whose fit over the arm is implausible never takes its turn (a joint left for
      // it stays unexplained: the TX40's joint 2 was left for springs whose wrist is 0.5 rad
      // soft).
      const auto whole = best.find(e.name);
      if (beaten || e.family == chosen.effect->family || !per_joint(e) ||
          std::find(taken.begin(), taken.end(), e.family) != taken.end() ||
          (whole != best.end() && !whole->second.plausible)) {
        continue;
      }
      const Effect theirs = without_fitted(narrowed(e, {joint - 1}), fitted);
      if (theirs.columns.cols() == 0) continue;
      const Candidate other =
          evaluate_point(theirs, s.accepted, s.r0, s.baseline, s.weight, s.folds, s.away, n, &scored);
      const bool better = better_by_the_margin(other, mine);
      const bool simpler_and_as_good = theirs.columns.cols() < mine_effect.columns.cols() &&
                                       !clearly_more(mine, other) && !better_by_the_margin(mine, other);
      // ... nor one that explains nothing where the velocity is away from zero, where it must
      // (a spring of the PUMA's joint 1 explained 38 % of a log whose joint 1 has a viscous
      // friction of 4.3, all of it at reversals: every friction and the gain gave joint 1 to
      // it, and a contact of a second, smaller effect was named alone; blind seed 149 case 34).
      const bool may_take =
          other.low > 0.0 && (!judged_away_from_zero(theirs) || other.away_shrink >= kAcceptShrink) &&
          plausible(describe(other, s.before, s.accepted.cols(), s.gap.torque_rms), s.derivation, s.gap);
      // Where the joint moves (closer_where_the_joint_moves): one that leaves clearly less there
      // than `mine` takes the joint if `mine` is not better by the margin over all rows (the
      // PUMA's joints 4 and 6, their torques mostly their drives' friction, had a Coulomb friction
      // of joint 4 and a gain of joint 6 named as one gain of both, gain4 0.911: blind seed 463
      // case 34), and one that leaves clearly more there does not take it even where it is better
      // over all rows.
      // (One that leaves clearly less there is never also clearly more: the second test is spared.)
      const bool theirs_closer =
          may_take && !better_by_the_margin(mine, other) && closer_where_the_joint_moves(other, mine, joint - 1, s);
      beaten = may_take && (better || simpler_and_as_good || theirs_closer) &&
               (theirs_closer || !closer_where_the_joint_moves(mine, other, joint - 1, s));
      if (beaten && simpler_and_as_good && lost_to_simpler != nullptr) *lost_to_simpler = true;
    }
    if (!beaten) kept.push_back(joint - 1);
  }
  return kept;
}

// `chosen` narrowed to the joints `kept`, its candidate stored in `store`. A profile effect's
// point is chosen again on those joints, but only where another point is clearly better (by more
// than half the fold spread): the point that suited every joint together (a Stribeck scale bent
// to fit a Coulomb friction of another joint) need not suit these, yet on one joint whose excess
// is near the noise where it moves, the best point there is a draw of that noise (seed 61 case
// 18: the step's scale 0.1 gave way to 0.15, and fs1 read 0.054 for 0.0705).
Candidate narrowed_at_best_point(const Effect& chosen, const std::vector<int>& kept, const std::deque<Effect>& effects,
                                 const std::vector<std::string>& fitted, std::deque<Effect>& store,
                                 const Eigen::MatrixXd& accepted, const Eigen::VectorXd& r0,
                                 const Eigen::VectorXd& baseline, const Eigen::VectorXd& weight, const Folds& folds,
                                 const Eigen::VectorXd& away, Eigen::Index n, const Eigen::VectorXd& scored) {
  std::optional<Candidate> own;
  std::optional<Candidate> best;
  for (const Effect& whole : effects) {
    if (chosen.profile_name.empty() || whole.name != chosen.name) continue;
    store.push_back(narrowed(without_fitted(whole, fitted), kept));
    Candidate c = evaluate_point(store.back(), accepted, r0, baseline, weight, folds, away, n, &scored);
    if (whole.profile == chosen.profile) own = c;
    if (!best || point_key(c) > point_key(*best)) best = std::move(c);
  }
  if (own && best && point_key(*best) <= point_key(*own) + half_point_spread(*own)) return *own;
  if (best) return *best;
  store.push_back(narrowed(chosen, kept));  // not a profile effect: as it is
  return evaluate(store.back(), accepted, r0, baseline, weight, folds, n, &scored);
}

// The per-joint effects among a step's named alternatives, narrowed to the step's joints (`step`,
// as selected) and evaluated there on top of the effects accepted before it.
std::vector<StepAlternative> per_joint_alternatives(const std::vector<const Candidate*>& named,
                                                    const RankedEffect& step, const StepState& s,
                                                    const Eigen::VectorXd& scored) {
  std::vector<int> joints;  // 0-based
  for (const int j : step.joints) joints.push_back(j - 1);
  const Eigen::Index n = s.before.size();
  std::vector<StepAlternative> out;
  for (const Candidate* c : named) {
    if (!per_joint(*c->effect)) continue;
    StepAlternative a{narrowed(*c->effect, joints), {}};
    a.described = describe(evaluate(a.effect, s.accepted, s.r0, s.baseline, s.weight, s.folds, n, &scored), s.before,
                           s.accepted.cols(), s.gap.torque_rms);
    a.described.accepted = true;
    out.push_back(std::move(a));
  }
  return out;
}

namespace {

// The squared residual that `c` leaves on the rows of `joints` (0-based) where the velocity is away
// from zero, per fold of `folds` (set_away_interval's sums), its own columns fitted on such rows.
std::vector<double> left_where_moving(const Candidate& c, const std::vector<int>& joints,
                                      const std::vector<Eigen::Index>& folds, const StepState& s) {
  const Eigen::Index n = s.before.size();
  Candidate mine = c;
  mine.away_heldout = heldout_fitted_away(*c.effect, s.accepted, s.r0, s.weight, s.folds, s.away, n);
  set_away_interval(mine, s.baseline, s.weight, s.away, joints, n);
  std::vector<double> out;
  for (const Eigen::Index f : folds) {
    double after = 0;
    for (const int j : joints) after += mine.away_after(f, j);
    out.push_back(after);
  }
  return out;
}

// Whether two per-joint effects that explain a step alike are told apart where their joint moves
// (closer_where_moving): a friction and another kind, and a rotor inertia and a torque gain.
bool compared_where_moving(const Effect& a, const Effect& b) {
  if (is_friction(a) != is_friction(b)) return true;
  return (a.family == "rotor_inertia" && b.family == "torque_gain") ||
         (a.family == "torque_gain" && b.family == "rotor_inertia");
}

// Whether `c` may be named over a rival where its joints move: a rotor inertia only if it reads an
// inertia the drive can have, its fitted change and the description's reflected inertia together
// not below zero at the point estimate (plausible_parameter with no allowance for the error). A
// torque gain above one makes a joint look lighter, which a rotor inertia can mimic only by going
// negative: a gain of 1.11 on the Kraft's base joint beside a viscous friction of it, the friction
// not yet fitted, read ia1 -0.060 for a described 0.041, and where the joint moves that rotor
// inertia left less than the gain in every fold (blind seed 281 case 54).
bool may_lead_where_moving(const Candidate& c, const StepState& s) {
  if (c.effect->family != "rotor_inertia") return true;
  for (FittedParameter p : describe(c, s.before, s.accepted.cols(), s.gap.torque_rms).parameters) {
    p.error = 0;
    if (!plausible_parameter(p, s.derivation, s.gap)) return false;
  }
  return true;
}

// Whether what one candidate leaves where its joints move, per fold (`by_a`), is clearly less than
// what another leaves there (`by_b`): less in every fold (at least three), and by `ratio` over them.
bool clearly_less(const std::vector<double>& by_a, const std::vector<double>& by_b, double ratio) {
  if (by_a.size() < 3) return false;
  for (std::size_t k = 0; k < by_a.size(); ++k) {
    if (!(by_a[k] < by_b[k])) return false;
  }
  return std::accumulate(by_b.begin(), by_b.end(), 0.0) >= ratio * std::accumulate(by_a.begin(), by_a.end(), 0.0);
}

// The ratio by which one of a pair compared where its joints move must leave less there: a
// friction against another kind by kCloserWhereMoving (closer_where_moving says why), a rotor
// inertia against a torque gain by any amount, fold by fold.
double ratio_where_moving(const Effect& a, const Effect& b) {
  constexpr double kCloserWhereMoving = 1.2;
  return is_friction(a) != is_friction(b) ? kCloserWhereMoving : 1.0;
}

// Whether `a` leaves clearly less than `b` where `joint` (0-based) moves, at the first step: the
// two are of the kinds compared where a joint moves (compared_where_moving), `a` may be named there
// and leaves clearly less there, by closer_where_moving's test. Over all rows a friction and
// another kind are compared mostly on the rows near reversals, where the model's own friction
// turns over otherwise than the plant's: the PUMA's joint 5, whose torque is mostly its 0.85 N m
// Coulomb friction, had a torque gain of 1.11 (read 1.106, 81 % held out) that a Stribeck friction
// at 0.02 rad/s took the joint from (88 %), a Coulomb friction took it from the Stribeck's, the
// Stribeck from the Coulomb's, and nothing was named; where the joint moves the gain leaves a
// sixteenth of what that Stribeck friction does (blind seed 457 case 1). Only at the first step:
// beside an accepted effect that has taken what a friction does where its joint moves, what is
// left of that friction is at the reversals (a gain of joints 2, 3 and 5 stood in for a Coulomb
// friction of the PUMA's joint 5 beside a payload; a rotor inertia of joint 5 that left less than
// the friction where the joint moves kept the joint at the third step, and the joint fit then read
// a gain of 0.84 and a negative rotor inertia where the Coulomb friction had been named: blind
// seed 353 case 4).
bool closer_where_the_joint_moves(const Candidate& a, const Candidate& b, int joint, const StepState& s) {
  if (s.accepted.cols() > 0) return false;
  if (!compared_where_moving(*a.effect, *b.effect) || !may_lead_where_moving(a, s)) return false;
  Candidate moving = a;  // only for the folds in which the joint moves
  set_away_interval(moving, s.baseline, s.weight, s.away, {joint}, s.before.size());
  const std::vector<int> joints{joint};
  return clearly_less(left_where_moving(a, joints, moving.away_folds, s),
                      left_where_moving(b, joints, moving.away_folds, s), ratio_where_moving(*a.effect, *b.effect));
}

}  // namespace

// Of two per-joint effects that explain a step alike (as_good_as its leader) on a joint in common
// and are compared where it moves (compared_where_moving), the one that leaves clearly less there
// leads: less in every fold in which the joint moves (at least three), and by `ratio` over them.
// The one left behind is then no alternative (Decided).
// - A friction and another effect (a torque gain), by kCloserWhereMoving: over all rows the two
//   are compared mostly on the rows near reversals, where the model's own friction turns over
//   differently from the plant's and what is left is that floor, not either effect: the PUMA's
//   joint 1, whose torque is mostly its drive's 26 N m Coulomb friction, had a Coulomb friction of
//   1.36 named "torque_gain or coulomb_friction" with the gain first by 54.1 % to 53.8 % held out;
//   where the joint moves the gain leaves 5.8 times what the friction does, in every fold (blind
//   seed 251 case 4), and beside a gain of 1.11 there a Coulomb friction leaves 900 times what the
//   gain does (blind seed 241 case 52).
// - A rotor inertia and a torque gain, in every fold alone: on a joint whose torque is mostly its
//   own inertia's (the Kraft's base joint carries no gravity) the two columns differ only by what
//   the gain also scales, the joint's Coriolis and friction torques, which act where it moves, and
//   there the other kind left only 6-66 % more than the injected one, in every fold (blind seed 269
//   cases 9 and 57: a Kraft tele-operation rotor inertia and gain of the base joint, each read as
//   the other; seven more "A or B" with the injected one first). A rotor inertia that reads a
//   negative inertia is not named so (may_lead_where_moving): where a friction of the joint is not
//   yet fitted, that friction is what is left where the joint moves, and the rotor inertia standing
//   in for a gain above one left less of it than the gain.
const Candidate* closer_where_moving(const Candidate* pick, const Candidate& top,
                                     const std::vector<const Candidate*>& order, const CandidateTest& usable,
                                     const StepState& s, Decided& decided) {
  if (!per_joint(*pick->effect)) return pick;
  const Eigen::Index n = s.before.size();
  const bool pick_may_lead = may_lead_where_moving(*pick, s);
  for (const Candidate* c : order) {
    if (c == pick || !usable(c) || !per_joint(*c->effect) || !as_good_as(*c, top) ||
        !compared_where_moving(*c->effect, *pick->effect)) {
      continue;
    }
    std::vector<int> joints;  // 0-based, where the two are compared
    std::vector<Eigen::Index> folds;
    if (is_friction(*c->effect) != is_friction(*pick->effect)) {
      const Candidate& friction = is_friction(*c->effect) ? *c : *pick;
      const Candidate& other = is_friction(*c->effect) ? *pick : *c;
      std::vector<int> theirs = describe(other, s.before, s.accepted.cols(), s.gap.torque_rms).joints;
      for (int& j : theirs) --j;
      if (!share_a_joint(friction.away_joints, theirs)) continue;
      joints = friction.away_joints;
      folds = friction.away_folds;
    } else {
      const std::vector<int> mine = describe(*pick, s.before, s.accepted.cols(), s.gap.torque_rms).joints;
      for (const int j : describe(*c, s.before, s.accepted.cols(), s.gap.torque_rms).joints) {
        if (std::find(mine.begin(), mine.end(), j) != mine.end()) joints.push_back(j - 1);
      }
      if (joints.empty()) continue;
      Candidate moving = *pick;  // only for the folds in which `joints` move (not what it leaves there)
      set_away_interval(moving, s.baseline, s.weight, s.away, joints, n);
      folds = moving.away_folds;
    }
    const bool c_may_lead = may_lead_where_moving(*c, s);
    if (folds.size() >= 3) {
      const double ratio = ratio_where_moving(*c->effect, *pick->effect);
      const std::vector<double> by_c = left_where_moving(*c, joints, folds, s);
      const std::vector<double> by_pick = left_where_moving(*pick, joints, folds, s);
      if (clearly_less(by_pick, by_c, ratio) && pick_may_lead) decided.emplace_back(pick->effect->family, c);
      if (clearly_less(by_c, by_pick, ratio) && c_may_lead) {
        decided.emplace_back(c->effect->family, pick);
        return c;
      }
    }
    // Not told apart: the one that reads a possible inertia is named first, the other as its
    // alternative (281/54 is "torque_gain or rotor_inertia").
    if (!pick_may_lead && c_may_lead) return c;
  }
  return pick;
}

}  // namespace dyncc::diagnose
