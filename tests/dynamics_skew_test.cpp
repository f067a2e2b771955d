// The symbolic skew-symmetry proof (Hdot - 2C skew  <=>  Hdot_ij - C_ij - C_ji == 0 for i <= j,
// decided by the trigonometric normal form) accepts dyncc's Christoffel C and REJECTS wrong ones:
// one Christoffel term with its sign flipped, and the misprinted eq. (2) of the paper (ERRATA 1).
//
// A transposed C is NOT a negative case for this property: Hdot - C^T - C is the same sum, so
// C^T passes the skew-symmetry test exactly as C does. It is a wrong Coriolis matrix all the same
// (C^T qd != C qd), which the Newton-Euler comparison detects; the last test pins both facts down.
#include <gtest/gtest.h>

#include <random>

#include "dynamics_support.hpp"
#include "sym/diff.hpp"
#include "sym/trig_normal_form.hpp"

namespace dyncc::test {
namespace {

using sym::Expr;
using sym::ZeroVerdict;

struct SkewResult {
  int zero = 0, nonzero = 0, unknown = 0;
  std::string first_nonzero;
};

SkewResult skew_check(const dyn::Matrix& Hdot, const dyn::Matrix& C) {
  SkewResult r;
  for (std::size_t i = 0; i < C.size(); ++i) {
    for (std::size_t j = i; j < C.size(); ++j) {
      const sym::ZeroTestResult z = sym::test_zero(Hdot[i][j] - C[i][j] - C[j][i]);
      if (z.verdict == ZeroVerdict::Zero) {
        ++r.zero;
      } else if (z.verdict == ZeroVerdict::NonZero) {
        if (r.nonzero++ == 0)
          r.first_nonzero = std::string("N").append(std::to_string(i + 1)).append(std::to_string(j + 1));
      } else {
        ++r.unknown;
      }
    }
  }
  return r;
}

class SkewSymmetry : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    d_ = derive_file(robots_dir() / GetParam());
    ASSERT_TRUE(d_);
    Hdot_ = dyn::mass_matrix_rate(d_->model);
  }
  std::unique_ptr<pipeline::Derivation> d_;
  dyn::Matrix Hdot_;
};

TEST_P(SkewSymmetry, HoldsForTheChristoffelMatrix) {
  const SkewResult r = skew_check(Hdot_, d_->model.C);
  const int n = static_cast<int>(d_->model.q.size());
  EXPECT_EQ(r.zero, n * (n + 1) / 2);
  EXPECT_EQ(r.nonzero, 0) << r.first_nonzero;
}

TEST_P(SkewSymmetry, FailsWithOneChristoffelTermSignFlipped) {
  const auto& m = d_->model;
  const std::size_t n = m.q.size();
  // The first off-diagonal c_ijk (i != j) that is not identically zero.
  bool flipped = false;
  dyn::Matrix wrong = m.C;
  for (std::size_t i = 0; i < n && !flipped; ++i) {
    for (std::size_t j = 0; j < n && !flipped; ++j) {
      for (std::size_t k = 0; k < n && !flipped; ++k) {
        if (i == j || sym::test_zero(m.christoffel[k][i][j]).verdict != ZeroVerdict::NonZero) continue;
        wrong[i][j] = m.C[i][j] - Expr(2) * m.christoffel[k][i][j] * m.qd[k];
        flipped = true;
      }
    }
  }
  ASSERT_TRUE(flipped) << "no non-zero off-diagonal Christoffel symbol";
  const SkewResult r = skew_check(Hdot_, wrong);
  EXPECT_GE(r.nonzero, 1) << "a flipped Christoffel term was not detected";
  EXPECT_EQ(r.unknown, 0);
}

// Eq. (2) as printed: C_ij = 1/2 sum_k (dH_ij/dq_k + dH_jk/dq_j - dH_jk/dq_i) qd_k.
TEST_P(SkewSymmetry, FailsForThePapersMisprintedChristoffelForm) {
  const auto& m = d_->model;
  const std::size_t n = m.q.size();
  std::vector<sym::Differentiator> d_dq;
  for (const Expr q : m.q) d_dq.emplace_back(q);
  dyn::Matrix wrong(n, std::vector<Expr>(n));
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      Expr c;
      for (std::size_t k = 0; k < n; ++k)
        c += Expr(1) / Expr(2) * (d_dq[k](m.H[i][j]) + d_dq[j](m.H[j][k]) - d_dq[i](m.H[j][k])) * m.qd[k];
      wrong[i][j] = c;
    }
  }
  const SkewResult r = skew_check(Hdot_, wrong);
  EXPECT_GE(r.nonzero, 1) << "the misprinted Christoffel form was not detected";
}

TEST_P(SkewSymmetry, TransposedCPassesSkewSymmetryButIsAWrongCoriolisMatrix) {
  const auto& m = d_->model;
  const std::size_t n = m.q.size();
  dyn::Matrix transposed(n, std::vector<Expr>(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) transposed[i][j] = m.C[j][i];
  EXPECT_EQ(skew_check(Hdot_, transposed).nonzero, 0);

  // ... but C^T qd differs from C qd.
  const auto N = static_cast<Eigen::Index>(n);
  std::mt19937_64 rng(5);
  double largest = 0.0;
  for (int k = 0; k < 10; ++k) {
    const dyn::State s = random_state(N, rng);
    const Eigen::MatrixXd C = d_->numeric->evaluate(s, d_->numeric->nominal_standard_values()).C;
    largest = std::max(largest, relative_difference(C.transpose() * s.qd, C * s.qd, max_abs(C * s.qd)));
  }
  EXPECT_GT(largest, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Robots, SkewSymmetry, ::testing::Values("kraft.yaml", "planar_2link.yaml", "puma560.yaml"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param.substr(0, info.param.find('.'));
                         });

}  // namespace
}  // namespace dyncc::test
