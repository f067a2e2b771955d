// How many log rows the diagnosis hands the model's tapes at once (NumericModel's batch
// evaluation, CompiledFunction::evaluate_rows): enough to fill the tapes' blocks with the moved
// states of each row, few enough to keep the blocks small. One number for every stage that
// evaluates the model along a log.
#pragma once

#include <Eigen/Core>

namespace dyncc::diagnose {

inline constexpr Eigen::Index kModelRowsPerBatch = 64;

}  // namespace dyncc::diagnose
