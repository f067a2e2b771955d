// The greatest common divisor of 128-bit integers, which rational arithmetic and the collection of
// rational coefficients both reduce by (std::gcd does not take __int128 in strict C++20).
#pragma once

#include "sym/rational.hpp"

namespace dyncc::sym {

/// gcd(|a|, |b|); gcd(0, 0) == 0.
Int128 wide_gcd(Int128 a, Int128 b);

}  // namespace dyncc::sym
