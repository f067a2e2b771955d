// Compile-only check that the controller path builds the way firmware builds it: float, no
// exceptions, no RTTI, warnings as errors (flags in tests/runtime.cmake). Nothing runs here;
// the firmware image under QEMU runs the same instantiation.
#include "dyncc/runtime/position_estimator.hpp"
#include "dyncc/runtime/slotine_li_controller.hpp"
#include "kraft/model.hpp"

namespace {
using Model = dyncc::generated::kraft_right::Model;
}  // namespace

template class dyncc::runtime::SlotineLiController<Model, float>;
template class dyncc::runtime::PositionEstimator<Model::dof, float>;
