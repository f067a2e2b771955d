// The zero-phase filter of signals.hpp over many signals at once (implemented in signals.cpp).
#pragma once

#include <Eigen/Dense>

namespace dyncc::diagnose {

/// Rows are samples, each column a signal: a sample's columns are side by side in memory.
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// zero_phase_lowpass of every column of x in place (the same numbers, to the last bit), the
/// columns filtered side by side: faster than one at a time, whose recurrence waits on its own
/// previous output at every sample (Dataset::condition filters some 400 columns for the contact's
/// candidates of one log).
void zero_phase_lowpass_rows(RowMatrix& x, double cutoff, double rate);

}  // namespace dyncc::diagnose
