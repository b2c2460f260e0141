#pragma once
/// @file
/// Forces and torques acting on the bodies of a World. Each force adds to per-body world force f
/// and world torque τ about the center of mass, and, where it has one, reports its potential
/// energy (for the energy diagnostics).

#include <functional>
#include <memory>
#include <vector>

#include "dynamics/rigid_body.h"

namespace dynamics {

struct Wrench {
  Vector3 force = Vector3::Zero();   ///< N, world
  Vector3 torque = Vector3::Zero();  ///< N·m, world, about the center of mass
};

/// What a force does to the conserved quantities, so that diagnostics can say which of energy and
/// momentum a world's physics conserves. nullptr means the force keeps it; otherwise a short name
/// for summaries ("gravity", "damping", ...).
struct ForceTraits {
  /// Non-null when the force does work not accounted for by PotentialEnergy (damping, applied loads).
  const char* breaks_energy = nullptr;
  /// Non-null when the force is external (not equal-and-opposite pairs between bodies).
  const char* breaks_momentum = nullptr;
  /// True when the force depends on velocities (damping, damped springs): the kick–drift–kick
  /// integrators then solve the first half kick implicitly, which keeps them second order.
  bool velocity_dependent = false;
};

class Force {
 public:
  virtual ~Force() = default;
  virtual ForceTraits Traits() const = 0;
  /// Adds this force's wrenches at time t to `out` (one per body).
  virtual void Apply(double t, const std::vector<RigidBody>& bodies, std::vector<Wrench>& out) const = 0;
  /// Potential energy, J (0 for non-conservative forces).
  virtual double PotentialEnergy(const std::vector<RigidBody>&) const { return 0.0; }
  /// The largest body index this force refers to (-1: none in particular).
  virtual int MaxBody() const { return -1; }
};

/// Uniform gravity g (m/s²) on every body: f = M g, potential −M g·x.
std::unique_ptr<Force> Gravity(const Vector3& g);
/// Linear damping f = −c v (N·s/m) on one body (or every body with body = -1).
std::unique_ptr<Force> LinearDamping(double c, int body = -1);
/// Angular damping τ = −c ω (N·m·s) on one body (or every body with body = -1).
std::unique_ptr<Force> AngularDamping(double c, int body = -1);
/// Constant world force through the center of mass, and constant world torque.
std::unique_ptr<Force> ConstantForce(int body, const Vector3& force);
std::unique_ptr<Force> ConstantTorque(int body, const Vector3& torque);
/// Constant torque given in body (principal) axes, turning with the body: τ_world = R τ_B.
std::unique_ptr<Force> BodyFrameTorque(int body, const Vector3& torque_body);
/// Constant force at a body point (body coordinates); `body_frame` says whether the force vector
/// turns with the body. Torque (p − x) × f.
std::unique_ptr<Force> PointForce(int body, const Vector3& point_body, const Vector3& force, bool body_frame);
/// Damped spring from a body point (body coordinates) to a world anchor: stiffness k (N/m), rest
/// length l0 (m), damping c (N·s/m) along the spring.
std::unique_ptr<Force> SpringToWorld(int body, const Vector3& point_body, const Vector3& anchor, double k,
                                     double rest_length, double damping);
/// Damped spring between points of two bodies (body coordinates).
std::unique_ptr<Force> SpringBetween(int body_a, const Vector3& point_a, int body_b, const Vector3& point_b, double k,
                                     double rest_length, double damping);
/// A medium the bodies move through: MuJoCo's inertia-box fluid model (`<option density viscosity
/// wind>`). Each body is taken as the box of its mass M and principal moments, half-sizes
/// rᵢ = √(3/(2M) (Iⱼ + Iₖ − Iᵢ)); in its principal axes, with v its velocity relative to the wind
/// and ω its angular velocity, it feels
///   quadratic drag (ρ):  fᵢ = −2 ρ rⱼ rₖ |vᵢ| vᵢ,   τᵢ = −½ ρ rᵢ (rⱼ⁴ + rₖ⁴) |ωᵢ| ωᵢ
///   viscous (β):         fᵢ = −6 π β r_eq vᵢ,      τᵢ = −8 π β r_eq³ ωᵢ,   r_eq = (r₁ + r₂ + r₃)/3.
/// MuJoCo's model has no buoyancy: that is Buoyancy's.
struct Medium {
  double density = 0;              ///< ρ, kg/m³ (air 1.2, water 1000)
  double viscosity = 0;            ///< β, Pa·s (air 1.8e-5, water 1e-3)
  Vector3 wind = Vector3::Zero();  ///< the medium's velocity, m/s, world
};
/// The medium's drag on `bodies` (empty: every body). @throws std::invalid_argument for a negative
/// or non-finite density or viscosity, or a wind that is not finite.
std::unique_ptr<Force> Fluid(const Medium& medium, std::vector<int> bodies = {});
/// The weight of the medium a body displaces, −ρ V g on body `body` of volume V (m³) through its
/// center of mass (its center of buoyancy for a uniform solid wholly immersed), with the potential
/// ρ V g·x. @throws std::invalid_argument for a negative density or volume.
std::unique_ptr<Force> Buoyancy(double density, const Vector3& g, int body, double volume);
/// Any user force: called with the time, the bodies and the wrenches to add to. Its traits say
/// what it breaks (default: energy and momentum, as "user forces") and whether it depends on the
/// velocities (default: yes, the safe assumption).
std::unique_ptr<Force> ForceCallback(
    std::function<void(double, const std::vector<RigidBody>&, std::vector<Wrench>&)> fn,
    ForceTraits traits = {"user forces", "user forces", true});

}  // namespace dynamics
