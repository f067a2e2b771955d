// The library of candidate unmodelled effects. Each one is a set of extra regressor columns over
// the stacked rows of a Dataset (row s*n + i: joint i at sample s), linear in its parameters
// (linearised about the nominal model where the effect itself is not linear: a delay, an
// offset, a compliance), so every candidate is fitted by the same least squares and compared by
// the same held-out error. Effects with a shape parameter (the Stribeck velocity) come once per
// value of a small grid: a one-dimensional profile with a linear fit at each point.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "diagnose/crossval.hpp"
#include "diagnose/dataset.hpp"

namespace dyncc::diagnose {

/// How a fitted column value turns into the effect's physical parameter.
enum class Reading { as_is, reciprocal, gain };

/// A value of an effect chosen by a search rather than fitted (when a load was picked up), reported
/// beside the fitted parameters with the search's resolution as its error.
struct ShapeValue {
  std::string name;
  double value = 0, resolution = 0;
};

/// A change of the description's standard parameters (NumericModel's order) that an effect's
/// fitted values mean (a load on the payload link), and where it holds: `gate` keeps the
/// evaluation rows (S*n x k) of the stretch it holds in and zeroes the others (empty: everywhere).
struct StandardChange {
  Eigen::VectorXd values;
  std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)> gate;
};

/// What the other selected effects fit, beside which an effect's columns are made again
/// (Effect::secant_at): their torque computed from the measured positions (analysis rows, A*n;
/// empty: none), which a delay lags as it lags the model's, and the loads among them, which a
/// shift of the positions moves as it moves the model.
struct BesideEffects {
  Eigen::VectorXd from_positions;
  std::vector<StandardChange> loads;
};

struct Effect {
  std::string name;                     // the JSON vocabulary: coulomb_friction, payload, ...
  Eigen::MatrixXd columns;              // S*n x k
  std::vector<std::string> parameters;  // per column, e.g. "fc2", "mass", "delay"
  std::vector<int> joint_of;            // per column: the joint it belongs to (0-based), -1 shared
  std::vector<Reading> reading;         // per column
  std::string profile_name;             // "velocity_scale" for a profile effect, else empty
  double profile = 0;
  std::vector<ShapeValue> shape;
  // A profile of more than one dimension: its coordinates, where a local search may start from (a
  // contact: ContactPoint::coordinates).
  std::vector<double> profile_point;
  std::string family;  // effects of one family are alternatives of each other
  // Where the columns are made from the logged torque (a spring's): that torque's noise in them,
  // per joint (`at` the joints, not columns), for reading the parameters unbiased (torque_noise.hpp).
  std::shared_ptr<const NoiseDraws> torque_noise;
  // An effect not linear in its parameter (a sensor delay, a shift of the positions) has columns
  // that are secants made at a first fit. This makes joint j's column (-1: a shared one) again at
  // theta, conditioned (the tangent where that serves), beside the other selected effects (a
  // delay lags their torque, a shift moves their loads). It refers to the Dataset the effect was
  // made from: called while the diagnosis runs (settle.cpp), not after. Empty for the others.
  std::function<Eigen::VectorXd(int joint, double theta, const BesideEffects& beside)> secant_at;
  // An effect that is a change of the standard parameters (a load): that change at `theta`, its
  // columns' coefficients. Empty for the others.
  std::function<StandardChange(const Eigen::VectorXd& theta)> standard_change;
};

/// A backlash shows only on a joint whose transmitted torque turns over: with its less common sign
/// less than this share of the time, the link sits on one side of the dead band, which is a
/// position offset (the diagnosis leaves such a joint's backlash column out; the bench does not
/// draw it).
inline constexpr double kBacklashTurnOver = 0.1;
/// rad: the most a transmission plausibly gives way, RMS under its joint's torque (a spring), or
/// half of it (a dead band's width is at most twice this); beyond, a joint is loose or the
/// description wrong. The bench draws within it, the diagnosis refuses fits beyond it.
inline constexpr double kLargestDeflection = 0.05;

/// Whether an effect's columns are sharp in time where the logged torque is (a friction's sign
/// turning over at a reversal): they get the filter's first pass from Dataset::prefilter, as the
/// logged torque does; every other effect's columns are made from the filtered positions, which
/// had it.
bool sharp_in_time(std::string_view effect);

/// An effect's columns at the evaluation rows (S*n x k) into the analysis rows, through the
/// filter's two passes as the logged torque goes (the first from prefilter where they are sharp).
Eigen::MatrixXd conditioned_columns(const Dataset& d, std::string_view effect, const Eigen::MatrixXd& stacked);

/// The payload link: the deepest link without children (ties: the heaviest), where a tool or a
/// hook carries a load.
int payload_link(const pipeline::Derivation& derivation);

/// Every candidate for the data (friction, payload, delay, gain, offset, compliance, backlash,
/// rotor inertia, and the description's own inertial parameters), built on the evaluation rows
/// and conditioned into the analysis rows. The contact's are ContactRows' (contact_effect.hpp):
/// the diagnosis keeps its geometry for the search it runs from them. `rests` (A*n, 1 in a
/// joint's holds: in_long_rests) are left out of the payload window's search.
std::vector<Effect> candidate_effects(const Dataset& data, const pipeline::Derivation& derivation,
                                      const Eigen::VectorXd& rests);

}  // namespace dyncc::diagnose
