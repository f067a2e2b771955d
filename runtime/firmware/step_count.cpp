// Firmware for counting instructions: runs DYNCC_STEPS control steps of the Kraft controller
// (float) on varying inputs and exits, printing nothing in between. Built twice (0 and 100
// steps); report.sh counts the instructions QEMU executes for each, and the difference / 100 is
// the cost of one step.
#include "control_loop.hpp"
#include "semihosting.hpp"

#ifndef DYNCC_STEPS
#define DYNCC_STEPS 0
#endif

int main() {
  using Controller = dyncc::runtime::SlotineLiController<dyncc::firmware::KraftModel, float>;
  Controller::Settings settings;
  for (auto& g : settings.gamma_inverse) g = 0.05f;
  Controller::Parameters initial{};
  for (int b = 0; b < Controller::r; ++b)
    initial[b] = static_cast<float>(dyncc::firmware::KraftModel::initial_estimate[b]);
  Controller controller(settings, initial);
  volatile float sink = 0.0f;  // keeps every step's result alive
  for (int step = 0; step < DYNCC_STEPS; ++step) {
    const float t = static_cast<float>(step) * settings.period;
    const Controller::Joints q{0.1f * t, -0.2f + 0.05f * t, 0.3f}, qd{0.4f, -0.1f, 0.2f * t}, zero{},
        qdd{0.5f, 0.1f, -0.3f};
    sink = sink + controller.step(q, qd, zero, zero, qdd).tau[0];
  }
  dyncc::firmware::write("done\n");
  return 0;
}
