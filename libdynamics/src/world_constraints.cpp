// World's loops, couplings and tendons (dynamics/constraints.h): their checks, and their states
// read from the articulation.

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "articulated/articulation.h"
#include "dynamics/world.h"

namespace dynamics {
namespace {

[[noreturn]] void Refuse(const char* call, const std::string& what, const std::string& name, const std::string& why) {
  throw std::invalid_argument(std::string("World::") + call + ": " + what + " '" + name + "': " + why);
}

void CheckBody(const char* call, const std::string& what, const std::string& name, int body, int num_bodies) {
  if (body < -1 || body >= num_bodies) {
    Refuse(call, what, name,
           "body " + std::to_string(body) + " does not exist (the world has " + std::to_string(num_bodies) + ")");
  }
}

void CheckFrame(const char* call, const std::string& what, const std::string& name, const Frame& f) {
  if (!f.origin.allFinite() || !f.orientation.coeffs().allFinite() || !(f.orientation.norm() > 0)) {
    Refuse(call, what, name, "a frame that is not finite (or a zero quaternion)");
  }
}

}  // namespace

Frame InWorld(const std::vector<RigidBody>& bodies, const BodyFrame& f) {
  Frame world;
  world.origin = f.frame.origin;
  world.orientation = f.frame.orientation.normalized();
  if (f.body < 0) return world;
  const RigidBody& b = bodies.at(static_cast<std::size_t>(f.body));
  world.origin = b.position + b.orientation.normalized() * f.frame.origin;
  world.orientation = b.orientation.normalized() * world.orientation;
  return world;
}

int World::AddLoop(const Loop& loop) {
  const char* call = "AddLoop";
  if (time_ != 0.0) Refuse(call, "loop", loop.name, "add loops before the first step");
  const int nb = static_cast<int>(bodies_.size());
  CheckBody(call, "loop", loop.name, loop.a.body, nb);
  CheckBody(call, "loop", loop.name, loop.b.body, nb);
  CheckFrame(call, "loop", loop.name, loop.a.frame);
  CheckFrame(call, "loop", loop.name, loop.b.frame);
  if (loop.a.body == loop.b.body) Refuse(call, "loop", loop.name, "both frames are on one body");
  if (!(loop.tolerance >= 0)) Refuse(call, "loop", loop.name, "a negative tolerance");
  // The frames must meet as the joints place the bodies now.
  Place();
  const Frame a = InWorld(bodies_, loop.a), b = InWorld(bodies_, loop.b);
  const Vector3 &pa = a.origin, &pb = b.origin;
  const Matrix3 Ra = a.orientation.toRotationMatrix(), Rb = b.orientation.toRotationMatrix();
  Vector3 gap = pb - pa;
  if (loop.type == LoopType::kSlider) gap -= Ra.col(2) * Ra.col(2).dot(gap);
  double turn = 0;
  if (loop.type == LoopType::kWeld || loop.type == LoopType::kSlider) {
    turn = Eigen::AngleAxisd(Rb * Ra.transpose()).angle();
  } else if (loop.type == LoopType::kHinge) {
    turn = std::acos(std::clamp(Ra.col(2).dot(Rb.col(2)), -1.0, 1.0));
  }
  if (gap.norm() > loop.tolerance || turn > loop.tolerance) {
    std::ostringstream msg;
    msg << "its frames do not meet where the joints place the bodies: " << gap.norm() << " m apart";
    if (turn > 0) msg << " and turned by " << turn << " rad";
    msg << " (tolerance " << loop.tolerance << ")";
    Refuse(call, "loop", loop.name, msg.str());
  }
  loops_.push_back(loop);
  jointed_ = true;
  placed_ = false;
  return static_cast<int>(loops_.size()) - 1;
}

int World::AddCoupling(const Coupling& coupling) {
  const char* call = "AddCoupling";
  const std::string& name = coupling.name;
  if (time_ != 0.0) Refuse(call, "coupling", name, "add couplings before the first step");
  auto check = [&](const Coordinate& x, const char* role) {
    if (x.index < 0) return;
    if (x.kind == Coordinate::Kind::kTendon) {
      if (x.index >= static_cast<int>(tendons_.size()))
        Refuse(call, "coupling", name,
               std::string("its ") + role + ", tendon " + std::to_string(x.index) + ", does not exist");
      return;
    }
    if (x.index >= static_cast<int>(joints_.size()))
      Refuse(call, "coupling", name,
             std::string("its ") + role + ", joint " + std::to_string(x.index) + ", does not exist");
    const Joint& j = joints_[static_cast<std::size_t>(x.index)];
    if (!HasOneCoordinate(j.type))
      Refuse(call, "coupling", name,
             std::string("its ") + role + ", joint '" + j.name + "', is " + JointTypeName(j.type) +
                 ": only revolute and prismatic joints couple");
  };
  if (coupling.follower.index < 0) Refuse(call, "coupling", name, "it has no follower");
  check(coupling.follower, "follower");
  check(coupling.leader, "leader");
  if (coupling.leader.index >= 0 && coupling.leader.kind == coupling.follower.kind &&
      coupling.leader.index == coupling.follower.index) {
    Refuse(call, "coupling", name, "it couples a coordinate to itself");
  }
  for (double c : coupling.polynomial) {
    if (!std::isfinite(c)) Refuse(call, "coupling", name, "a coefficient is not finite");
  }
  if (!std::isfinite(coupling.follower_reference) || !std::isfinite(coupling.leader_reference))
    Refuse(call, "coupling", name, "a reference is not finite");
  auto same = [](const Coordinate& a, const Coordinate& b) { return a.kind == b.kind && a.index == b.index; };
  for (const Coupling& c : couplings_) {
    if (same(c.follower, coupling.follower))
      Refuse(call, "coupling", name, "its follower already follows coupling '" + c.name + "'");
  }
  // A cycle: the leader, followed up its own leaders, comes back to the follower.
  Coordinate at = coupling.leader;
  for (std::size_t steps = 0; at.index >= 0 && steps <= couplings_.size(); ++steps) {
    if (same(at, coupling.follower)) Refuse(call, "coupling", name, "it closes a cycle of couplings");
    const Coupling* up = nullptr;
    for (const Coupling& c : couplings_) {
      if (same(c.follower, at)) up = &c;
    }
    if (!up) break;
    at = up->leader;
  }
  couplings_.push_back(coupling);
  jointed_ = true;
  placed_ = false;
  return static_cast<int>(couplings_.size()) - 1;
}

int World::AddTendon(const Tendon& tendon) {
  const char* call = "AddTendon";
  const std::string& name = tendon.name;
  if (time_ != 0.0) Refuse(call, "tendon", name, "add tendons before the first step");
  if (tendon.joints.empty() == tendon.path.empty())
    Refuse(call, "tendon", name, "a tendon is fixed (joints) or spatial (a path), one of the two");
  for (const auto& [j, c] : tendon.joints) {
    if (j < 0 || j >= static_cast<int>(joints_.size()))
      Refuse(call, "tendon", name, "joint " + std::to_string(j) + " does not exist");
    if (!HasOneCoordinate(joints_[static_cast<std::size_t>(j)].type))
      Refuse(call, "tendon", name,
             "joint '" + joints_[static_cast<std::size_t>(j)].name + "' is not revolute or prismatic");
    if (!std::isfinite(c)) Refuse(call, "tendon", name, "a coefficient is not finite");
  }
  if (!tendon.path.empty() && tendon.path.size() < 2)
    Refuse(call, "tendon", name, "a spatial tendon needs two points or more");
  for (const BodyFrame& f : tendon.path) {
    CheckBody(call, "tendon", name, f.body, static_cast<int>(bodies_.size()));
    CheckFrame(call, "tendon", name, f.frame);
  }
  if (std::isnan(tendon.limits.lower) || std::isnan(tendon.limits.upper) || tendon.limits.lower > tendon.limits.upper)
    Refuse(call, "tendon", name, "its range's lower end is above its upper (or not a number)");
  if (!(tendon.stiffness >= 0) || !(tendon.damping >= 0) || !std::isfinite(tendon.rest_length))
    Refuse(call, "tendon", name, "a negative (or not finite) stiffness, damping or rest length");
  if (tendon.motor.mode == JointMotor::Mode::kVelocity)
    Refuse(call, "tendon", name, "a velocity motor on a tendon is not simulated (use a position motor, kp = 0)");
  tendons_.push_back(tendon);
  jointed_ = true;
  placed_ = false;
  return static_cast<int>(tendons_.size()) - 1;
}

ConstraintState World::loop_state(int k) const {
  if (k < 0 || k >= static_cast<int>(loops_.size()))
    throw std::out_of_range("World::loop_state: no loop " + std::to_string(k));
  Place();
  return articulation_->LoopState(k);
}

ConstraintState World::coupling_state(int k) const {
  if (k < 0 || k >= static_cast<int>(couplings_.size()))
    throw std::out_of_range("World::coupling_state: no coupling " + std::to_string(k));
  Place();
  return articulation_->CouplingState(k);
}

ConstraintState World::tendon_state(int k) const {
  if (k < 0 || k >= static_cast<int>(tendons_.size()))
    throw std::out_of_range("World::tendon_state: no tendon " + std::to_string(k));
  Place();
  return articulation_->TendonState(k);
}

}  // namespace dynamics
