// A robot file's couplings, loops and tendons made the world's (robot_constraints.h).

#include "robot_constraints.h"

#include <limits>
#include <stdexcept>

namespace dynamics::internal {
namespace {

using massprops::Placement;

class Placer {
 public:
  Placer(const massprops::RobotModel& model, const Placement& pose, const RobotInWorld& added,
         const std::vector<Placement>& reference)
      : model_(model), pose_(pose), added_(added), reference_(reference) {}
  // A frame `p` of link `link` (-1: the file's world) as a frame of its body.
  BodyFrame On(int link, const Placement& p) const {
    BodyFrame f;
    if (link < 0) {
      f.frame = FrameOf(pose_.Then(p));
      return f;
    }
    f.body = added_.body_of_link[static_cast<std::size_t>(link)];
    f.frame = FrameOf(added_.link_in_body[static_cast<std::size_t>(link)].Then(p));
    return f;
  }
  // Where a body's frame is at the reference configuration, in the world.
  Placement AtReference(const BodyFrame& f) const {
    const Placement frame{f.frame.orientation.toRotationMatrix(), f.frame.origin};
    return f.body < 0 ? frame : Reference(f.body).Then(frame);
  }
  // A world placement as a frame of link `link`'s body at the reference configuration.
  BodyFrame Into(int link, const Placement& world) const {
    if (link < 0) return BodyFrame{-1, FrameOf(world)};
    const int body = added_.body_of_link[static_cast<std::size_t>(link)];
    return BodyFrame{body, FrameOf(Reference(body).Inverse().Then(world))};
  }
  // A tendon's length at the reference configuration (a fixed one's: 0, every joint at 0).
  double ReferenceLength(const Tendon& t) const {
    double length = 0;
    for (std::size_t k = 0; k + 1 < t.path.size(); ++k)
      length += (AtReference(t.path[k + 1]).translation - AtReference(t.path[k]).translation).norm();
    return length;
  }
  int Joint(int k, const std::string& what) const {
    const int j = added_.joint_of[static_cast<std::size_t>(k)];
    if (j < 0) {
      throw std::invalid_argument(model_.path + ": " + what + ": joint '" +
                                  model_.joints[static_cast<std::size_t>(k)].name +
                                  "' does not move here (fixed, lumped or a free root): nothing to couple");
    }
    return j;
  }

 private:
  const Placement& Reference(int body) const {
    return reference_.at(static_cast<std::size_t>(body - added_.bodies.front()));
  }
  const massprops::RobotModel& model_;
  const Placement& pose_;
  const RobotInWorld& added_;
  const std::vector<Placement>& reference_;
};

// Runs `add`, what the world refuses named by the file too.
template <typename Add>
void Named(const massprops::RobotModel& model, const Add& add) {
  try {
    add();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(model.path + ": " + e.what());
  }
}

}  // namespace

Frame FrameOf(const Placement& p) {
  Frame f;
  f.origin = p.translation;
  f.orientation = Quaternion(p.rotation).normalized();
  return f;
}

void AddRobotConstraints(ContactWorld& world, const massprops::RobotModel& model, const Placement& pose,
                         const RobotInWorld& added, const std::vector<Placement>& reference,
                         const std::vector<JointMotor>& tendon_motors) {
  const Placer place(model, pose, added, reference);
  std::vector<double> lengths;  // each tendon's at the reference configuration
  for (std::size_t t = 0; t < model.tendons.size(); ++t) {
    const massprops::RobotTendon& rt = model.tendons[t];
    const std::string what = "tendon '" + rt.name + "'";
    Tendon tendon;
    tendon.name = rt.name;
    for (const auto& [k, c] : rt.joints) tendon.joints.emplace_back(place.Joint(k, what), c);
    for (const auto& [link, point] : rt.path)
      tendon.path.push_back(place.On(link, Placement{Matrix3::Identity(), point}));
    if (rt.range) tendon.limits.lower = rt.range->first, tendon.limits.upper = rt.range->second;
    tendon.stiffness = rt.stiffness;
    tendon.damping = rt.damping;
    lengths.push_back(place.ReferenceLength(tendon));
    for (const auto& [k, c] : rt.joints) lengths.back() += c * model.joints[static_cast<std::size_t>(k)].ref;
    tendon.rest_length = rt.rest_length ? *rt.rest_length : lengths.back();
    if (t < tendon_motors.size()) tendon.motor = tendon_motors[t];
    Named(model, [&] { world.AddTendon(tendon); });
  }
  for (const massprops::RobotCoupling& rc : model.couplings) {
    const std::string what = "coupling '" + rc.name + "'";
    Coupling c;
    c.name = rc.name;
    c.polynomial = rc.polynomial;
    const Coordinate::Kind kind = rc.tendons ? Coordinate::Kind::kTendon : Coordinate::Kind::kJoint;
    auto coordinate = [&](int k) {
      if (k < 0) return Coordinate{kind, -1};
      return Coordinate{kind, rc.tendons ? k : place.Joint(k, what)};
    };
    c.follower = coordinate(rc.follower);
    c.leader = coordinate(rc.leader);
    // The coordinates at the reference configuration (MuJoCo's qpos0: every joint at its ref).
    auto reference_of = [&](int k) {
      return rc.tendons ? lengths[static_cast<std::size_t>(k)] : model.joints[static_cast<std::size_t>(k)].ref;
    };
    c.follower_reference = reference_of(rc.follower);
    if (rc.leader >= 0) c.leader_reference = reference_of(rc.leader);
    Named(model, [&] { world.AddCoupling(c); });
  }
  for (const massprops::RobotLoop& rl : model.loops) {
    Loop loop;
    loop.name = rl.name;
    loop.type = rl.type == massprops::RobotLoop::Type::kBall    ? LoopType::kBall
                : rl.type == massprops::RobotLoop::Type::kWeld  ? LoopType::kWeld
                : rl.type == massprops::RobotLoop::Type::kHinge ? LoopType::kHinge
                                                                : LoopType::kSlider;
    loop.a = place.On(rl.link_a, rl.in_a);
    loop.b = rl.in_b ? place.On(rl.link_b, *rl.in_b) : place.Into(rl.link_b, place.AtReference(loop.a));
    // A file's keyframe may leave a loop open by what its numbers round to: closed by the first step.
    loop.tolerance = 1e-3;
    Named(model, [&] { world.AddLoop(loop); });
  }
}

}  // namespace dynamics::internal
