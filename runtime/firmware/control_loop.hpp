// The fixed stream the firmware test runs, shared by the Cortex-M4 image (float) and the host
// reference (double): 3 s of the paper's 81 Hz loop on the generated Kraft model. A desired
// sum-of-sines motion, a "measured" position that lags it by a known pattern, the position
// estimator, and the adaptive Slotine-Li controller from the paper's initial estimate.
// Everything is computed inside the program: no input files on the target.
#pragma once

#include <cmath>

#include "dyncc/runtime/position_estimator.hpp"
#include "dyncc/runtime/slotine_li_controller.hpp"
#include "kraft/model.hpp"

namespace dyncc::firmware {

using KraftModel = dyncc::generated::kraft_right::Model;
inline constexpr int kSteps = 243;  // 3 s at 81 Hz

/// Runs the loop; emit(label, index, value) receives every output: the command torque of
/// every step ("tau", step * 3 + joint) and the final estimate ("p", parameter).
template <typename S, typename Emit>
void run_control_loop(Emit&& emit) {
  using Controller = runtime::SlotineLiController<KraftModel, S>;
  constexpr int n = KraftModel::dof;
  constexpr int r = KraftModel::parameters;
  typename Controller::Settings settings;
  settings.lambda = S(3.14159265358979);  // 1/2 Hz bandwidth (ERRATA 8)
  settings.feedback = runtime::Feedback::lambda_H;
  settings.period = S(1) / S(81);
  for (int b = 0; b < r; ++b) settings.gamma_inverse[b] = S(0.05);
  typename Controller::Parameters initial{};
  for (int b = 0; b < r; ++b) initial[b] = static_cast<S>(KraftModel::initial_estimate[b]);
  Controller controller(settings, initial);
  runtime::PositionEstimator<n, S> estimator(settings.period, S(16));

  for (int step = 0; step < kSteps; ++step) {
    const S t = static_cast<S>(step) * settings.period;
    typename Controller::Joints q_des{}, qd_des{}, qdd_des{}, measured{};
    for (int k = 0; k < n; ++k) {
      const S w = S(1.1) + S(0.4) * static_cast<S>(k);
      const S amplitude = S(0.4);
      q_des[k] = amplitude * std::sin(w * t);
      qd_des[k] = amplitude * w * std::cos(w * t);
      qdd_des[k] = -amplitude * w * w * std::sin(w * t);
      measured[k] = q_des[k] + S(0.05) * std::sin(S(0.7) * t + static_cast<S>(k)) - S(0.02);
    }
    estimator.update(measured);
    const auto out = controller.step(estimator.position(), estimator.velocity(), q_des, qd_des, qdd_des);
    for (int k = 0; k < n; ++k) emit("tau", step * n + k, out.tau[k]);
  }
  for (int b = 0; b < r; ++b) emit("p", b, controller.estimate()[b]);
}

}  // namespace dyncc::firmware
