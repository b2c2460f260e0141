// The primitives as implicit solids: signed distances (or functions of the same sign).

#include <algorithm>
#include <cmath>

#include "implicit/implicit_internal.h"

namespace massprops::implicit {
namespace {

using internal::Centered;
using internal::Num;
using internal::RequirePositive;

class SphereSolid final : public ImplicitSolid {
 public:
  explicit SphereSolid(Scalar r) : r_(r) { RequirePositive(r, "sphere: r"); }
  Scalar Value(const Vector3& x) const override { return x.norm() - r_; }
  AlignedBox3 Bounds() const override { return Centered(Vector3::Constant(r_)); }
  std::string Describe() const override { return "sphere(r=" + Num(r_) + ")"; }

 private:
  Scalar r_;
};

class EllipsoidSolid final : public ImplicitSolid {
 public:
  explicit EllipsoidSolid(const Vector3& s) : s_(s) {
    for (int i = 0; i < 3; ++i) RequirePositive(s[i], "ellipsoid: semi-axis");
  }
  Scalar Value(const Vector3& x) const override { return x.cwiseQuotient(s_).squaredNorm() - 1.0; }
  AlignedBox3 Bounds() const override { return Centered(s_); }
  std::string Describe() const override {
    return "ellipsoid(a=" + Num(s_.x()) + ", b=" + Num(s_.y()) + ", c=" + Num(s_.z()) + ")";
  }

 private:
  Vector3 s_;
};

class BoxSolid final : public ImplicitSolid {
 public:
  explicit BoxSolid(const Vector3& size) : half_(0.5 * size) {
    for (int i = 0; i < 3; ++i) RequirePositive(size[i], "box: edge");
  }
  Scalar Value(const Vector3& x) const override { return (x.cwiseAbs() - half_).maxCoeff(); }
  AlignedBox3 Bounds() const override { return Centered(half_); }
  std::string Describe() const override {
    return "box(x=" + Num(2 * half_.x()) + ", y=" + Num(2 * half_.y()) + ", z=" + Num(2 * half_.z()) + ")";
  }

 private:
  Vector3 half_;
};

class CylinderSolid final : public ImplicitSolid {
 public:
  CylinderSolid(Scalar r, Scalar h) : r_(r), h_(h) {
    RequirePositive(r, "cylinder: r");
    RequirePositive(h, "cylinder: h");
  }
  Scalar Value(const Vector3& x) const override {
    return std::max(std::hypot(x.x(), x.y()) - r_, std::abs(x.z()) - 0.5 * h_);
  }
  AlignedBox3 Bounds() const override { return Centered(Vector3(r_, r_, 0.5 * h_)); }
  std::string Describe() const override { return "cylinder(r=" + Num(r_) + ", h=" + Num(h_) + ")"; }

 private:
  Scalar r_, h_;
};

class ConeSolid final : public ImplicitSolid {
 public:
  ConeSolid(Scalar r, Scalar h) : r_(r), h_(h) {
    RequirePositive(r, "cone: r");
    RequirePositive(h, "cone: h");
  }
  Scalar Value(const Vector3& x) const override {
    const Scalar apex = 0.75 * h_;
    // Inside: below the apex, above the base, and within the radius r (apex − z)/h.
    return std::max({-0.25 * h_ - x.z(), x.z() - apex, std::hypot(x.x(), x.y()) - r_ * (apex - x.z()) / h_});
  }
  AlignedBox3 Bounds() const override { return AlignedBox3(Vector3(-r_, -r_, -0.25 * h_), Vector3(r_, r_, 0.75 * h_)); }
  std::string Describe() const override { return "cone(r=" + Num(r_) + ", h=" + Num(h_) + ")"; }

 private:
  Scalar r_, h_;
};

class TorusSolid final : public ImplicitSolid {
 public:
  TorusSolid(Scalar R, Scalar a) : R_(R), a_(a) {
    RequirePositive(R, "torus: R");
    RequirePositive(a, "torus: r");
    if (!(a < R))
      throw std::invalid_argument("torus: r must be smaller than R (got r=" + Num(a) + ", R=" + Num(R) + ")");
  }
  Scalar Value(const Vector3& x) const override { return std::hypot(std::hypot(x.x(), x.y()) - R_, x.z()) - a_; }
  AlignedBox3 Bounds() const override { return Centered(Vector3(R_ + a_, R_ + a_, a_)); }
  std::string Describe() const override { return "torus(R=" + Num(R_) + ", r=" + Num(a_) + ")"; }

 private:
  Scalar R_, a_;
};

class CapsuleSolid final : public ImplicitSolid {
 public:
  CapsuleSolid(Scalar r, Scalar h) : r_(r), h_(h) {
    RequirePositive(r, "capsule: r");
    RequirePositive(h, "capsule: h");
  }
  Scalar Value(const Vector3& x) const override {
    const Scalar z = std::clamp(x.z(), -0.5 * h_, 0.5 * h_);
    return (x - Vector3(0, 0, z)).norm() - r_;
  }
  AlignedBox3 Bounds() const override { return Centered(Vector3(r_, r_, 0.5 * h_ + r_)); }
  std::string Describe() const override { return "capsule(r=" + Num(r_) + ", h=" + Num(h_) + ")"; }

 private:
  Scalar r_, h_;
};

}  // namespace

ImplicitPtr Sphere(Scalar r) { return std::make_shared<SphereSolid>(r); }
ImplicitPtr Ellipsoid(const Vector3& s) { return std::make_shared<EllipsoidSolid>(s); }
ImplicitPtr Box(const Vector3& size) { return std::make_shared<BoxSolid>(size); }
ImplicitPtr Cylinder(Scalar r, Scalar h) { return std::make_shared<CylinderSolid>(r, h); }
ImplicitPtr Cone(Scalar r, Scalar h) { return std::make_shared<ConeSolid>(r, h); }
ImplicitPtr Torus(Scalar major, Scalar minor) { return std::make_shared<TorusSolid>(major, minor); }
ImplicitPtr Capsule(Scalar r, Scalar h) { return std::make_shared<CapsuleSolid>(r, h); }
}  // namespace massprops::implicit
