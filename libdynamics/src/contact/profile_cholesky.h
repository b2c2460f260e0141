#pragma once
// The Cholesky factor of a symmetric positive definite matrix that skips, in each row, the zeros
// before its first nonzero: the factor's nonzeros stay within that profile (the "envelope" or
// "skyline" of the matrix), so a matrix whose rows reach back a few entries — the Delassus matrix
// of a column of boxes, ordered from the ground up — costs k b² instead of k³ / 6. A dense matrix
// is factored as a dense one. Rows are stored contiguously (row-major), and the products run
// over the shorter of two rows' profiles. The block solve of the contacts (block_solve.cpp) uses
// it; it allocates only when a larger matrix than before comes.

#include <Eigen/Core>
#include <vector>

namespace dynamics::contact {

class ProfileCholesky {
 public:
  /// Factors the k × k matrix S (its lower triangle read) with `relative` of its diagonal added
  /// (S + relative · diag(S)). False where S is not positive definite to within rounding.
  bool Compute(const Eigen::MatrixXd& S, double relative = 0);
  /// x := (S + relative · diag(S))⁻¹ x, for the last matrix factored.
  void SolveInPlace(Eigen::VectorXd& x) const;
  /// The order of the last matrix factored.
  Eigen::Index size() const { return k_; }

 private:
  Eigen::Index k_ = 0;
  std::vector<Eigen::Index> first_;  // each row's first nonzero
  std::vector<double> L_;            // the factor, row-major, k × k (beyond the profile: unused)
  std::vector<double> inverse_;      // 1 / its diagonal
};

}  // namespace dynamics::contact
