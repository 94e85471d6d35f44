#pragma once

#include <Eigen/Core>

namespace visgrab::grasp::detail {

/// A = J^T J, double for double what Eigen gives for `A.noalias() = J.transpose() * J`.
/// Where this build's Eigen is 3.4.0 with SSE2 and without FMA/AVX and the product is Eigen's
/// single-block general product (rows + 2 cols >= 20, rows and cols < 48), it is computed
/// here in the same order of additions as Eigen's kernel, skipping the products with an exact
/// zero factor (adding them changes no bit); otherwise, or if J has a non-finite value, by Eigen.
void gramMatrix(const Eigen::MatrixXd& J, Eigen::MatrixXd& A);

/// g = J^T r, double for double what Eigen gives for `g.noalias() = J.transpose() * r`
/// (computed here in Eigen's order of additions, every product included, so non-finite values
/// give Eigen's result too; for rows < 48 and cols >= 2, otherwise by Eigen).
void gradient(const Eigen::MatrixXd& J, const Eigen::VectorXd& r, Eigen::VectorXd& g);

}  // namespace visgrab::grasp::detail
