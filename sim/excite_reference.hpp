// What an excitation run tracks, and when: the Fourier excitation, or the master arm's motion in
// the paper's tele-operation task (simulated once by the scenario code, on the rigid plant,
// `paper-unloaded` or, when the hidden effect is a payload, `paper-0.5kg` with that payload, and
// followed through a cubic spline of its 81 Hz samples). The task also says when the payload is on
// the hook (from the pick-up to its release) and where the table is (the paper's, which the
// operator presses on from about 7 s to 17 s).
#pragma once

#include <functional>

#include "excite.hpp"
#include "operator.hpp"

namespace dyncc::sim {

struct ExciteReference {
  std::function<TrajectoryPoint(double)> at;
  double attach = 0.0;        // s, the payload goes on the hook (the Fourier run: from the start)
  double release = -1.0;      // s, and comes off (-1: never)
  double low_hook = 0.0;      // m, base frame: how low the hook goes (the Fourier run's: in kTouchedPeriods of
                              // its periods; the tele-operation run's: its lowest point); a contact's depth
                              // puts the table that far above it
  double table_height = 0.0;  // m: where a table is unless the contact effect says otherwise
};

/// The base periods of the Fourier run in which its hook goes as low as `low_hook` at least.
inline constexpr int kTouchedPeriods = 3;

/// The Fourier run's table: this far above the reference's low hook point, so the arm presses
/// on it at its lowest swings only, briefly and lightly (about 10-20 % of the torque RMS with the
/// paper's table friction; the depth is the contact effect's size).
inline constexpr double kDefaultTableDepth = 0.01;  // m

/// The reference of `settings` (its trajectory, duration, seed and payload).
ExciteReference excite_reference(const ExciteSettings& settings);

}  // namespace dyncc::sim
