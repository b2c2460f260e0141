#include "dynamics/world.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <Eigen/SVD>

#include "dynamics/free_rigid_body.h"

namespace dynamics {
namespace {

Matrix3 Skew(const Vector3& w) {
  Matrix3 m;
  m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return m;
}

// Rotation by angle about principal axis `axis` (0, 1, 2) as a quaternion.
Quaternion AxisRotation(int axis, double angle) {
  return Quaternion(Eigen::AngleAxisd(angle, Vector3::Unit(axis)));
}

// q̇ = ½ (0, ω_world) ⊗ q.
Quaternion QuaternionRate(const Quaternion& q, const Vector3& omega_world) {
  const Quaternion w(0.0, omega_world.x(), omega_world.y(), omega_world.z());
  Quaternion r = w * q;
  r.coeffs() *= 0.5;
  return r;
}

// Free rotation over h by the implicit midpoint rule on the body angular momentum Π with the
// Cayley update of the attitude. The midpoint equation y = Π0 + (h/2) y × I0⁻¹y (y = Π at the
// midpoint) is solved by Newton's method. Then Π1 = 2y − Π0 and R1 = R0 cay(h I0⁻¹ y); since
// cay(hω)Π1 = Π0 exactly in exact arithmetic, world L = RΠ is untouched and kept as it is.
// Returns false when Newton does not converge (the caller sub-steps).
bool MidpointRotation(RigidBody& b, double h) {
  const Vector3 J = b.inertia.cwiseInverse();
  const Vector3 pi0 = b.BodyAngularMomentum();
  const double scale = pi0.norm();
  if (scale == 0.0) return true;
  // Fixed-point iteration first: it contracts by about h|ω| per sweep and costs a cross product;
  // Newton (a 3×3 solve per iteration) takes over when h|ω| is not small.
  Vector3 y = pi0;
  bool converged = false;
  for (int it = 0; it < 12 && !converged; ++it) {
    const Vector3 next = pi0 + 0.5 * h * y.cross(J.cwiseProduct(y));
    converged = (next - y).norm() <= 1e-15 * scale;
    y = next;
  }
  for (int it = 0; it < 50 && !converged; ++it) {
    const Vector3 w = J.cwiseProduct(y);
    const Vector3 g = y - pi0 - 0.5 * h * y.cross(w);
    const Matrix3 dg = Matrix3::Identity() - 0.5 * h * (-Skew(w) + Skew(y) * J.asDiagonal());
    const Vector3 dy = dg.partialPivLu().solve(g);
    if (!dy.allFinite()) return false;
    y -= dy;
    converged = dy.norm() <= 1e-15 * scale;
  }
  if (!converged) {
    const Vector3 w = J.cwiseProduct(y);
    converged = (y - pi0 - 0.5 * h * y.cross(w)).norm() <= 1e-13 * scale;
  }
  if (!converged) return false;
  const Vector3 half = 0.5 * h * J.cwiseProduct(y);  // Cayley: (1, hω/2) normalized
  const Quaternion dq = Quaternion(1.0, half.x(), half.y(), half.z()).normalized();
  b.orientation = (b.orientation * dq).normalized();
  return true;
}

// Free rotation over h by the symmetric splitting into exact rotations about the principal axes:
// T1(h/2) T2(h/2) T3(h) T2(h/2) T1(h/2). Each flow keeps Π_i and rotates the body about e_i at
// the rate Π_i/I_i. World L is untouched.
void SplittingRotation(RigidBody& b, double h) {
  Vector3 pi = b.BodyAngularMomentum();
  Quaternion q = b.orientation;
  auto flow = [&](int i, double t) {
    const double angle = t * pi[i] / b.inertia[i];
    q = q * AxisRotation(i, angle);
    pi = AxisRotation(i, -angle) * pi;
  };
  flow(0, 0.5 * h);
  flow(1, 0.5 * h);
  flow(2, h);
  flow(1, 0.5 * h);
  flow(0, 0.5 * h);
  b.orientation = q.normalized();
}

// The exact free flow over h; false when the body is outside its domain (the caller falls back).
bool ExactRotation(RigidBody& b, double h) {
  const Vector3& I = b.inertia;
  if (!(I[0] < I[1] && I[1] < I[2])) return false;
  try {
    const ExactFreeRotation flow(I, b.BodyAngularVelocity(), b.orientation);
    b.orientation = flow.Orientation(h).normalized();
    return true;
  } catch (const std::invalid_argument&) {
    return false;  // separatrix or L along the third axis
  }
}

void CheckBody(const RigidBody& b) {
  std::ostringstream msg;
  if (!(b.mass > 0) || !std::isfinite(b.mass)) {
    msg << "mass must be finite and positive, got " << b.mass;
  } else if (!b.inertia.allFinite() || b.inertia.minCoeff() <= 0) {
    msg << "principal moments must be finite and positive, got " << b.inertia.transpose();
  } else {
    Vector3 s = b.inertia;
    std::sort(s.data(), s.data() + 3);
    if (s[0] + s[1] < s[2] * (1 - 1e-9)) {
      msg << "principal moments " << b.inertia.transpose()
          << " violate the triangle inequality I1 + I2 >= I3: no real body has them";
    }
  }
  if (msg.tellp() == 0 && (!b.position.allFinite() || !b.velocity.allFinite() ||
                           !b.orientation.coeffs().allFinite() || !b.angular_momentum.allFinite())) {
    msg << "the state is not finite";
  }
  if (msg.tellp() == 0 && std::fabs(b.orientation.norm() - 1.0) > 1e-6) {
    msg << "the orientation quaternion is not unit (norm " << b.orientation.norm() << ")";
  }
  if (msg.tellp() != 0) throw std::invalid_argument("World::AddBody: " + msg.str());
}

}  // namespace

Matrix3 ExplicitEulerRotation(const Matrix3& R, const Vector3& omega_world, double h, bool reproject) {
  Matrix3 out = R + h * Skew(omega_world) * R;
  if (!reproject) return out;
  Eigen::JacobiSVD<Matrix3> svd(out, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Matrix3 U = svd.matrixU();
  if ((U * svd.matrixV().transpose()).determinant() < 0) U.col(2) *= -1.0;
  return U * svd.matrixV().transpose();
}

const char* IntegratorName(Integrator integrator) {
  switch (integrator) {
    case Integrator::kImplicitMidpoint: return "implicit-midpoint";
    case Integrator::kSplitting: return "splitting";
    case Integrator::kRK4: return "rk4";
    case Integrator::kExplicitEuler: return "explicit-euler";
    case Integrator::kQuaternionEuler: return "quaternion-euler";
    case Integrator::kSymplecticEuler: return "symplectic-euler";
    case Integrator::kImplicitGyroscopic: return "implicit-gyroscopic";
    case Integrator::kExactSplitting: return "exact-splitting";
  }
  return "?";
}

Integrator ParseIntegrator(const std::string& name) {
  for (Integrator i : kAllIntegrators) {
    if (name == IntegratorName(i)) return i;
  }
  throw std::invalid_argument("unknown integrator '" + name +
                              "' (implicit-midpoint, splitting, rk4, explicit-euler, "
                              "quaternion-euler, symplectic-euler, implicit-gyroscopic)");
}

int World::AddBody(const RigidBody& body) {
  CheckBody(body);
  RigidBody b = body;
  b.orientation.normalize();
  bodies_.push_back(b);
  return static_cast<int>(bodies_.size()) - 1;
}

void World::AddForce(std::unique_ptr<Force> force) {
  if (!force) throw std::invalid_argument("World::AddForce: null force");
  if (force->MaxBody() >= static_cast<int>(bodies_.size())) {
    std::ostringstream msg;
    msg << "World::AddForce: the force refers to body " << force->MaxBody() << ", but the world has "
        << bodies_.size() << " bodies (add the bodies first)";
    throw std::invalid_argument(msg.str());
  }
  forces_.push_back(std::move(force));
}

void World::ComputeWrenches(double t, std::vector<Wrench>& out) const {
  out.resize(bodies_.size());
  std::fill(out.begin(), out.end(), Wrench{});
  for (const auto& f : forces_) f->Apply(t, bodies_, out);
}

template <typename Fn>
void World::ForEachBody(const Fn& fn) {
  const std::size_t n = bodies_.size();
  if (n < 4096) {  // not worth a thread
    for (std::size_t i = 0; i < n; ++i) fn(i);
    return;
  }
  static const int kHardwareThreads = static_cast<int>(std::thread::hardware_concurrency());
  const int threads = num_threads_ > 0 ? num_threads_ : kHardwareThreads;
  if (threads <= 1) {
    for (std::size_t i = 0; i < n; ++i) fn(i);
    return;
  }
  constexpr std::size_t kChunk = 1024;
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t c = next.fetch_add(1); c * kChunk < n; c = next.fetch_add(1)) {
      for (std::size_t i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i) fn(i);
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
}

bool World::TryStep(double h) {
  std::vector<Wrench>& w = wrenches_;
  const std::size_t n = bodies_.size();
  switch (integrator_) {
    case Integrator::kImplicitMidpoint:
    case Integrator::kSplitting:
    case Integrator::kExactSplitting: {
      auto half_kick = [&] {
        ForEachBody([&](std::size_t i) {
          bodies_[i].velocity += 0.5 * h / bodies_[i].mass * w[i].force;
          bodies_[i].angular_momentum += 0.5 * h * w[i].torque;
        });
      };
      ComputeWrenches(time_, w);
      half_kick();
      std::atomic<bool> ok{true};
      ForEachBody([&](std::size_t i) {  // drift
        bodies_[i].position += h * bodies_[i].velocity;
        if (integrator_ == Integrator::kSplitting) {
          SplittingRotation(bodies_[i], h);
        } else if (integrator_ == Integrator::kExactSplitting && ExactRotation(bodies_[i], h)) {
          // done
        } else if (!MidpointRotation(bodies_[i], h)) {
          ok = false;
        }
      });
      if (!ok) return false;
      ComputeWrenches(time_ + h, w);
      half_kick();
      return true;
    }
    case Integrator::kExplicitEuler: {
      ComputeWrenches(time_, w);
      ForEachBody([&](std::size_t i) {
        RigidBody& b = bodies_[i];
        const Vector3 omega = b.AngularVelocity();
        b.position += h * b.velocity;
        b.velocity += h / b.mass * w[i].force;
        b.orientation = Quaternion(ExplicitEulerRotation(b.Rotation(), omega, h, true)).normalized();
        b.angular_momentum += h * w[i].torque;
      });
      return true;
    }
    case Integrator::kQuaternionEuler: {
      ComputeWrenches(time_, w);
      ForEachBody([&](std::size_t i) {
        RigidBody& b = bodies_[i];
        const Quaternion dq = QuaternionRate(b.orientation, b.AngularVelocity());
        b.position += h * b.velocity;
        b.velocity += h / b.mass * w[i].force;
        b.orientation.coeffs() += h * dq.coeffs();
        b.orientation.normalize();
        b.angular_momentum += h * w[i].torque;
      });
      return true;
    }
    case Integrator::kSymplecticEuler: {
      ComputeWrenches(time_, w);
      ForEachBody([&](std::size_t i) {
        RigidBody& b = bodies_[i];
        b.velocity += h / b.mass * w[i].force;
        b.angular_momentum += h * w[i].torque;
        b.position += h * b.velocity;
        const Quaternion dq = QuaternionRate(b.orientation, b.AngularVelocity());
        b.orientation.coeffs() += h * dq.coeffs();
        b.orientation.normalize();
      });
      return true;
    }
    case Integrator::kImplicitGyroscopic: {
      ComputeWrenches(time_, w);
      ForEachBody([&](std::size_t i) {
        RigidBody& b = bodies_[i];
        b.velocity += h / b.mass * w[i].force;
        b.position += h * b.velocity;
        // Body frame: explicit torque, then one Newton step of I0(ω' − ω) + h ω' × I0ω' = 0
        // from ω' = ω (Catto 2015).
        const Matrix3 I0 = b.inertia.asDiagonal();
        Vector3 omega = b.BodyAngularVelocity() +
                        h * (b.orientation.conjugate() * w[i].torque).cwiseQuotient(b.inertia);
        const Vector3 f = h * omega.cross(I0 * omega);
        const Matrix3 jac = I0 + h * (Skew(omega) * I0 - Skew(I0 * omega));
        omega -= jac.partialPivLu().solve(f);
        // As engines do, the world angular velocity is the state carried over the attitude
        // update; L follows from it with the new attitude.
        const Vector3 omega_world = b.orientation * omega;
        const Quaternion dq = QuaternionRate(b.orientation, omega_world);
        b.orientation.coeffs() += h * dq.coeffs();
        b.orientation.normalize();
        b.angular_momentum = b.orientation * (I0 * (b.orientation.conjugate() * omega_world));
      });
      return true;
    }
    case Integrator::kRK4: {
      // Stages on copies of the whole state, so that coupled forces see consistent states.
      rk4_start_ = bodies_;
      const std::vector<RigidBody>& start = rk4_start_;
      auto rates = [&](double t, std::vector<Rate>& k) {
        ComputeWrenches(t, w);
        k.resize(n);
        ForEachBody([&](std::size_t i) {
          const RigidBody& b = bodies_[i];
          k[i].dx = b.velocity;
          k[i].dv = w[i].force / b.mass;
          k[i].dL = w[i].torque;
          k[i].dq = QuaternionRate(b.orientation, b.AngularVelocity()).coeffs();
        });
      };
      auto set_stage = [&](const std::vector<Rate>& k, double a) {
        ForEachBody([&](std::size_t i) {
          RigidBody& b = bodies_[i];
          b.position = start[i].position + a * k[i].dx;
          b.velocity = start[i].velocity + a * k[i].dv;
          b.angular_momentum = start[i].angular_momentum + a * k[i].dL;
          b.orientation.coeffs() = start[i].orientation.coeffs() + a * k[i].dq;
          b.orientation.normalize();  // stages stay on the unit sphere (ω is then well defined)
        });
      };
      std::vector<Rate>& k1 = rk4_k_[0];
      std::vector<Rate>& k2 = rk4_k_[1];
      std::vector<Rate>& k3 = rk4_k_[2];
      std::vector<Rate>& k4 = rk4_k_[3];
      rates(time_, k1);
      set_stage(k1, 0.5 * h);
      rates(time_ + 0.5 * h, k2);
      set_stage(k2, 0.5 * h);
      rates(time_ + 0.5 * h, k3);
      set_stage(k3, h);
      rates(time_ + h, k4);
      ForEachBody([&](std::size_t i) {
        RigidBody& b = bodies_[i];
        b.position = start[i].position + h / 6 * (k1[i].dx + 2 * k2[i].dx + 2 * k3[i].dx + k4[i].dx);
        b.velocity = start[i].velocity + h / 6 * (k1[i].dv + 2 * k2[i].dv + 2 * k3[i].dv + k4[i].dv);
        b.angular_momentum =
            start[i].angular_momentum + h / 6 * (k1[i].dL + 2 * k2[i].dL + 2 * k3[i].dL + k4[i].dL);
        b.orientation.coeffs() = start[i].orientation.coeffs() +
                                 h / 6 * (k1[i].dq + 2 * k2[i].dq + 2 * k3[i].dq + k4[i].dq);
        b.orientation.normalize();
      });
      return true;
    }
  }
  return false;
}

StepStatus World::Step(double h) {
  if (!(h > 0) || !std::isfinite(h)) {
    std::ostringstream msg;
    msg << "World::Step: the time step must be finite and positive, got " << h;
    throw std::invalid_argument(msg.str());
  }
  StepStatus status;
  const double t0 = time_;
  if (integrator_ != Integrator::kImplicitMidpoint && integrator_ != Integrator::kExactSplitting) {
    TryStep(h);
    time_ = t0 + h;
    return status;
  }
  const std::vector<RigidBody> saved = bodies_;
  for (int substeps = 1; substeps <= 1024; substeps *= 2) {
    bool ok = true;
    const double dt = h / substeps;
    for (int s = 0; s < substeps && ok; ++s) {
      ok = TryStep(dt);
      time_ = t0 + dt * (s + 1);
    }
    if (ok) {
      time_ = t0 + h;
      status.substeps = substeps;
      return status;
    }
    bodies_ = saved;
    time_ = t0;
  }
  throw std::runtime_error(
      "World::Step: the implicit midpoint solve did not converge even with 1024 sub-steps; the "
      "angular velocity is too large for this step (reduce the time step)");
}

Drift DriftSince(const Diagnostics& start, const Diagnostics& now) {
  auto rel = [](double change, double scale) { return scale != 0.0 ? change / scale : change; };
  Drift d;
  const double e_scale = start.total_energy != 0.0 ? std::fabs(start.total_energy) : start.kinetic_energy;
  d.energy = rel(now.total_energy - start.total_energy, e_scale);
  d.linear_momentum = rel((now.linear_momentum - start.linear_momentum).norm(), start.linear_momentum.norm());
  d.angular_momentum = rel((now.angular_momentum - start.angular_momentum).norm(), start.angular_momentum.norm());
  return d;
}

Conservation World::Conserves() const {
  Conservation c;
  auto note = [](std::string& list, const char* what) {
    if (list.find(what) == std::string::npos) list += (list.empty() ? "" : ", ") + std::string(what);
  };
  for (const auto& f : forces_) {
    const ForceTraits t = f->Traits();
    if (t.breaks_energy) {
      c.energy = false;
      note(c.energy_broken_by, t.breaks_energy);
    }
    if (t.breaks_momentum) {
      c.momentum = false;
      note(c.momentum_broken_by, t.breaks_momentum);
    }
  }
  return c;
}

Diagnostics World::Diagnose() const {
  Diagnostics d;
  d.time = time_;
  for (const RigidBody& b : bodies_) {
    d.kinetic_energy += b.KineticEnergy();
    d.linear_momentum += b.LinearMomentum();
    d.angular_momentum += b.AngularMomentumAbout(Vector3::Zero());
  }
  for (const auto& f : forces_) d.potential_energy += f->PotentialEnergy(bodies_);
  d.total_energy = d.kinetic_energy + d.potential_energy;
  return d;
}

}  // namespace dynamics
