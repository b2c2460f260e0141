// CSG, rigid motions and scaling of implicit solids.

#include <algorithm>
#include <cmath>

#include "implicit/implicit_internal.h"

namespace massprops::implicit {
namespace {

using internal::Num;
using internal::RequirePositive;

class CsgSolid final : public ImplicitSolid {
 public:
  enum Op { kUnion, kIntersection, kDifference };
  CsgSolid(Op op, std::vector<ImplicitPtr> parts) : op_(op), parts_(std::move(parts)) {
    if (parts_.size() < (op_ == kDifference ? 2u : 1u)) throw std::invalid_argument("CSG needs at least two solids");
    for (const auto& p : parts_) {
      if (!p) throw std::invalid_argument("CSG: a part is missing");
    }
    bounds_ = parts_[0]->Bounds();
    for (std::size_t i = 1; i < parts_.size(); ++i) {
      if (op_ == kUnion) bounds_.extend(parts_[i]->Bounds());
      if (op_ == kIntersection) bounds_ = bounds_.intersection(parts_[i]->Bounds());
    }
    if (bounds_.isEmpty())
      throw std::invalid_argument("intersection: the parts' bounding boxes do not overlap: the solid is empty");
  }
  Scalar Value(const Vector3& x) const override {
    Scalar v = parts_[0]->Value(x);
    for (std::size_t i = 1; i < parts_.size(); ++i) {
      const Scalar w = parts_[i]->Value(x);
      v = op_ == kUnion ? std::min(v, w) : op_ == kIntersection ? std::max(v, w) : std::max(v, -w);
    }
    return v;
  }
  AlignedBox3 Bounds() const override { return bounds_; }
  std::string Describe() const override {
    std::string s = op_ == kUnion ? "union(" : op_ == kIntersection ? "intersection(" : "difference(";
    for (std::size_t i = 0; i < parts_.size(); ++i) s += (i ? ", " : "") + parts_[i]->Describe();
    return s + ")";
  }

 private:
  Op op_;
  std::vector<ImplicitPtr> parts_;
  AlignedBox3 bounds_;
};

class TransformedSolid final : public ImplicitSolid {
 public:
  TransformedSolid(ImplicitPtr a, const Matrix3& R, const Vector3& t, Scalar s)
      : a_(std::move(a)), R_(R), t_(t), s_(s) {
    if (!a_) throw std::invalid_argument("transform: the solid is missing");
    if (!R.allFinite() || !t.allFinite() || (R.transpose() * R - Matrix3::Identity()).cwiseAbs().maxCoeff() > 1e-9 ||
        R.determinant() < 0) {
      throw std::invalid_argument("transform: not a rotation, or not finite");
    }
    RequirePositive(s, "scale: s");
    const AlignedBox3 b = a_->Bounds();
    for (int corner = 0; corner < 8; ++corner) {
      const Vector3 c = b.corner(static_cast<AlignedBox3::CornerType>(corner));
      bounds_.extend(Vector3(s_ * (R_ * c) + t_));
    }
  }
  Scalar Value(const Vector3& x) const override { return s_ * a_->Value(R_.transpose() * ((x - t_) / s_)); }
  AlignedBox3 Bounds() const override { return bounds_; }
  std::string Describe() const override {
    std::string s = a_->Describe();
    if (s_ != 1) s = "scale(" + s + ", s=" + Num(s_) + ")";
    if (!R_.isIdentity(0)) {
      const Eigen::AngleAxisd aa(R_);
      s = "rotate(" + s + ", axis=[" + Num(aa.axis().x()) + ", " + Num(aa.axis().y()) + ", " + Num(aa.axis().z()) +
          "], deg=" + Num(aa.angle() * 180 / kPi) + ")";
    }
    if (!t_.isZero(0)) s = "move(" + s + ", x=" + Num(t_.x()) + ", y=" + Num(t_.y()) + ", z=" + Num(t_.z()) + ")";
    return s;
  }

 private:
  ImplicitPtr a_;
  Matrix3 R_;
  Vector3 t_;
  Scalar s_;
  AlignedBox3 bounds_;
};

}  // namespace

ImplicitPtr Union(std::vector<ImplicitPtr> parts) {
  return std::make_shared<CsgSolid>(CsgSolid::kUnion, std::move(parts));
}
ImplicitPtr Intersection(std::vector<ImplicitPtr> parts) {
  return std::make_shared<CsgSolid>(CsgSolid::kIntersection, std::move(parts));
}
ImplicitPtr Difference(ImplicitPtr a, ImplicitPtr b) {
  return std::make_shared<CsgSolid>(CsgSolid::kDifference, std::vector<ImplicitPtr>{std::move(a), std::move(b)});
}
ImplicitPtr Transformed(ImplicitPtr a, const Matrix3& R, const Vector3& t) {
  return std::make_shared<TransformedSolid>(std::move(a), R, t, 1.0);
}
ImplicitPtr Scaled(ImplicitPtr a, Scalar s) {
  return std::make_shared<TransformedSolid>(std::move(a), Matrix3::Identity(), Vector3::Zero(), s);
}

}  // namespace massprops::implicit
