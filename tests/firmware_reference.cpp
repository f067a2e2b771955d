// Host reference of the firmware test: the same control loop (runtime/firmware/control_loop.hpp)
// in double, printed as "label index value" with every digit, then "done".
#include <cstdio>

#include "control_loop.hpp"

int main() {
  dyncc::firmware::run_control_loop<double>(
      [](const char* label, int index, double value) { std::printf("%s %d %.17g\n", label, index, value); });
  std::printf("done\n");
  return 0;
}
