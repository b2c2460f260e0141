// The definitions of dynamics/world.h: a world of rigid bodies stepped together, with the
// integrators of the project and energy and momentum diagnostics.

#include "dynamics/world.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "articulated/articulation.h"
#include "integrators/integrator.h"

namespace dynamics {
namespace {

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
  if (msg.tellp() == 0 && (!b.position.allFinite() || !b.velocity.allFinite() || !b.orientation.coeffs().allFinite() ||
                           !b.angular_momentum.allFinite())) {
    msg << "the state is not finite";
  }
  if (msg.tellp() == 0 && std::fabs(b.orientation.norm() - 1.0) > 1e-6) {
    msg << "the orientation quaternion is not unit (norm " << b.orientation.norm() << ")";
  }
  if (msg.tellp() != 0) throw std::invalid_argument("World::AddBody: " + msg.str());
}

}  // namespace

World::World(Integrator integrator) : integrator_(integrator), scratch_(std::make_unique<internal::StepScratch>()) {}
World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

int World::AddBody(const RigidBody& body) {
  CheckBody(body);
  if (jointed_ && time_ != 0.0) {
    throw std::invalid_argument("World::AddBody: an articulated world takes its bodies before its first step");
  }
  RigidBody b = body;
  b.orientation.normalize();
  bodies_.push_back(b);
  as_added_.push_back(b);
  parent_of_.push_back(-1);
  if (jointed_) placed_ = false;  // (a new free body needs no placing; joints waiting to place theirs still do)
  return static_cast<int>(bodies_.size()) - 1;
}

int World::AddJoint(const Joint& joint) {
  if (time_ != 0.0)
    throw std::invalid_argument("World::AddJoint: joint '" + joint.name + "': add joints before the first step");
  internal::CheckJoint(joint, static_cast<int>(bodies_.size()), joints_);
  bool loop = false;  // the child among the parent's ancestors
  for (int b = joint.parent; b >= 0 && !loop; b = parent_of_[static_cast<std::size_t>(b)]) loop = b == joint.child;
  joints_.push_back(joint);
  if (loop) {
    try {
      std::vector<RigidBody> bodies = bodies_;
      [[maybe_unused]] const internal::Articulation refused(joints_, bodies);  // names a body the loop leaves out
    } catch (...) {
      joints_.pop_back();
      throw;
    }
  }
  parent_of_[static_cast<std::size_t>(joint.child)] = joint.parent;
  // Only free joints from the world (so no body carries another): free bodies, stepped as such
  // (placed by their joints all the same).
  jointed_ = jointed_ || joint.type != JointType::kFree || joint.parent >= 0;
  placed_ = false;
  return static_cast<int>(joints_.size()) - 1;
}

void World::Place() const {
  if (placed_) return;
  auto articulation = std::make_unique<internal::Articulation>(joints_, bodies_);
  articulation->SetConstraints(loops_, couplings_, tendons_);
  articulation_ = jointed_ ? std::move(articulation) : nullptr;
  placed_ = true;
}

JointState World::joint_state(int j) const {
  if (j < 0 || j >= static_cast<int>(joints_.size())) {
    throw std::out_of_range("World::joint_state: no joint " + std::to_string(j));
  }
  Place();
  return articulation_ ? articulation_->State(j)
                       : internal::JointStateFromBodies(joints_[static_cast<std::size_t>(j)], bodies_);
}

void World::AddForce(std::unique_ptr<Force> force) {
  if (!force) throw std::invalid_argument("World::AddForce: null force");
  if (force->MaxBody() >= static_cast<int>(bodies_.size())) {
    std::ostringstream msg;
    msg << "World::AddForce: the force refers to body " << force->MaxBody() << ", but the world has " << bodies_.size()
        << " bodies (add the bodies first)";
    throw std::invalid_argument(msg.str());
  }
  forces_.push_back(std::move(force));
}

StepStatus internal::Diverged(double time, int body, const char* quantity) {
  StepStatus status;
  status.ok = false;
  status.diverged = true;
  status.body = body;
  std::ostringstream msg;
  msg << "diverged at t = " << time << " s: body " << body << "'s " << quantity
      << " is no longer finite (forces too large for this step, or an unstable integrator; reduce the time step)";
  status.message = msg.str();
  return status;
}

StepStatus World::Step(double h) {
  if (!(h > 0) || !std::isfinite(h)) {
    std::ostringstream msg;
    msg << "World::Step: the time step must be finite and positive, got " << h;
    throw std::invalid_argument(msg.str());
  }
  StepStatus status = Advance(h);
  if (status.ok) {
    const auto [body, quantity] = FirstNonFinite();
    if (body >= 0) {
      const int substeps = status.substeps;
      status = internal::Diverged(time_, body, quantity);
      status.substeps = substeps;
    }
  }
  return status;
}

std::pair<int, const char*> World::FirstNonFinite() const {
  Place();
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const RigidBody& b = bodies_[i];
    // One sum per body: a NaN or an infinity anywhere makes it non-finite.
    const double sum = b.position.sum() + b.velocity.sum() + b.orientation.coeffs().sum() + b.angular_momentum.sum();
    if (std::isfinite(sum)) continue;
    // Find the quantity (the sum can also overflow while every part is finite).
    if (!b.position.allFinite()) return {static_cast<int>(i), "position"};
    if (!b.velocity.allFinite()) return {static_cast<int>(i), "velocity"};
    if (!b.orientation.coeffs().allFinite()) return {static_cast<int>(i), "orientation"};
    if (!b.angular_momentum.allFinite()) return {static_cast<int>(i), "angular momentum"};
  }
  return {-1, ""};
}

StepStatus World::Advance(double h) {
  Place();
  const internal::IntegratorInfo& info = internal::Info(integrator_);
  if (articulation_) {
    if (integrator_ != Integrator::kImplicitMidpoint && integrator_ != Integrator::kRK4) {
      throw std::invalid_argument(std::string("World::Step: the ") + info.name +
                                  " integrator has no meaning for joints (it steps free bodies); an articulated world "
                                  "takes implicit-midpoint or rk4");
    }
    if (integrator_ != Integrator::kImplicitMidpoint && articulation_->Bilateral()) {
      throw std::invalid_argument(std::string("World::Step: loops and couplings are held by the implicit-midpoint "
                                              "integrator only, not ") +
                                  info.name);
    }
    const double t0 = time_;
    StepStatus status = articulation_->Advance(integrator_, forces_, t0, h, bodies_);
    time_ = t0 + h;
    return status;
  }
  internal::StepContext context(bodies_, forces_, *scratch_, num_threads_);
  StepStatus status;
  const double t0 = time_;
  if (!info.may_fail) {
    info.step(context, t0, h);
    time_ = t0 + h;
    return status;
  }
  std::vector<RigidBody>& saved = scratch_->saved;
  saved.assign(bodies_.begin(), bodies_.end());  // into kept capacity: no allocation after the first step
  const int substeps = internal::StepWithHalving(
      t0, h, [] {},
      [&](double t, double dt, int s) {
        const bool ok = info.step(context, t, dt);
        time_ = t0 + dt * (s + 1);
        return ok;
      },
      [&] {
        std::copy(saved.begin(), saved.end(), bodies_.begin());
        time_ = t0;
      });
  if (substeps > 0) {
    time_ = t0 + h;
    status.substeps = substeps;
    return status;
  }
  status.ok = false;
  status.substeps = internal::kMostSubsteps;
  status.message = std::string("the ") + info.name +
                   " solve did not converge even with 1024 sub-steps; the angular velocity is too large for "
                   "this step (reduce the time step)";
  return status;
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
  for (const Joint& j : joints_) {
    if (j.damping > 0) note(c.energy_broken_by, "joint damping");
    if (j.friction > 0) note(c.energy_broken_by, "joint friction");
    if (j.motor.mode != JointMotor::Mode::kOff) note(c.energy_broken_by, "joint motors");
    if (HasOneCoordinate(j.type) && j.limits.restitution < 1 &&
        (std::isfinite(j.limits.lower) || std::isfinite(j.limits.upper))) {
      note(c.energy_broken_by, "joint stops");
    }
    if (j.parent < 0 && j.type != JointType::kFree) note(c.momentum_broken_by, "joints to the world");
  }
  for (const Tendon& t : tendons_) {
    if (t.damping > 0) note(c.energy_broken_by, "tendon damping");
    if (t.motor.mode != JointMotor::Mode::kOff) note(c.energy_broken_by, "tendon motors");
    if (t.limits.restitution < 1 && (std::isfinite(t.limits.lower) || std::isfinite(t.limits.upper)))
      note(c.energy_broken_by, "tendon ranges");
  }
  for (const Loop& l : loops_) {
    if (l.a.body < 0 || l.b.body < 0) note(c.momentum_broken_by, "loops to the world");
  }
  c.energy = c.energy_broken_by.empty();
  c.momentum = c.momentum_broken_by.empty();
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
  Place();
  Diagnostics d;
  d.time = time_;
  for (const RigidBody& b : bodies_) {
    d.kinetic_energy += b.KineticEnergy();
    d.linear_momentum += b.LinearMomentum();
    d.angular_momentum += b.AngularMomentumAbout(Vector3::Zero());
  }
  for (const auto& f : forces_) d.potential_energy += f->PotentialEnergy(bodies_);
  if (articulation_) {
    d.potential_energy += articulation_->SpringEnergy();
    d.kinetic_energy += articulation_->ArmatureEnergy();
  }
  d.total_energy = d.kinetic_energy + d.potential_energy;
  return d;
}

}  // namespace dynamics
