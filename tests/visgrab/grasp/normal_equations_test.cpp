// The contact IK's normal equations (visgrab/grasp/detail/normal_equations.hpp) against Eigen's
// own products, bit for bit: random Jacobians of every size below Eigen's single-block limit
// (and some beyond it), with many exact zeros and entries of very different magnitudes so
// that any other order of additions shows in the last bits.
#include "visgrab/grasp/detail/normal_equations.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

namespace {

using visgrab::grasp::detail::gradient;
using visgrab::grasp::detail::gramMatrix;

Eigen::MatrixXd randomJacobian(std::mt19937& rng, Eigen::Index rows, Eigen::Index cols) {
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-12, 4);
  std::bernoulli_distribution zero(0.5);
  Eigen::MatrixXd J(rows, cols);
  for (Eigen::Index k = 0; k < J.size(); ++k) {
    J.data()[k] = zero(rng) ? (zero(rng) ? 0.0 : -0.0) : std::ldexp(mantissa(rng), exponent(rng));
  }
  return J;
}

bool sameBits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST(NormalEquations, GramMatrixIsEigensBitForBit) {
  std::mt19937 rng(11);
  int mismatches = 0;
  for (Eigen::Index rows = 0; rows <= 52; ++rows) {
    for (Eigen::Index cols = 1; cols <= 20; ++cols) {
      for (int trial = 0; trial < 3; ++trial) {
        const Eigen::MatrixXd J = randomJacobian(rng, rows, cols);
        const Eigen::MatrixXd expected = J.transpose() * J;
        Eigen::MatrixXd A = Eigen::MatrixXd::Constant(3, 3, 7.0);  // resized and overwritten
        gramMatrix(J, A);
        if (!sameBits(A, expected)) {
          ++mismatches;
          ADD_FAILURE() << rows << " x " << cols << " (trial " << trial << ")";
        }
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(NormalEquations, GradientIsEigensBitForBit) {
  std::mt19937 rng(12);
  int mismatches = 0;
  for (Eigen::Index rows = 0; rows <= 52; ++rows) {
    for (Eigen::Index cols = 1; cols <= 20; ++cols) {
      for (int trial = 0; trial < 3; ++trial) {
        const Eigen::MatrixXd J = randomJacobian(rng, rows, cols);
        const Eigen::VectorXd r = randomJacobian(rng, rows, 1);
        const Eigen::VectorXd expected = J.transpose() * r;
        Eigen::VectorXd g = Eigen::VectorXd::Constant(2, 7.0);
        gradient(J, r, g);
        if (!sameBits(g, expected)) {
          ++mismatches;
          ADD_FAILURE() << rows << " x " << cols << " (trial " << trial << ")";
        }
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
}

// A non-finite entry gives what Eigen gives (NaN or infinity where Eigen has them).
TEST(NormalEquations, NonFiniteEntriesGiveEigensResult) {
  std::mt19937 rng(13);
  Eigen::MatrixXd J = randomJacobian(rng, 28, 13);
  J(3, 4) = std::numeric_limits<double>::infinity();
  const Eigen::MatrixXd expected = J.transpose() * J;
  Eigen::MatrixXd A;
  gramMatrix(J, A);
  EXPECT_TRUE(sameBits(A, expected));
  EXPECT_TRUE(std::isnan(A(4, 0)) || std::isinf(A(4, 0)) || J(3, 0) == 0.0);
  const Eigen::VectorXd r = randomJacobian(rng, 28, 1);
  const Eigen::VectorXd expectedG = J.transpose() * r;
  Eigen::VectorXd g;
  gradient(J, r, g);
  EXPECT_TRUE(sameBits(g, expectedG));
}

}  // namespace
