// placeholder: the plots are being written in this issue.
#include <stdexcept>

#include "plot.hpp"

namespace dyncc::sim {
void write_figure(const Figure& /*figure*/, const std::filesystem::path& /*stem*/) {
  throw std::runtime_error("plots are not built yet");
}
}  // namespace dyncc::sim
