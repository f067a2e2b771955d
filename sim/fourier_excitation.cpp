#include "fourier_excitation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>

namespace dyncc::sim {
FourierExcitation::FourierExcitation(unsigned seed, double scale) : scale_(scale) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> phase(0.0, 2 * std::numbers::pi), size(0.5, 1.0);
  for (int j = 0; j < kDof; ++j) {
    // Amplitudes falling with the harmonic (so accelerations stay moderate), then scaled so their
    // sum is the joint's reach: the excursion can never leave the range. The joints' base
    // frequencies differ by a few per cent so their motions do not stay in step.
    std::array<double, kHarmonics> a{};
    double sum = 0;
    for (int k = 0; k < kHarmonics; ++k) {
      a[k] = size(random) / (k + 1);
      sum += a[k];
    }
    const double omega = 2 * std::numbers::pi * kBaseFrequency * (1.0 + 0.07 * j);
    for (int k = 0; k < kHarmonics; ++k) waves_.push_back({kReach[j] * a[k] / sum, omega * (k + 1), phase(random)});
  }
}

TrajectoryPoint FourierExcitation::at(double t) const {
  // Fade-in window w(t) = 10u^3 - 15u^4 + 6u^5 over kFadeIn: q = middle + w f, so with f's
  // derivatives qd = w' f + w f', qdd = w'' f + 2 w' f' + w f''.
  const double u = std::clamp(t / kFadeIn, 0.0, 1.0);
  const double w = u * u * u * (10 - 15 * u + 6 * u * u);
  const double w1 = t < kFadeIn ? 30 * u * u * (1 - u) * (1 - u) / kFadeIn : 0.0;
  const double w2 = t < kFadeIn ? 60 * u * (1 - u) * (1 - 2 * u) / (kFadeIn * kFadeIn) : 0.0;
  TrajectoryPoint out;
  for (int j = 0; j < kDof; ++j) {
    double f = 0, f1 = 0, f2 = 0;
    for (int k = 0; k < kHarmonics; ++k) {
      const Wave& v = waves_[static_cast<std::size_t>(j) * kHarmonics + static_cast<std::size_t>(k)];
      const double s = std::sin(v.omega * t + v.phase), c = std::cos(v.omega * t + v.phase);
      f += scale_ * v.amplitude * s;
      f1 += scale_ * v.amplitude * v.omega * c;
      f2 -= scale_ * v.amplitude * v.omega * v.omega * s;
    }
    out.q[j] = kMiddle[j] + w * f;
    out.qd[j] = w1 * f + w * f1;
    out.qdd[j] = w2 * f + 2 * w1 * f1 + w * f2;
  }
  return out;
}

}  // namespace dyncc::sim
