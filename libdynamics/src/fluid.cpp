// The definitions of dynamics/forces.h's Fluid and Buoyancy: MuJoCo's inertia-box fluid model
// (its documentation's "Fluid forces: Inertia model") and Archimedes' buoyancy.

#include <cmath>
#include <stdexcept>
#include <string>

#include "dynamics/forces.h"

namespace dynamics {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Half-sizes of the box of mass m with principal moments I (its sides along the principal axes).
Vector3 InertiaBox(double m, const Vector3& I) {
  Vector3 r;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    r[i] = std::sqrt(std::max(0.0, 1.5 / m * (I[j] + I[k] - I[i])));
  }
  return r;
}

class FluidForce : public Force {
 public:
  FluidForce(const Medium& medium, std::vector<int> bodies) : medium_(medium), bodies_(std::move(bodies)) {}
  ForceTraits Traits() const override {
    if (medium_.density == 0 && medium_.viscosity == 0) return {};
    return {"fluid", "fluid", true};
  }
  void Apply(double, const std::vector<RigidBody>& b, std::vector<Wrench>& out) const override {
    if (bodies_.empty()) {
      for (std::size_t i = 0; i < b.size(); ++i) Add(b[i], out[i]);
    } else {
      for (const int i : bodies_) Add(b[static_cast<std::size_t>(i)], out[static_cast<std::size_t>(i)]);
    }
  }
  int MaxBody() const override {
    int most = -1;
    for (const int i : bodies_) most = std::max(most, i);
    return most;
  }

 private:
  void Add(const RigidBody& body, Wrench& w) const {
    if (!(body.mass > 0)) return;
    const Vector3 r = InertiaBox(body.mass, body.inertia);
    const Vector3 v = body.orientation.conjugate() * (body.velocity - medium_.wind);  // principal axes
    const Vector3 omega = body.BodyAngularVelocity();
    const double rho = medium_.density, beta = medium_.viscosity;
    const double r_eq = (r.x() + r.y() + r.z()) / 3;
    Vector3 f = -6 * kPi * beta * r_eq * v;
    Vector3 tau = -8 * kPi * beta * r_eq * r_eq * r_eq * omega;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      f[i] -= 2 * rho * r[j] * r[k] * std::abs(v[i]) * v[i];
      tau[i] -= 0.5 * rho * r[i] * (std::pow(r[j], 4) + std::pow(r[k], 4)) * std::abs(omega[i]) * omega[i];
    }
    w.force += body.orientation * f;
    w.torque += body.orientation * tau;
  }

  Medium medium_;
  std::vector<int> bodies_;
};

class BuoyancyForce : public Force {
 public:
  BuoyancyForce(const Vector3& lift, int body) : lift_(lift), body_(body) {}
  ForceTraits Traits() const override { return {nullptr, "buoyancy"}; }
  void Apply(double, const std::vector<RigidBody>&, std::vector<Wrench>& out) const override {
    out[static_cast<std::size_t>(body_)].force += lift_;
  }
  double PotentialEnergy(const std::vector<RigidBody>& b) const override {
    return -lift_.dot(b[static_cast<std::size_t>(body_)].position);
  }
  int MaxBody() const override { return body_; }

 private:
  Vector3 lift_;  // −ρ V g
  int body_;
};

}  // namespace

std::unique_ptr<Force> Fluid(const Medium& medium, std::vector<int> bodies) {
  if (!(medium.density >= 0) || !std::isfinite(medium.density)) {
    throw std::invalid_argument("fluid: the density must be a finite number >= 0 (kg/m^3)");
  }
  if (!(medium.viscosity >= 0) || !std::isfinite(medium.viscosity)) {
    throw std::invalid_argument("fluid: the viscosity must be a finite number >= 0 (Pa s)");
  }
  if (!medium.wind.allFinite()) throw std::invalid_argument("fluid: the wind must be finite (m/s)");
  for (const int i : bodies) {
    if (i < 0) throw std::invalid_argument("fluid: body " + std::to_string(i) + " does not exist");
  }
  return std::make_unique<FluidForce>(medium, std::move(bodies));
}

std::unique_ptr<Force> Buoyancy(double density, const Vector3& g, int body, double volume) {
  if (!(density >= 0) || !std::isfinite(density)) {
    throw std::invalid_argument("buoyancy: the density must be a finite number >= 0 (kg/m^3)");
  }
  if (!(volume >= 0) || !std::isfinite(volume)) {
    throw std::invalid_argument("buoyancy: the volume must be a finite number >= 0 (m^3)");
  }
  if (body < 0) throw std::invalid_argument("buoyancy: body " + std::to_string(body) + " does not exist");
  return std::make_unique<BuoyancyForce>(-density * volume * g, body);
}

}  // namespace dynamics
