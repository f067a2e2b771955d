// The logs conditioned for identification and the nominal model evaluated along them: filtered
// positions and their derivatives, filtered torques, the model's torque with the description's
// nominal parameters, its regressors and its sensitivity to the positions. Every later stage
// (effects, fits, the verdict) works on these stacked rows: row s*n + i is joint i at sample s.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <vector>

#include "diagnose/joint_log.hpp"
#include "diagnose/signals.hpp"
#include "pipeline/derivation.hpp"

namespace dyncc::diagnose {

/// Velocity scale (rad/s) over which Coulomb friction turns over, in the nominal model and in the
/// friction effects alike: the sign of a filtered velocity estimate near zero is noise.
inline constexpr double kSignVelocity = 0.002;
/// The sign of a velocity smoothed over `scale` (rad/s).
inline double smooth_sign(double velocity, double scale) { return std::tanh(velocity / scale); }
/// The sign of a velocity as the nominal model's friction sees it, smoothed over kSignVelocity.
inline double smooth_sign(double velocity) { return smooth_sign(velocity, kSignVelocity); }
/// How a static friction excess fades with speed (Stribeck), over the velocity scale `scale`.
inline double stribeck_fade(double velocity, double scale) {
  const double v = velocity / scale;
  return std::exp(-v * v);
}

struct ConditioningOptions {
  double cutoff = 0;  // Hz; 0 = automatic, min(rate / 8, 4 Hz)
  // The torque column is a command a digital controller holds from its row until the next one
  // (zero-order hold), not a torque measured at the row's instant: on average it acts half a
  // period after its time stamp, a lag that would otherwise read as part of a sensor delay.
  bool held_torque = false;
};

/// Two sets of rows. Evaluation rows (at most kEvaluationRate, from filtered positions): where
/// the model, its regressors and the effect columns are evaluated. Analysis rows: what the fits
/// use, after the SAME zero-phase low-pass has been applied to the logged torque and to every
/// model column (parallel filtering: a torque step from Coulomb friction and its model column are
/// smoothed alike), edges trimmed, decimated to about 8 rows per filter period.
///
/// Everything passes that filter twice. A column made from the filtered positions through a
/// smooth function (an inertial torque, a viscous friction) had its first pass in the positions;
/// the logged torque, and a friction's sign (sharp at each reversal, in the log and in the
/// model), get it from `prefilter`; `condition` is the second pass for all. Passed once, the
/// torque kept a band the model's inertial torque had lost (the residual held F (1 - F) of the
/// torque, wherever the acceleration stepped), which a closed loop's Stribeck excess took up
/// (read 10-11 % high) and its sensor delay (read up to a sample long). The one exception is
/// measured, not derived: a contact's columns, made from the only anti-aliased positions, pass
/// once; through both passes the stored bench named two more contacts right, but four logs that
/// tests keep (brief touches, a held hook, a contact beside a friction or a load) read worse.
struct Dataset {
  Eigen::Index n = 0;  // joints
  std::vector<std::string> logs;
  std::vector<Audit> audits;
  double cutoff = 0;         // Hz, of the zero-phase filter
  bool held_torque = false;  // the torque was read as a held command (ConditioningOptions)

  // Evaluation rows (stacked over logs; row s*n + i of a stacked matrix is joint i at row s).
  Eigen::VectorXd t;  // per log's own clock
  std::vector<int> log_of;
  Eigen::MatrixXd q, qd, qdd, tau;  // tau only anti-aliased here
  // Positions only anti-aliased, as the torque: where a nonlinear function of them acts within a
  // filter period (a table touched for 30 ms), it is evaluated on these and filtered after, as the
  // torque it adds is; on the low-passed q the touch's dip is smoothed away.
  Eigen::MatrixXd q_sharp;
  // The nominal model (Coulomb with the smoothed sign) after its first pass: its rigid-body part
  // made from the filtered positions, its friction part filtered (see prefilter).
  Eigen::MatrixXd model_tau;
  Eigen::MatrixXd model_friction;  // its friction part (the description's, Coulomb smoothed alike), not filtered
  Eigen::MatrixXd model_tau_rate;  // d model_tau / dt
  Eigen::MatrixXd base_rigid;      // S*n x r': base regressor without friction columns
  std::vector<std::string> base_rigid_names;
  Eigen::MatrixXd standard;              // S*n x p: standard regressor (for the payload link's columns)
  std::vector<Eigen::MatrixXd> dtau_dq;  // S of n x n: d model_tau / dq
  [[nodiscard]] Eigen::Index samples() const { return t.size(); }

  // Evaluation rows -> analysis rows.
  struct Segment {
    Eigen::Index begin = 0, end = 0;  // evaluation rows of one log
    double rate = 0;                  // Hz of those rows
    std::vector<Eigen::Index> keep;   // offsets (from begin) kept as analysis rows
  };
  std::vector<Segment> segments;
  /// Filters every column of a stacked (S*n x k) matrix along time, per joint and per log, and
  /// keeps the analysis rows: (A*n x k).
  [[nodiscard]] Eigen::MatrixXd condition(const Eigen::MatrixXd& stacked) const;
  /// The first pass of the filter (see above): the same filter along time, per joint and per
  /// log, every evaluation row kept (S*n x k).
  [[nodiscard]] Eigen::MatrixXd prefilter(const Eigen::MatrixXd& stacked) const;

  // Analysis rows.
  double step = 0;             // s between analysis rows (of the slowest log)
  Eigen::VectorXd analysis_t;  // A
  std::vector<int> analysis_log;
  Eigen::MatrixXd analysis_qd, analysis_qdd, analysis_tau;  // A x n
  Eigen::VectorXd residual;  // A*n: logged torque - model torque, each through both passes
  // Per joint: the RMS over the analysis rows of how far the filtered rigid-body model torque moves
  // when the positions move by their noise (see position_noise_torque in dataset.cpp).
  Eigen::VectorXd position_noise_torque;
  [[nodiscard]] Eigen::Index rows() const { return analysis_t.size(); }
};

/// Per joint: how far the filtered velocity estimate may be off (rad/s), one standard error from
/// the positions' noise and quantisation (the worst log) through the filter's bandwidth. A
/// velocity this close to zero has no reliable sign.
Eigen::VectorXd velocity_error(const Dataset& d);

/// Per joint, the velocity (rad/s) over which the friction candidates' sign turns over: the
/// velocity estimate's own error, not less than kSignVelocity. Where the estimate is noise (in a
/// hold) the sign is not known, and the columns predict next to no friction instead of a random
/// +-fc (on tele-operation logs with 1.5 mrad potentiometer steps one fold's holds swung the
/// held-out interval below zero).
Eigen::VectorXd friction_sign_velocity(const Dataset& d);

/// Per stacked analysis row (A*n): 1 where joint i's velocity is away from zero, 0 where the band
/// |qd| < max(kTurnOverBand, twice the velocity error) leaks into the row through the filter (its
/// filtered indicator above `leak`, kBandLeak unless told). Near zero a joint's friction is not a
/// function of the velocity estimate (stiction in a hold, a turn-over of its own shape at a
/// reversal), so what explains residual only there is no evidence of a friction effect.
inline constexpr double kTurnOverBand = 0.03;  // rad/s: regularised or sigmoid friction turns over within ~0.01
inline constexpr double kBandLeak = 0.05;
/// Where a joint's rows near zero hold a static friction (settle.cpp, worse_at_rest), what it
/// holds there is any torque within +-fc, and the filter spreads it into the rows around: a
/// slow reversal of a loaded joint that sticks for a moment spreads a bias its load's columns
/// take up. The joint fit leaves out every row of such a joint that the band reaches beyond this
/// share, unless a friction effect is in the fit (fit_together). At kBandLeak, 10 g loads on the MuJoCo plant's
/// tele-operation logs (which sticks: its friction is a constraint) read 4.6 % light at 1 kHz and 4.1 % at 500 Hz (12
/// runs each; 9 and 8 of them beyond the bench's 3 %); at this, 1.3 % and 1.1 % (2 and 1 beyond). Without the plant's
/// dry friction they read +0.7 %. At 200 Hz the plant's friction is softer (its step is 5 ms) and such loads read -0.1
/// % at kBandLeak and -1.6 % at this (1 and 5 of 11 beyond).
inline constexpr double kStaticFrictionLeak = 0.001;
Eigen::VectorXd away_from_zero_velocity(const Dataset& d, double leak = kBandLeak);

/// Per-joint weights that make every joint count relative to its own torque: 1 / torque RMS (floored
/// at 1e-3 of the largest, so a joint that carries nothing does not dominate).
Eigen::VectorXd torque_weights(const Eigen::VectorXd& torque_rms);
/// The joint weights spread over stacked rows (row r is joint r % n).
Eigen::VectorXd stacked_weights(const Eigen::VectorXd& joint_weights, Eigen::Index rows);
/// The torque RMS per joint of the analysis rows' logged torque.
Eigen::VectorXd analysis_torque_rms(const Dataset& d);

/// Conditions the logs and evaluates the model. Throws LogError when a log is too short for the
/// filter (fewer than kMinimumSamples rows left after the edges are trimmed).
Dataset build_dataset(const std::vector<JointLog>& logs, const pipeline::Derivation& derivation,
                      const ConditioningOptions& options = {});

}  // namespace dyncc::diagnose
