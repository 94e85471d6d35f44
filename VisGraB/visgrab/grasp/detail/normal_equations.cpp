#include "visgrab/grasp/detail/normal_equations.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

namespace visgrab::grasp::detail {

namespace {

using Eigen::Index;

// The orders below are those of Eigen 3.4.0's kernels for doubles in SSE2 packets (two lanes),
// without fused multiply-add: every product and sum rounded on its own.
#if EIGEN_VERSION_AT_LEAST(3, 4, 0) && !EIGEN_VERSION_AT_LEAST(3, 4, 1) && \
    defined(EIGEN_VECTORIZE_SSE2) && !defined(EIGEN_VECTORIZE_AVX) &&      \
    !defined(EIGEN_VECTORIZE_FMA)
constexpr bool kKnownKernels = true;
#else
constexpr bool kKnownKernels = false;
#endif

// Below this size on every side, Eigen's blocking heuristic returns the whole product as one
// block (one pass over the depth).
constexpr Index kSingleBlock = 48;
// EIGEN_GEMM_TO_COEFFBASED_THRESHOLD: smaller products are evaluated lazily (another order).
constexpr Index kGemmThreshold = 20;

constexpr Index kMaxSize = kSingleBlock - 1;
// The exponent bits of a double: all set for infinities and NaNs.
constexpr std::uint64_t kExponent = 0x7ff0000000000000ULL;

// The non-zero entries of J row by row, in column order (row k's at k * kMaxSize); false if J
// has a non-finite value.
struct SparseRows {
  std::array<int, kMaxSize> count;
  std::array<int, kMaxSize * kMaxSize> column;
  std::array<double, kMaxSize * kMaxSize> value;

  bool gather(const Eigen::MatrixXd& J) {
    const Index m = J.rows();
    std::fill_n(count.begin(), m, 0);
    bool finite = true;  // checked on the exponent bits: no chain of floating-point additions
    for (Index c = 0; c < J.cols(); ++c) {
      const double* values = J.col(c).data();
      for (Index k = 0; k < m; ++k) {
        const double v = values[k];
        finite &= (std::bit_cast<std::uint64_t>(v) & kExponent) != kExponent;
        const auto at = static_cast<std::size_t>(k * kMaxSize + count[static_cast<std::size_t>(k)]);
        column[at] = static_cast<int>(c);
        value[at] = v;
        count[static_cast<std::size_t>(k)] += v != 0.0 ? 1 : 0;
      }
    }
    return finite;
  }
};

}  // namespace

// Eigen's general product res = lhs * rhs (lhs = J^T, rhs = J, res zeroed, alpha 1) packs the
// rows of res in panels of two packets (4 rows), then one packet (2 rows), then single rows,
// and the columns in panels of 4, then single columns. Each entry is a sum over the depth k
// in order, from +0, except the one-packet rows within 4-column panels: there, for k below
// the depth rounded down to 8, even k go to one accumulator and odd k to another, which are
// added before the rest of k. The entry is then 0 + 1 * sum, which is the sum. A sum that
// starts at +0 is never -0, so skipping a product that is +-0 changes nothing.
void gramMatrix(const Eigen::MatrixXd& J, Eigen::MatrixXd& A) {
  const Index m = J.rows();
  const Index n = J.cols();
  SparseRows rows;  // NOLINT(cppcoreguidelines-pro-type-member-init): filled by gather
  if (!kKnownKernels || m >= kSingleBlock || n >= kSingleBlock || n < 2 ||
      m + 2 * n < kGemmThreshold || !rows.gather(J)) {
    A.noalias() = J.transpose() * J;
    return;
  }
  const Index panels = (n / 4) * 4;
  const Index band = ((n - panels) / 2) * 2;  // the one-packet rows: panels .. panels + band
  const Index peeled = m & ~Index(7);
  // Entries away from the split ones sum the same products in the same order on both sides of
  // the diagonal, so the lower triangle is summed (row-major) and mirrored. The split entries
  // (one-packet rows, columns < panels) keep their odd-k sums apart until merged; their
  // mirrors (rows < panels, one-packet columns) are summed in `upper`.
  std::array<double, kMaxSize * kMaxSize> lower;
  std::array<double, 2 * kMaxSize> odd;
  std::array<double, 2 * kMaxSize> upper;
  std::fill_n(lower.begin(), n * n, 0.0);
  std::fill_n(odd.begin(), 2 * n, 0.0);
  std::fill_n(upper.begin(), 2 * n, 0.0);
  const auto merge = [&] {
    for (Index i = panels; i < panels + band; ++i) {
      for (Index j = 0; j < panels; ++j) lower[i * n + j] += odd[(i - panels) * n + j];
    }
  };
  const int* column = rows.column.data();
  const double* value = rows.value.data();
  for (Index k = 0; k < m; ++k) {
    if (k == peeled) merge();
    const bool oddStep = k < peeled && (k % 2) == 1;
    const int first = static_cast<int>(k * kMaxSize);
    const int last = first + rows.count[static_cast<std::size_t>(k)];
    int bandFirst = first;  // the row's entries in the one-packet columns
    while (bandFirst < last && column[bandFirst] < panels) ++bandFirst;
    int bandLast = bandFirst;
    while (bandLast < last && column[bandLast] < panels + band) ++bandLast;
    for (int a = first; a < last; ++a) {
      const Index i = column[a];
      const double li = value[a];
      double* row = lower.data() + i * n;
      if (oddStep && i >= panels && i < panels + band) {
        double* oddRow = odd.data() + (i - panels) * n;
        for (int b = first; b <= a; ++b) {
          const Index j = column[b];
          (j < panels ? oddRow : row)[j] += li * value[b];
        }
      } else {
        for (int b = first; b <= a; ++b) row[column[b]] += li * value[b];
      }
      if (i < panels) {
        for (int b = bandFirst; b < bandLast; ++b) {
          upper[(column[b] - panels) * n + i] += li * value[b];
        }
      }
    }
  }
  if (peeled == m) merge();
  A.resize(n, n);
  for (Index i = 0; i < n; ++i) {
    for (Index j = 0; j <= i; ++j) {
      A(i, j) = lower[i * n + j];
      A(j, i) = lower[i * n + j];
    }
  }
  for (Index i = panels; i < panels + band; ++i) {
    for (Index j = 0; j < panels; ++j) A(j, i) = upper[(i - panels) * n + j];
  }
}

// Eigen's row-major matrix-vector product res = J^T r (res zeroed, alpha 1): each entry sums
// J(k, i) r(k) in two lanes, even k and odd k, over the depth rounded down to 2, adds the
// lanes, then the last k if the depth is odd; the entry is 0 + 1 * sum.
void gradient(const Eigen::MatrixXd& J, const Eigen::VectorXd& r, Eigen::VectorXd& g) {
  const Index m = J.rows();
  const Index n = J.cols();
  if (!kKnownKernels || m >= kSingleBlock || n < 2) {
    g.noalias() = J.transpose() * r;
    return;
  }
  const Index pairs = (m / 2) * 2;
  g.resize(n);
  // Every product is added, as Eigen does, so non-finite values give what Eigen gives.
  for (Index i = 0; i < n; ++i) {
    const double* Ji = J.col(i).data();
    double lane0 = 0.0;
    double lane1 = 0.0;
    for (Index k = 0; k < pairs; k += 2) {
      lane0 += Ji[k] * r[k];
      lane1 += Ji[k + 1] * r[k + 1];
    }
    double sum = lane0 + lane1;
    if (pairs < m) sum += Ji[m - 1] * r[m - 1];
    g[i] = sum;
  }
}

}  // namespace visgrab::grasp::detail
