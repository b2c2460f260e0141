// Signed-distance grids, trilinearly interpolated.

#include <algorithm>
#include <cmath>

#include "implicit/implicit_internal.h"

namespace massprops::implicit {
namespace {

using internal::Num;
using internal::RequirePositive;

class GridSolid final : public ImplicitSolid {
 public:
  GridSolid(const Eigen::Vector3i& n, const Vector3& origin, const Vector3& h, std::vector<Scalar> v, std::string name)
      : n_(n), origin_(origin), h_(h), v_(std::move(v)), name_(std::move(name)) {
    if ((n.array() < 2).any()) throw std::invalid_argument("grid: at least 2 samples along each axis");
    for (int i = 0; i < 3; ++i) RequirePositive(h[i], "grid: spacing");
    if (!origin.allFinite()) throw std::invalid_argument("grid: origin not finite");
    const auto count =
        static_cast<std::size_t>(n.x()) * static_cast<std::size_t>(n.y()) * static_cast<std::size_t>(n.z());
    if (v_.size() != count) {
      throw std::invalid_argument("grid: " + std::to_string(v_.size()) + " values for " + std::to_string(n.x()) + "×" +
                                  std::to_string(n.y()) + "×" + std::to_string(n.z()) + " samples");
    }
    for (std::size_t i = 0; i < v_.size(); ++i) {
      if (!std::isfinite(v_[i])) throw std::invalid_argument("grid: value " + std::to_string(i) + " is not finite");
    }
  }
  Scalar Value(const Vector3& x) const override {
    const Vector3 u = (x - origin_).cwiseQuotient(h_);
    Scalar f[3];
    int i[3];
    for (int k = 0; k < 3; ++k) {
      if (!(u[k] >= 0 && u[k] <= n_[k] - 1)) return 1.0;  // outside the grid: absent
      i[k] = std::min(static_cast<int>(u[k]), n_[k] - 2);
      f[k] = u[k] - i[k];
    }
    auto at = [&](int dx, int dy, int dz) {
      return v_[static_cast<std::size_t>(i[0] + dx) +
                static_cast<std::size_t>(n_.x()) *
                    (static_cast<std::size_t>(i[1] + dy) +
                     static_cast<std::size_t>(n_.y()) * static_cast<std::size_t>(i[2] + dz))];
    };
    Scalar c[2];
    for (int dz = 0; dz < 2; ++dz) {
      const Scalar c0 = at(0, 0, dz) * (1 - f[0]) + at(1, 0, dz) * f[0];
      const Scalar c1 = at(0, 1, dz) * (1 - f[0]) + at(1, 1, dz) * f[0];
      c[dz] = c0 * (1 - f[1]) + c1 * f[1];
    }
    return c[0] * (1 - f[2]) + c[1] * f[2];
  }
  AlignedBox3 Bounds() const override {
    return AlignedBox3(origin_, origin_ + h_.cwiseProduct((n_.array() - 1).cast<Scalar>().matrix()));
  }
  std::string Describe() const override { return name_; }

 private:
  Eigen::Vector3i n_;
  Vector3 origin_, h_;
  std::vector<Scalar> v_;
  std::string name_;
};

}  // namespace

ImplicitPtr SdfGrid(const Eigen::Vector3i& size, const Vector3& origin, const Vector3& spacing,
                    std::vector<Scalar> values, std::string description) {
  return std::make_shared<GridSolid>(size, origin, spacing, std::move(values), std::move(description));
}

}  // namespace massprops::implicit
