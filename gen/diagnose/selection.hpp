// The forward selection's stages, shared by the files that make it up (not a public interface:
// diagnosis.hpp is). A candidate effect judged held out (candidate.cpp), what its fit reads as
// (reading.cpp), which candidate a step names (step_choice.cpp), the selection judged together
// once it is taken (settle.cpp), and the steps themselves (diagnosis.cpp).
#pragma once

#include <Eigen/Dense>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "diagnose/contact_effect.hpp"
#include "diagnose/crossval.hpp"
#include "diagnose/diagnosis.hpp"
#include "diagnose/effects.hpp"
#include "diagnose/gap.hpp"
#include "pipeline/derivation.hpp"

namespace dyncc::diagnose {

// Between the names of effects a log cannot tell apart ("A or B").
inline constexpr std::string_view kOr = " or ";
inline constexpr double kAcceptShrink = 0.05;  // an effect must remove 5 % of the weighted held-out error
inline constexpr double kMaterial = 0.015;     // ... and explain at least 1.5 % of some joint's torque RMS
inline constexpr double kStudent95 = 2.776;    // t quantile, 4 degrees of freedom (5 folds)

struct Candidate {
  const Effect* effect = nullptr;
  CrossValidation cv;
  double shrink = 0, low = 0, high = 0;
  std::vector<double> folds;  // the shrink of each held-out fold
  Eigen::VectorXd after;
  double explained = 0;    // sum over joints of (before^2 - after^2) / torque_rms^2
  double material = 0;     // largest per-joint explained RMS / torque RMS
  bool plausible = true;   // its fitted parameters make physical sense
  double away_shrink = 0;  // the shrink on the rows where the velocity is away from zero
  // A friction's held-out residual with its own columns fitted on the rows away from zero velocity
  // only, as the final joint fit fits them (fit_together): what its shrink and interval there are
  // read from. Empty: cv's (an effect judged there that is fitted on every row).
  Eigen::VectorXd away_heldout;
  [[nodiscard]] const Eigen::VectorXd& heldout_away() const {
    return away_heldout.size() > 0 ? away_heldout : cv.heldout;
  }
  // Per column of cv, the error beyond the folds' spread (regime_error); only for the final joint
  // fit, whose parameters are reported: the steps judge significance on the folds alone.
  Eigen::VectorXd systematic;
  // Per column of cv, what its coefficient is multiplied by to be read in applied torque
  // (applied_torque_scale); empty: 1. Final joint fit only, like `systematic`.
  Eigen::VectorXd applied_scale;
  // Per column of cv, the coefficient and its error as read for the parameters where they differ
  // from the fit's (read_free_of_torque_noise); empty: cv's. Final joint fit only.
  Eigen::VectorXd read_theta, read_error;
  // A friction's 95 % interval on those rows of its own joints, over the folds in which they move
  // (see away_interval); empty (low above high) where fewer than three folds do.
  double away_low = std::numeric_limits<double>::infinity();
  double away_high = -std::numeric_limits<double>::infinity();
  // The folds that interval is over and their weighted sums of squares on those rows before and
  // after (held out), per joint: what a comparison with another friction there is made from.
  std::vector<int> away_joints;
  std::vector<Eigen::Index> away_folds;
  Eigen::MatrixXd away_before, away_after;  // folds x joints
  // Significant where its joints move: an interval there (three moving folds or more) above zero.
  [[nodiscard]] bool significant_away() const { return away_low > 0.0 && away_low <= away_high; }
  // Significant only where its joints move (its interval over all rows includes zero).
  [[nodiscard]] bool significant_only_away() const { return low <= 0.0 && significant_away(); }
};

// Pairs of candidates that the rows where their joints move tell apart (closer_where_moving): the
// winner's family and the loser, which is then no alternative of the winner.
using Decided = std::vector<std::pair<std::string, const Candidate*>>;

// A per-joint effect that a step named as an alternative ("A or B"), narrowed to the step's joints,
// and what it explains there on top of the effects accepted before that step.
struct StepAlternative {
  Effect effect;
  RankedEffect described;
};

// What a selection step judges a candidate on: the residual, the fit accepted so far and its
// held-out residual.
struct StepState {
  const Eigen::MatrixXd& accepted;
  const Eigen::VectorXd &r0, &baseline, &weight;
  const Folds& folds;
  const Eigen::VectorXd& away;
  const Eigen::VectorXd& before;  // per joint, the held-out RMS so far
  const Gap& gap;
  const pipeline::Derivation& derivation;
};

// Which candidates a rule may consider (usable, acceptable, may lead a pair).
using CandidateTest = std::function<bool(const Candidate*)>;

// candidate.cpp
double score(const Eigen::VectorXd& stacked, const Eigen::VectorXd& weight, Eigen::Index n, Eigen::Index begin,
             Eigen::Index end, const Eigen::VectorXd* scored);
bool is_friction(const Effect& e);
bool judged_away_from_zero(const Effect& e);
double point_key(const Candidate& c);
double student95(std::size_t dof);
bool as_good_as(const Candidate& c, const Candidate& top);
void set_away_interval(Candidate& c, const Eigen::VectorXd& baseline, const Eigen::VectorXd& weight,
                       const Eigen::VectorXd& away, const std::vector<int>& joints, Eigen::Index n);
bool clearly_more(const Candidate& a, const Candidate& b);
bool better_by_the_margin(const Candidate& a, const Candidate& b);
void set_shrink(Candidate& c, const Eigen::VectorXd& baseline, const Eigen::VectorXd& weight, Eigen::Index n,
                const Eigen::VectorXd* scored = nullptr);
Candidate evaluate(const Effect& effect, const Eigen::MatrixXd& accepted, const Eigen::VectorXd& r0,
                   const Eigen::VectorXd& baseline, const Eigen::VectorXd& weight, const Folds& folds, Eigen::Index n,
                   const Eigen::VectorXd* scored = nullptr);
Eigen::VectorXd heldout_fitted_away(const Effect& effect, const Eigen::MatrixXd& accepted, const Eigen::VectorXd& r0,
                                    const Eigen::VectorXd& weight, const Folds& folds, const Eigen::VectorXd& away,
                                    Eigen::Index n);
Candidate evaluate_point(const Effect& effect, const Eigen::MatrixXd& accepted, const Eigen::VectorXd& r0,
                         const Eigen::VectorXd& baseline, const Eigen::VectorXd& weight, const Folds& folds,
                         const Eigen::VectorXd& away, Eigen::Index n, const Eigen::VectorXd* scored = nullptr);
void measure(Candidate& c, const Eigen::VectorXd& before, const Eigen::VectorXd& torque_rms, Eigen::Index accepted);
bool spans(const Eigen::MatrixXd& outer, const Eigen::MatrixXd& inner);
Eigen::Index columns_on(const Effect& e, const std::vector<int>& joints);
Effect kept_columns(const Effect& e, const std::function<bool(std::size_t)>& keep_column);
Effect narrowed(const Effect& e, const std::vector<int>& joints);
bool shares_fitted(const Effect& e, const std::vector<std::string>& fitted);
Effect without_fitted(const Effect& e, const std::vector<std::string>& fitted);
double half_point_spread(const Candidate& c);
bool clearly_above(const Candidate& c, const Candidate& mine);
bool acceptable(const Candidate* c);

// reading.cpp
double physical(Reading reading, double theta);
bool per_joint(const Effect& e);
bool shifts_positions(const Effect& e);
std::optional<FittedParameter> surface_push(const Candidate& c, Eigen::Index offset);
std::vector<int> own_joints(const Candidate& c, Eigen::Index offset, const Eigen::VectorXd& torque_rms);
RankedEffect describe(const Candidate& c, const Eigen::VectorXd& before, Eigen::Index offset,
                      const Eigen::VectorXd& torque_rms);
std::vector<int> plausible_joints(const Effect& e, const RankedEffect& r, const pipeline::Derivation& derivation,
                                  const Gap& gap);

// step_choice.cpp
const Candidate* first_of_a_smaller_pair(const Candidate* chosen, const std::vector<const Candidate*>& order,
                                         const std::map<std::string, Candidate>& best, const CandidateTest& acceptable,
                                         const CandidateTest& can_lead, const Eigen::MatrixXd& accepted,
                                         const Eigen::VectorXd& r0, const Eigen::VectorXd& baseline,
                                         const Eigen::VectorXd& weight, const Folds& folds, Eigen::Index n,
                                         const Eigen::VectorXd& scored);
bool share_a_joint(const std::vector<int>& a, const std::vector<int>& b);
const Candidate* simplest_equal(const Candidate* top, const std::vector<const Candidate*>& order,
                                const CandidateTest& usable, const Eigen::VectorXd& before, Eigen::Index offset,
                                const Eigen::VectorXd& torque_rms);
std::string alternatives(const Candidate& chosen, const Candidate& top, const std::vector<const Candidate*>& order,
                         const CandidateTest& usable, Eigen::Index offset, const Eigen::VectorXd& torque_rms,
                         std::vector<const Candidate*>& named, const Decided& decided,
                         std::vector<std::pair<std::string, std::vector<int>>>& if_narrowed);
Candidate narrowed_at_best_point(const Effect& chosen, const std::vector<int>& kept, const std::deque<Effect>& effects,
                                 const std::vector<std::string>& fitted, std::deque<Effect>& store,
                                 const Eigen::MatrixXd& accepted, const Eigen::VectorXd& r0,
                                 const Eigen::VectorXd& baseline, const Eigen::VectorXd& weight, const Folds& folds,
                                 const Eigen::VectorXd& away, Eigen::Index n, const Eigen::VectorXd& scored);
std::vector<StepAlternative> per_joint_alternatives(const std::vector<const Candidate*>& named,
                                                    const RankedEffect& step, const StepState& s,
                                                    const Eigen::VectorXd& scored);
std::vector<int> own_joints_of_effect(const Candidate& chosen, const RankedEffect& r, const StepState& s,
                                      const std::deque<Effect>& effects, const std::map<std::string, Candidate>& best,
                                      const std::vector<std::string>& taken, const std::vector<std::string>& fitted,
                                      const Eigen::VectorXd& scored, bool* lost_to_simpler = nullptr);
const Candidate* closer_where_moving(const Candidate* pick, const Candidate& top,
                                     const std::vector<const Candidate*>& order, const CandidateTest& usable,
                                     const StepState& s, Decided& decided);

// settle.cpp
std::vector<bool> worse_at_rest(const Eigen::VectorXd& heldout, const Eigen::VectorXd& away,
                                const Eigen::VectorXd* rests, Eigen::Index n);
void settle_selection(Diagnosis& out, const Dataset& d, const std::deque<Effect>& effects,
                      const std::vector<std::vector<StepAlternative>>& step_alternatives,
                      std::vector<Eigen::VectorXd> step_parts, const pipeline::Derivation& derivation);

}  // namespace dyncc::diagnose
