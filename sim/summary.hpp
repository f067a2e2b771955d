// What a run shows, in the paper's terms: RMS of each tracking error s_i before the pick-up,
// while holding the payload and after the put-down; how long the errors take to settle after the
// payload leaves the table; how far the estimates drift while pressing on the table; the final p^.
//
// Windows: "before" from 1 s to the first contact (the reach); "holding" from 1 s after both the
// lift-off and the end of the operator's lift to the put-down (the settling transient is its
// own figure, `reconvergence`); "after" from 1 s after the payload is left on the table to the end.
#pragma once

#include <string>
#include <vector>

#include "scenario.hpp"

namespace dyncc::sim {

struct Summary {
  std::string scenario, plant;
  bool adaptation = true;
  double payload = 0;
  Joints rms_before{}, rms_holding{}, rms_after{};  // rad/s
  double first_contact = -1;                        // s: the hook reaches the payload
  double lift_off = -1;                             // s: the payload clears the table (after the pick-up)
  double lift_delay = -1;     // s: lift_off minus the operator's lift start (the paper: "release is delayed")
  double reconvergence = -1;  // s after lift_off until the s2, s3 errors settle; -1 = they do not
  double press_drift = 0;     // |change of the first-moment estimates M*| over the press / |their true values|
  Parameters final_estimate{};
};

Summary summarize(const Run& run);

/// A plain-text table (one row per run) of the RMS figures and timings.
std::string summary_table(const std::vector<Summary>& rows);
/// The final estimates of several runs side by side (one column per run).
std::string estimate_table(const std::vector<Summary>& rows);

/// RMS of s_joint over samples with t in [from, to).
double rms(const Run& run, int joint, double from, double to);

}  // namespace dyncc::sim
