// What the report measures on a signal of uniformly spaced samples: its amplitude spectrum (where
// in frequency a residual lives: the motion's harmonics, a resonance, noise) and its correlation
// with another signal by lag (a delay between two signals shows as a peak off zero).
#pragma once

#include <Eigen/Dense>

namespace dyncc::diagnose {

struct Spectrum {
  Eigen::VectorXd frequency;  // Hz, from 0 to the Nyquist frequency
  Eigen::VectorXd amplitude;  // a sinusoid of amplitude A between two bins reads close to A
};

/// Single-sided amplitude spectrum of `x` sampled at `rate` Hz: mean removed, Hann window,
/// zero-padded to a power of two. Empty for fewer than 2 samples.
Spectrum amplitude_spectrum(const Eigen::VectorXd& x, double rate);

struct Correlation {
  Eigen::VectorXd lag;    // s, from -max_lag to +max_lag in steps of 1 / rate
  Eigen::VectorXd value;  // Pearson correlation of a(t) with b(t + lag) over the samples both have
};

/// Normalised cross-correlation of `a` and `b` (same length, sampled at `rate` Hz) at every lag
/// up to `max_lag` seconds either way (at most a quarter of the record). A lag where a signal is
/// constant over the overlap gets 0.
Correlation cross_correlation(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double rate, double max_lag);

/// The lag of the largest value, refined between samples by the parabola through it and its
/// neighbours. 0 for an empty correlation.
double peak_lag(const Correlation& c);

}  // namespace dyncc::diagnose
