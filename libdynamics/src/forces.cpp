// The definitions of dynamics/forces.h: forces and torques acting on the bodies of a World.

#include "dynamics/forces.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dynamics {
namespace {

class GravityForce : public Force {
 public:
  explicit GravityForce(const Vector3& g) : g_(g) {}
  ForceTraits Traits() const override { return {nullptr, "gravity"}; }
  void Apply(double, const std::vector<RigidBody>& b, std::vector<Wrench>& out) const override {
    for (std::size_t i = 0; i < b.size(); ++i) out[i].force += b[i].mass * g_;
  }
  double PotentialEnergy(const std::vector<RigidBody>& b) const override {
    double u = 0;
    for (const auto& body : b) u -= body.mass * g_.dot(body.position);
    return u;
  }

 private:
  Vector3 g_;
};

class DampingForce : public Force {
 public:
  DampingForce(double c, int body, bool angular) : c_(c), body_(body), angular_(angular) {}
  ForceTraits Traits() const override {
    if (c_ == 0) return {};
    return {"damping", "damping", true};
  }
  void Apply(double, const std::vector<RigidBody>& b, std::vector<Wrench>& out) const override {
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (body_ >= 0 && static_cast<std::size_t>(body_) != i) continue;
      if (angular_) {
        out[i].torque -= c_ * b[i].AngularVelocity();
      } else {
        out[i].force -= c_ * b[i].velocity;
      }
    }
  }

  int MaxBody() const override { return body_; }

 private:
  double c_;
  int body_;
  bool angular_;
};

class PointForceImpl : public Force {
 public:
  PointForceImpl(int body, const Vector3& p, const Vector3& f, bool body_frame, bool pure_torque)
      : body_(body), p_(p), f_(f), body_frame_(body_frame), pure_torque_(pure_torque) {}
  ForceTraits Traits() const override {
    const char* what = pure_torque_ ? "applied torques" : "applied forces";
    return {what, what};
  }
  void Apply(double, const std::vector<RigidBody>& b, std::vector<Wrench>& out) const override {
    const RigidBody& body = b[static_cast<std::size_t>(body_)];
    Wrench& w = out[static_cast<std::size_t>(body_)];
    const Vector3 f = body_frame_ ? Vector3(body.orientation * f_) : f_;
    if (pure_torque_) {
      w.torque += f;
      return;
    }
    w.force += f;
    w.torque += (body.orientation * p_).cross(f);
  }
  int MaxBody() const override { return body_; }

 private:
  int body_;
  Vector3 p_, f_;
  bool body_frame_, pure_torque_;
};

// Spring force on the first end, for ends at a and b moving at va and vb.
Vector3 SpringForce(const Vector3& a, const Vector3& b, const Vector3& va, const Vector3& vb, double k, double l0,
                    double c) {
  const Vector3 d = b - a;
  const double len = d.norm();
  if (len == 0.0) return Vector3::Zero();  // direction undefined: no force (measure zero)
  const Vector3 u = d / len;
  return (k * (len - l0) + c * (vb - va).dot(u)) * u;
}

class SpringImpl : public Force {
 public:
  SpringImpl(int a, const Vector3& pa, int b, const Vector3& pb_or_anchor, double k, double l0, double c)
      : a_(a), b_(b), pa_(pa), pb_(pb_or_anchor), k_(k), l0_(l0), c_(c) {}
  ForceTraits Traits() const override {
    return {c_ > 0 ? "spring damping" : nullptr, b_ >= 0 ? nullptr : "springs to the world", c_ > 0};
  }
  void Apply(double, const std::vector<RigidBody>& bodies, std::vector<Wrench>& out) const override {
    const RigidBody& A = bodies[static_cast<std::size_t>(a_)];
    const Vector3 xa = A.PointPosition(pa_);
    const Vector3 va = A.PointVelocity(xa);
    Vector3 xb = pb_, vb = Vector3::Zero();
    if (b_ >= 0) {
      const RigidBody& B = bodies[static_cast<std::size_t>(b_)];
      xb = B.PointPosition(pb_);
      vb = B.PointVelocity(xb);
    }
    const Vector3 f = SpringForce(xa, xb, va, vb, k_, l0_, c_);
    out[static_cast<std::size_t>(a_)].force += f;
    out[static_cast<std::size_t>(a_)].torque += (xa - A.position).cross(f);
    if (b_ >= 0) {
      const RigidBody& B = bodies[static_cast<std::size_t>(b_)];
      out[static_cast<std::size_t>(b_)].force -= f;
      out[static_cast<std::size_t>(b_)].torque += (xb - B.position).cross(-f);
    }
  }
  double PotentialEnergy(const std::vector<RigidBody>& bodies) const override {
    const Vector3 xa = bodies[static_cast<std::size_t>(a_)].PointPosition(pa_);
    const Vector3 xb = b_ >= 0 ? bodies[static_cast<std::size_t>(b_)].PointPosition(pb_) : pb_;
    const double s = (xb - xa).norm() - l0_;
    return 0.5 * k_ * s * s;
  }
  int MaxBody() const override { return std::max(a_, b_); }

 private:
  int a_, b_;
  Vector3 pa_, pb_;
  double k_, l0_, c_;
};

class CallbackForce : public Force {
 public:
  CallbackForce(std::function<void(double, const std::vector<RigidBody>&, std::vector<Wrench>&)> fn, ForceTraits traits)
      : fn_(std::move(fn)), traits_(traits) {}
  ForceTraits Traits() const override { return traits_; }
  void Apply(double t, const std::vector<RigidBody>& b, std::vector<Wrench>& out) const override { fn_(t, b, out); }

 private:
  std::function<void(double, const std::vector<RigidBody>&, std::vector<Wrench>&)> fn_;
  ForceTraits traits_;
};

void RequireFinite(const Vector3& v, const char* what) {
  if (!v.allFinite()) throw std::invalid_argument(std::string(what) + " must be finite");
}
void RequireNonNegative(double v, const char* what) {
  if (!(v >= 0) || !std::isfinite(v)) throw std::invalid_argument(std::string(what) + " must be finite and >= 0");
}

}  // namespace

std::unique_ptr<Force> Gravity(const Vector3& g) {
  RequireFinite(g, "gravity");
  return std::make_unique<GravityForce>(g);
}
std::unique_ptr<Force> LinearDamping(double c, int body) {
  RequireNonNegative(c, "linear damping");
  return std::make_unique<DampingForce>(c, body, false);
}
std::unique_ptr<Force> AngularDamping(double c, int body) {
  RequireNonNegative(c, "angular damping");
  return std::make_unique<DampingForce>(c, body, true);
}
std::unique_ptr<Force> ConstantForce(int body, const Vector3& force) {
  RequireFinite(force, "force");
  return std::make_unique<PointForceImpl>(body, Vector3::Zero(), force, false, false);
}
std::unique_ptr<Force> ConstantTorque(int body, const Vector3& torque) {
  RequireFinite(torque, "torque");
  return std::make_unique<PointForceImpl>(body, Vector3::Zero(), torque, false, true);
}
std::unique_ptr<Force> BodyFrameTorque(int body, const Vector3& torque_body) {
  RequireFinite(torque_body, "torque");
  return std::make_unique<PointForceImpl>(body, Vector3::Zero(), torque_body, true, true);
}
std::unique_ptr<Force> PointForce(int body, const Vector3& point_body, const Vector3& force, bool body_frame) {
  RequireFinite(point_body, "point");
  RequireFinite(force, "force");
  return std::make_unique<PointForceImpl>(body, point_body, force, body_frame, false);
}
std::unique_ptr<Force> SpringToWorld(int body, const Vector3& point_body, const Vector3& anchor, double k,
                                     double rest_length, double damping) {
  RequireFinite(point_body, "spring point");
  RequireFinite(anchor, "spring anchor");
  RequireNonNegative(k, "spring stiffness");
  RequireNonNegative(rest_length, "spring rest length");
  RequireNonNegative(damping, "spring damping");
  return std::make_unique<SpringImpl>(body, point_body, -1, anchor, k, rest_length, damping);
}
std::unique_ptr<Force> SpringBetween(int body_a, const Vector3& point_a, int body_b, const Vector3& point_b, double k,
                                     double rest_length, double damping) {
  RequireFinite(point_a, "spring point");
  RequireFinite(point_b, "spring point");
  RequireNonNegative(k, "spring stiffness");
  RequireNonNegative(rest_length, "spring rest length");
  RequireNonNegative(damping, "spring damping");
  if (body_b < 0) throw std::invalid_argument("SpringBetween: body_b must be a body index");
  return std::make_unique<SpringImpl>(body_a, point_a, body_b, point_b, k, rest_length, damping);
}
std::unique_ptr<Force> ForceCallback(
    std::function<void(double, const std::vector<RigidBody>&, std::vector<Wrench>&)> fn, ForceTraits traits) {
  if (!fn) throw std::invalid_argument("ForceCallback: empty function");
  return std::make_unique<CallbackForce>(std::move(fn), traits);
}

}  // namespace dynamics
