// The profile (envelope) Cholesky factor (profile_cholesky.h).

#include "profile_cholesky.h"

#include <algorithm>
#include <cmath>

namespace dynamics::contact {
namespace {

// Σ a[l] b[l] for l in [0, n).
double Dot(const double* a, const double* b, Eigen::Index n) {
  double sum = 0;
  for (Eigen::Index l = 0; l < n; ++l) sum += a[l] * b[l];
  return sum;
}

}  // namespace

bool ProfileCholesky::Compute(const Eigen::MatrixXd& S, double relative) {
  k_ = S.rows();
  const auto k = static_cast<std::size_t>(k_);
  first_.resize(k);
  inverse_.resize(k);
  if (L_.size() < k * k) L_.resize(k * k);
  for (Eigen::Index i = 0; i < k_; ++i) {
    Eigen::Index f = 0;
    while (f < i && S(i, f) == 0) ++f;
    first_[static_cast<std::size_t>(i)] = f;
  }
  // Row by row: L(i, j) = (S(i, j) − Σ_l L(i, l) L(j, l)) / L(j, j) over the columns both rows
  // reach, then the diagonal.
  for (Eigen::Index i = 0; i < k_; ++i) {
    double* Li = &L_[static_cast<std::size_t>(i * k_)];
    const Eigen::Index fi = first_[static_cast<std::size_t>(i)];
    for (Eigen::Index j = fi; j < i; ++j) {
      const double* Lj = &L_[static_cast<std::size_t>(j * k_)];
      const Eigen::Index from = std::max(fi, first_[static_cast<std::size_t>(j)]);
      Li[j] = (S(i, j) - Dot(Li + from, Lj + from, j - from)) * inverse_[static_cast<std::size_t>(j)];
    }
    const double d = S(i, i) * (1 + relative) - Dot(Li + fi, Li + fi, i - fi);
    if (!(d > 0)) return false;
    Li[i] = std::sqrt(d);
    inverse_[static_cast<std::size_t>(i)] = 1 / Li[i];
  }
  return true;
}

void ProfileCholesky::SolveInPlace(Eigen::VectorXd& x) const {
  // L y = x, then Lᵀ x = y (Lᵀ by columns: each row of L, once its unknown is known, taken off
  // the unknowns before it).
  for (Eigen::Index i = 0; i < k_; ++i) {
    const double* Li = &L_[static_cast<std::size_t>(i * k_)];
    const Eigen::Index fi = first_[static_cast<std::size_t>(i)];
    x[i] = (x[i] - Dot(Li + fi, x.data() + fi, i - fi)) * inverse_[static_cast<std::size_t>(i)];
  }
  for (Eigen::Index i = k_ - 1; i >= 0; --i) {
    const double* Li = &L_[static_cast<std::size_t>(i * k_)];
    x[i] *= inverse_[static_cast<std::size_t>(i)];
    const double xi = x[i];
    for (Eigen::Index l = first_[static_cast<std::size_t>(i)]; l < i; ++l) x[l] -= Li[l] * xi;
  }
}

}  // namespace dynamics::contact
