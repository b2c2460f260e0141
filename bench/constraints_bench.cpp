// Loops and couplings at speed (issue 68): steps per second of a parallelogram four-bar closed by a
// ball loop beside the same three links as an open chain (the loop's cost), a mimic gripper, and the
// field humanoid (tests/robot/field/mjcf/humanoid.xml) falling onto the ground with its arms coupled
// left to right by four couplings beside the same model uncoupled — baselines in the same run, so
// the ratios hold on any machine. items_per_second = steps/s.

#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "bodies/robot.h"
#include "dynamics/contact.h"
#include "dynamics/world.h"
#include "massprops/robot/robot_model.h"

namespace {

using dynamics::Vector3;

dynamics::RigidBody Box(double m, double a, double b, double c, const Vector3& at) {
  dynamics::RigidBody body;
  body.mass = m;
  body.inertia = Vector3(b * b + c * c, a * a + c * c, a * a + b * b) * (m / 12.0);
  body.position = at;
  return body;
}

dynamics::Joint Hinge(const dynamics::World& w, int parent, int child, const Vector3& anchor, double q) {
  dynamics::Joint j;
  j.name = "j" + std::to_string(child);
  j.parent = parent;
  j.child = child;
  j.position = {q};
  w.PlaceJoint(j, anchor, Vector3::UnitY());
  return j;
}

// range(0): 1 closes the loop, 0 leaves the chain open.
void BM_FourBar(benchmark::State& state) {
  dynamics::World w;
  const double q0 = M_PI / 3;
  const int c1 = w.AddBody(Box(1, 0.05, 0.05, 1, Vector3(0, 0, -0.5)));
  const int c2 = w.AddBody(Box(1, 0.05, 0.05, 1, Vector3(0.8, 0, -0.5)));
  const int cp = w.AddBody(Box(0.6, 0.8, 0.05, 0.05, Vector3(0.4, 0, -1)));
  w.AddJoint(Hinge(w, -1, c1, Vector3(0, 0, 0), q0));
  w.AddJoint(Hinge(w, -1, c2, Vector3(0.8, 0, 0), q0));
  w.AddJoint(Hinge(w, c1, cp, Vector3(0, 0, -1), -q0));
  if (state.range(0)) {
    dynamics::Loop loop;
    loop.a = {cp, {Vector3(0.4, 0, 0), dynamics::Quaternion::Identity()}};
    loop.b = {c2, {Vector3(0, 0, -0.5), dynamics::Quaternion::Identity()}};
    w.AddLoop(loop);
  }
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -9.81)));
  w.Step(1e-3);
  for (auto _ : state) {
    if (!w.Step(1e-3).ok) state.SkipWithError("step failed");
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(state.range(0) ? "closed by a ball loop" : "open chain");
}
BENCHMARK(BM_FourBar)->Arg(0)->Arg(1)->UseRealTime();

const std::string kField = std::string(MASSPROPS_DATA_DIR) + "/../tests/robot/field/";

// The mimic gripper holding a box (couplings, contact and a motor in one solve).
void BM_MimicGripper(benchmark::State& state) {
  const massprops::RobotModel model = massprops::ReadRobotModel(kField + "constraints/gripper.urdf");
  dynamics::World w;
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -9.81)));
  dynamics::ContactWorld world(std::move(w));
  dynamics::RobotOptions options;
  options.motors["left_finger_joint"] = {dynamics::JointMotor::Mode::kVelocity, 0.05, 20, 0, 0, 0};
  options.positions = {{"left_finger_joint", 0.039}, {"right_finger_joint", 0.039}};
  dynamics::AddRobot(world, model, options);
  world.AddBody(Box(0.2, 0.06, 0.06, 0.06, Vector3(0, 0, 0.25)),
                dynamics::Collider{dynamics::shape::Box{Vector3::Constant(0.03)}, dynamics::Matrix3::Identity(),
                                   Vector3::Zero(), dynamics::Material{}});
  for (int s = 0; s < 100; ++s) world.Step(1e-3);  // gripped
  for (auto _ : state) {
    if (!world.Step(1e-3).ok) state.SkipWithError("step failed");
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MimicGripper)->UseRealTime();

// range(0): 1 couples the arms (left = right at shoulders, elbow and wrist), 0 leaves them free.
void BM_HumanoidArms(benchmark::State& state) {
  massprops::RobotModel model = massprops::ReadRobotModel(kField + "mjcf/humanoid.xml");
  if (state.range(0)) {
    for (const char* joint : {"shoulder_?_x", "shoulder_?_y", "elbow_?", "wrist_?"}) {
      massprops::RobotCoupling c;
      std::string left = joint, right = joint;
      left.replace(left.find('?'), 1, "left");
      right.replace(right.find('?'), 1, "right");
      for (std::size_t k = 0; k < model.joints.size(); ++k) {
        if (model.joints[k].name == left) c.follower = static_cast<int>(k);
        if (model.joints[k].name == right) c.leader = static_cast<int>(k);
      }
      c.name = left;
      model.couplings.push_back(c);
    }
  }
  dynamics::World w;
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -9.81)));
  dynamics::ContactWorld world(std::move(w));
  world.AddGround({});
  dynamics::RobotOptions options;
  options.pose = dynamics::PlaceAboveGround(model, options, {dynamics::Ground{}}, dynamics::kSetDownClearance);
  dynamics::AddRobot(world, model, options);
  long steps = 0;
  for (auto _ : state) {
    if (!world.Step(1e-3).ok) state.SkipWithError("step failed");
    if (++steps == 2000) {  // the fall and the first second on the ground, again and again
      state.PauseTiming();
      world = dynamics::ContactWorld(dynamics::World());
      dynamics::World again;
      again.AddForce(dynamics::Gravity(Vector3(0, 0, -9.81)));
      world = dynamics::ContactWorld(std::move(again));
      world.AddGround({});
      dynamics::AddRobot(world, model, options);
      steps = 0;
      state.ResumeTiming();
    }
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(state.range(0) ? "arms coupled (4 couplings)" : "uncoupled");
}
BENCHMARK(BM_HumanoidArms)->Arg(0)->Arg(1)->UseRealTime()->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
