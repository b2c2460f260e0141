// Robots in contact side by side with MuJoCo 2.2 (Debian's libmujoco-dev): one MJCF file read by
// both engines — ours through massprops::ReadRobotModel and dynamics::AddRobot, MuJoCo through
// mj_loadXML with a floor (or a table) written beside it. A comparison tool: never a dependency
// of the libraries.
//
//   robot_peer --check   the example quadruped (data/robots/quadruped/quadruped.xml) dropped limp
//                        onto the ground from 5 cm: its resting base height, knee angle and the
//                        time it takes to come to rest in each engine; exit 1 when either does
//                        not rest within 3 s, the heights differ by more than 1.5 cm (MuJoCo's
//                        soft stops let its knees sink past their limit) or our knees leave
//                        their stops
//   robot_peer --bench   steps per second (h = 1 ms, medians of three runs) of the quadruped
//                        settling on the ground and of a 7-DOF arm draped over a table, ours
//                        against MuJoCo's Euler
//   robot_peer --ours quadruped|arm STEPS [--reuse-distance D]
//                        ours alone (for a profiler): steps per second and sweeps a step
//   robot_peer --bench --file FILE.xml
//                        any MJCF file as it is (its floor, its placement), limp: steps per second
//                        over 3 s of falling and resting in each engine, when each comes to rest
//                        and where it rests the root
//   robot_peer --joints FILE.xml KEY SECONDS TOL
//                        any MJCF file as it is, from its keyframe KEY ('' for none): every
//                        hinge's and slide's angle and rate after SECONDS in both engines, and
//                        each free root's center of mass; exit 1 when an angle or rate differs by more than
//                        TOL or a free root's center of mass by more than 1 cm

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

#include <unistd.h>

#include <mujoco/mujoco.h>

#include "bodies/robot.h"
#include "dynamics/contact.h"
#include "massprops/robot/robot_model.h"
#include "peer_timing.h"

namespace {

using massprops::Vector3;

const std::string kQuadruped = std::string(MASSPROPS_DATA_DIR) + "/robots/quadruped/quadruped.xml";
constexpr double kDrop = 0.05;  // m: the feet's height above the ground at the start

/// A model both engines read: the MJCF text, and what stands beside the robot.
struct Setup {
  std::string path;                         ///< the MJCF file (ours reads it)
  std::string mujoco_path;                  ///< with the floor or table MuJoCo needs in its own file
  bool ground = true;                       ///< else a table
  double base_z = 0;                        ///< the root body's height at the start
  std::map<std::string, double> positions;  ///< initial joint positions
  bool file_floor = false;                  ///< the file brings its floor and places the robot
  std::string keyframe;                     ///< the file's keyframe to start from ("": none)
  double reuse_distance = -1;               ///< ours: ContactOptions::reuse_distance (< 0: the default)
};

std::string Slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("robot_peer: '" + from + "' not in the model");
  return text.replace(at, from.size(), to);
}

// The table: its top at z = 0.3 m under x in [0.05, 0.65] m.
const Vector3 kTableCentre(0.35, 0, 0.15), kTableHalf(0.3, 0.3, 0.15);

/// The quadruped, its feet 5 cm above the ground.
Setup Quadruped() {
  Setup s;
  s.path = kQuadruped;
  // Knees a little bent (straight legs would balance, unstably, for a while): the feet 0.4 cos 0.3
  // below the hips.
  for (const char* leg : {"front_left", "front_right", "rear_left", "rear_right"}) {
    s.positions[std::string(leg) + "_hip"] = 0.3;
    s.positions[std::string(leg) + "_knee"] = -0.6;
  }
  s.base_z = 0.4 * std::cos(0.3) + kDrop;
  std::string text = Slurp(kQuadruped);
  const std::string dir = std::string(MASSPROPS_DATA_DIR) + "/robots/quadruped/";
  text = Replace(text, "<compiler angle=\"radian\"/>",
                 "<compiler angle=\"radian\" meshdir=\"" + dir +
                     "\"/>\n  <option timestep=\"0.001\"/>\n"
                     "  <default><geom friction=\"0.6 0.005 0.0001\"/></default>");
  text = Replace(text, "<worldbody>", "<worldbody>\n    <geom name=\"floor\" type=\"plane\" size=\"5 5 0.1\"/>");
  s.mujoco_path = "/tmp/robot_peer_quadruped_" + std::to_string(::getpid()) + ".xml";
  std::ofstream(s.mujoco_path) << text;
  return s;
}

/// A 7-DOF arm of 0.1 m box links reaching along +x from a base 0.5 m up, hinges about z, y, x,
/// y, x, y, x with a little damping: limp, it falls onto the table and drapes over it.
Setup Arm() {
  std::ostringstream x;
  x << "<mujoco model=\"arm\">\n  <compiler angle=\"radian\"/>\n  <worldbody>\n";
  const char* axes[] = {"0 0 1", "0 1 0", "1 0 0", "0 1 0", "1 0 0", "0 1 0", "1 0 0"};
  std::string close;
  for (int i = 0; i < 7; ++i) {
    x << std::string(4 + 2 * i, ' ') << "<body name=\"link" << i + 1 << "\" pos=\"" << (i == 0 ? "0 0 0.5" : "0.1 0 0")
      << "\">\n"
      << std::string(6 + 2 * i, ' ') << "<joint name=\"j" << i + 1 << "\" type=\"hinge\" axis=\"" << axes[i]
      << "\" damping=\"0.05\"/>\n"
      << std::string(6 + 2 * i, ' ')
      << "<inertial pos=\"0.05 0 0\" mass=\"0.5\" diaginertia=\"0.0001333 0.0004833 0.0004833\"/>\n"
      << std::string(6 + 2 * i, ' ') << "<geom type=\"box\" pos=\"0.05 0 0\" size=\"0.05 0.02 0.02\"/>\n";
    close = std::string(4 + 2 * i, ' ') + "</body>\n" + close;
  }
  x << close << "  </worldbody>\n</mujoco>\n";
  Setup s;
  s.ground = false;
  s.path = "/tmp/robot_peer_arm_" + std::to_string(::getpid()) + ".xml";
  std::ofstream(s.path) << x.str();
  std::string text =
      Replace(x.str(), "<worldbody>",
              "<option timestep=\"0.001\"/>\n  <default><geom friction=\"0.6 0.005 0.0001\"/></default>\n"
              "  <worldbody>\n    <geom name=\"table\" type=\"box\" pos=\"0.35 0 0.15\" size=\"0.3 0.3 0.15\"/>");
  s.mujoco_path = "/tmp/robot_peer_arm_mj_" + std::to_string(::getpid()) + ".xml";
  std::ofstream(s.mujoco_path) << text;
  return s;
}

/// Any MJCF file as it is, with its own floor, placed where it places itself (or its keyframe).
Setup FromFile(const std::string& path, const std::string& keyframe = "") {
  Setup s;
  s.path = s.mujoco_path = path;
  s.file_floor = true;
  s.keyframe = keyframe;
  return s;
}

struct Ours {
  dynamics::ContactWorld world;
  massprops::RobotModel model;
  dynamics::RobotInWorld added;
  int base = 0;
  explicit Ours(const Setup& s) {
    dynamics::World w(dynamics::Integrator::kImplicitMidpoint);
    w.AddForce(dynamics::Gravity(Vector3(0, 0, -9.81)));
    dynamics::ContactOptions contact;
    if (s.reuse_distance >= 0) contact.reuse_distance = s.reuse_distance;
    world = dynamics::ContactWorld(std::move(w), contact);
    model = massprops::ReadRobotModel(s.path);
    if (s.file_floor) {
      for (const massprops::RobotGround& g : model.grounds) {
        world.AddGround(dynamics::GroundOf(g));
      }
      for (const massprops::RobotTerrain& t : model.terrains) {
        world.AddStatic(dynamics::TerrainCollider(t), t.pose.rotation, t.pose.translation);
      }
    } else if (s.ground) {
      world.AddGround({});
    } else {
      world.AddStatic({dynamics::shape::Box{kTableHalf}, massprops::Matrix3::Identity(), Vector3::Zero(), {}},
                      massprops::Matrix3::Identity(), kTableCentre);
    }
    dynamics::RobotOptions options;
    if (!s.file_floor) {  // MuJoCo's qpos puts the free root at base_z; our pose moves the file's world
      options.pose.translation = Vector3(0, 0, s.base_z);
      for (const massprops::RobotJoint& j : model.joints) {
        if (j.parent < 0 && j.type == massprops::RobotJointType::kFloating) {
          options.pose.translation -= j.parent_to_joint.translation;
        }
      }
    }
    options.positions = s.positions;
    options.keyframe = s.keyframe;
    added = dynamics::AddRobot(world, model, options);
    base = added.bodies.front();
  }
  void Step() {
    const dynamics::StepStatus st = world.Step(1e-3);
    if (!st.ok) throw std::runtime_error("ours: " + st.message);
  }
  double BaseZ() const { return world.world().bodies()[static_cast<std::size_t>(base)].position.z(); }
  double Fastest() const {
    double v = 0;
    for (const dynamics::RigidBody& b : world.world().bodies()) v = std::max(v, b.velocity.norm());
    return v;
  }
};

struct MuJoCo {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  int base = 1;
  explicit MuJoCo(const Setup& s) {
    char error[1000] = "";
    m = mj_loadXML(s.mujoco_path.c_str(), nullptr, error, sizeof error);
    if (!m) throw std::runtime_error(std::string("MuJoCo refused the model: ") + error);
    d = mj_makeData(m);
    if (s.ground && !s.file_floor) d->qpos[2] = s.base_z;  // the free joint's position
    if (!s.keyframe.empty()) {
      const int key = mj_name2id(m, mjOBJ_KEY, s.keyframe.c_str());
      if (key < 0) throw std::runtime_error("MuJoCo's model has no keyframe '" + s.keyframe + "'");
      mj_resetDataKeyframe(m, d, key);
    }
    for (const auto& [name, q] : s.positions) {
      const int j = mj_name2id(m, mjOBJ_JOINT, name.c_str());
      if (j < 0) throw std::runtime_error("MuJoCo's model has no joint '" + name + "'");
      d->qpos[m->jnt_qposadr[j]] = q;
    }
    mj_forward(m, d);
  }
  ~MuJoCo() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  void Step() { mj_step(m, d); }
  double BaseZ() const { return d->xipos[3 * base + 2]; }  // the base's center of mass
  double Fastest() const {
    double v = 0;
    for (int b = 1; b < m->nbody; ++b) {
      mjtNum vel[6];
      mj_objectVelocity(m, d, mjOBJ_BODY, b, vel, 0);
      v = std::max(v, std::sqrt(vel[3] * vel[3] + vel[4] * vel[4] + vel[5] * vel[5]));
    }
    return v;
  }
};

/// Steps for `seconds`: the time after which every body stays slower than 1 mm/s (-1: never),
/// and the base's height at the end.
template <typename Engine>
std::pair<double, double> Settle(Engine& e, double seconds) {
  double rest = -1;
  const int steps = static_cast<int>(std::lround(seconds / 1e-3));
  for (int s = 1; s <= steps; ++s) {
    e.Step();
    if (e.Fastest() < 1e-3) {
      if (rest < 0) rest = s * 1e-3;
    } else {
      rest = -1;
    }
  }
  return {rest, e.BaseZ()};
}

// The front left knee's angle at the end (its stop is at -2.4 rad).
double Knee(const Ours& o) {
  const auto& joints = o.world.world().joints();
  for (std::size_t k = 0; k < joints.size(); ++k) {
    if (joints[k].name == "front_left_knee") return o.world.world().joint_state(static_cast<int>(k)).position[0];
  }
  throw std::runtime_error("ours has no front_left_knee");
}
double Knee(const MuJoCo& mj) {
  return mj.d->qpos[mj.m->jnt_qposadr[mj_name2id(mj.m, mjOBJ_JOINT, "front_left_knee")]];
}

int Check() {
  const Setup q = Quadruped();
  Ours ours(q);
  MuJoCo mj(q);
  const auto [ours_rest, ours_z] = Settle(ours, 3.0);
  const auto [mj_rest, mj_z] = Settle(mj, 3.0);
  std::remove(q.mujoco_path.c_str());
  std::printf("the example quadruped dropped limp from %.0f cm onto the ground (h = 1 ms):\n", kDrop * 100);
  std::printf("  %-26s %14s %22s %14s\n", "engine", "at rest after", "resting base height", "knee (stop -2.4)");
  auto row = [](const char* name, double rest, double z, double knee) {
    char when[32];
    if (rest < 0) {
      std::snprintf(when, sizeof when, "not in 3 s");
    } else {
      std::snprintf(when, sizeof when, "%.3f s", rest);
    }
    std::printf("  %-26s %14s %20.4f m %12.4f rad\n", name, when, z, knee);
  };
  row("ours (implicit midpoint)", ours_rest, ours_z, Knee(ours));
  row("MuJoCo 2.2 (Euler)", mj_rest, mj_z, Knee(mj));
  // Both fold onto their knee stops; MuJoCo's stops are soft (its knees rest past them), which
  // lowers its body by about a centimetre.
  const bool ok =
      ours_rest > 0 && mj_rest > 0 && std::fabs(ours_z - mj_z) < 0.015 && std::fabs(Knee(ours) + 2.4) < 1e-3;
  std::printf("%s\n",
              ok ? "agree (both at rest, heights within 1.5 cm, our knees on their stops within 1 mrad)" : "DISAGREE");
  return ok ? 0 : 1;
}

template <typename Engine>
double StepsPerSecond(const Setup& s, int steps) {
  return peers::Median3([&] {
    Engine e(s);
    return peers::StepsPerSecond([&] { e.Step(); }, steps);
  });
}

// Our solver's sweeps a step, averaged over `steps` steps from the start (the iterations the
// contact solve used: what a block solve of a tree's contacts would cut).
double MeanSweeps(const Setup& s, int steps) {
  Ours o(s);
  long total = 0;
  for (int k = 0; k < steps; ++k) {
    o.Step();
    total += o.world.stats().iterations;
  }
  return static_cast<double>(total) / steps;
}

// Steps per second of one MJCF file as it is (its floor, its placement), limp, falling and coming
// to rest: the first and the last of `seconds`, and where each engine rests it.
int BenchFile(const std::string& path, double seconds) {
  const Setup s = FromFile(path);
  const int steps = static_cast<int>(std::lround(seconds / 1e-3));
  Ours ours(s);
  MuJoCo mj(s);
  const auto [ours_rest, ours_z] = Settle(ours, seconds);
  const auto [mj_rest, mj_z] = Settle(mj, seconds);
  std::printf("%s: %d bodies in MuJoCo, limp, h = 1 ms for %g s\n", path.c_str(), mj.m->nbody - 1, seconds);
  std::printf(
      "  at rest after: ours %.3f s, MuJoCo %.3f s (-1: not at rest); root's center of mass at the end: "
      "ours %.4f m, MuJoCo %.4f m\n",
      ours_rest, mj_rest, ours_z, mj_z);
  const double o = StepsPerSecond<Ours>(s, steps), m = StepsPerSecond<MuJoCo>(s, steps);
  std::printf(
      "  steps/s (medians of 3 runs of %d steps, the fall and the rest): ours %.0f, MuJoCo Euler %.0f, "
      "MuJoCo / ours %.2f\n",
      steps, o, m, m / o);
  return 0;
}

// Ours alone, for a profiler: the quadruped's or the arm's `steps` steps, three times
// (`reuse_distance` ≥ 0: ContactOptions::reuse_distance, for a before and after in one build).
int OursOnly(const std::string& model, int steps, double reuse_distance) {
  if (model != "quadruped" && model != "arm") throw std::runtime_error("--ours: quadruped or arm");
  Setup s = model == "quadruped" ? Quadruped() : Arm();
  s.reuse_distance = reuse_distance;
  const double rate = StepsPerSecond<Ours>(s, steps);
  std::printf("%s: %.0f steps/s (ours), %.1f sweeps a step\n", model.c_str(), rate, MeanSweeps(s, steps));
  for (const std::string& p : {s.path, s.mujoco_path}) {
    if (p != kQuadruped) std::remove(p.c_str());
  }
  return 0;
}

int Bench() {
  const Setup q = Quadruped(), a = Arm();
  std::printf("h = 1 ms, steps/s (medians of 3 runs of 3000 steps: the fall, the landing and rest)\n");
  std::printf("%-34s %12s %14s %8s %16s\n", "model", "ours", "MuJoCo Euler", "ratio", "our sweeps/step");
  for (const auto& [name, setup] : {std::pair<const char*, const Setup*>{"quadruped on the ground (14 dof)", &q},
                                    std::pair<const char*, const Setup*>{"7-DOF arm draped over a table", &a}}) {
    const double ours = StepsPerSecond<Ours>(*setup, 3000), mj = StepsPerSecond<MuJoCo>(*setup, 3000);
    std::printf("%-34s %12.0f %14.0f %8.2f %16.1f\n", name, ours, mj, mj / ours, MeanSweeps(*setup, 3000));
  }
  for (const std::string& p : {q.mujoco_path, a.path, a.mujoco_path}) std::remove(p.c_str());
  return 0;
}

// Any MJCF file read as it is by both engines (its own floor, if any: no other is added), from the
// keyframe named (or the file's q = 0, ctrl = 0): every hinge's and slide's angle and rate after
// `seconds`, ours (implicit midpoint, 1 ms) beside MuJoCo's (Euler at 0.1 ms: its actuators' gains
// are explicit there). A settled state does not depend on the integrator: they must agree within
// `tolerance` (rad, rad/s) for every joint.
int Joints(const std::string& path, const std::string& keyframe, double seconds, double tolerance) {
  Ours o(FromFile(path, keyframe));
  MuJoCo mj(FromFile(path, keyframe));
  const massprops::RobotModel& model = o.model;
  const dynamics::RobotInWorld& added = o.added;
  const dynamics::ContactWorld& ours = o.world;
  mjModel* m = mj.m;
  mjData* d = mj.d;
  m->opt.timestep = 1e-4;
  const long steps = std::lround(seconds / 1e-3);
  for (long s = 0; s < steps; ++s) o.Step();
  for (long s = 0; s < 10 * steps; ++s) mj.Step();
  std::printf("%s%s%s after %g s: each joint, ours (implicit midpoint, 1 ms) and MuJoCo 2.2 (Euler, 0.1 ms)\n",
              path.c_str(), keyframe.empty() ? "" : ", keyframe ", keyframe.c_str(), seconds);
  std::printf("  %-14s %14s %14s %14s %14s\n", "joint", "q ours", "q MuJoCo", "rate ours", "rate MuJoCo");
  double worst = 0;
  for (std::size_t k = 0; k < model.joints.size(); ++k) {
    const massprops::RobotJoint& j = model.joints[k];
    const bool one = j.type == massprops::RobotJointType::kRevolute ||
                     j.type == massprops::RobotJointType::kContinuous ||
                     j.type == massprops::RobotJointType::kPrismatic;
    if (!one || added.joint_of[k] < 0) continue;
    const int id = mj_name2id(m, mjOBJ_JOINT, j.name.c_str());
    if (id < 0) throw std::runtime_error("MuJoCo's model has no joint '" + j.name + "'");
    const dynamics::JointState st = ours.world().joint_state(added.joint_of[k]);
    const double q = d->qpos[m->jnt_qposadr[id]], v = d->qvel[m->jnt_dofadr[id]];
    std::printf("  %-14s %14.6f %14.6f %14.6f %14.6f\n", j.name.c_str(), st.position[0], q, st.velocity[0], v);
    worst = std::max({worst, std::abs(st.position[0] - q), std::abs(st.velocity[0] - v)});
  }
  // Each free root's center of mass: within 1 cm (MuJoCo's soft contacts sink a few millimetres).
  bool height_ok = true;
  for (const massprops::RobotJoint& j : model.joints) {
    if (j.type != massprops::RobotJointType::kFloating || j.parent >= 0) continue;
    const std::string& name = model.links[static_cast<std::size_t>(j.child)].name;
    const int id = mj_name2id(m, mjOBJ_BODY, name.c_str());
    if (id < 0) throw std::runtime_error("MuJoCo's model has no body '" + name + "'");
    const int body = added.body_of_link[static_cast<std::size_t>(j.child)];
    const Vector3 p = ours.world().bodies()[static_cast<std::size_t>(body)].position;
    const Vector3 q(d->xipos[3 * id], d->xipos[3 * id + 1], d->xipos[3 * id + 2]);
    const bool ok = (p - q).norm() < 0.01;
    height_ok = height_ok && ok;
    std::printf("  %-14s (%.4f, %.4f, %.4f) (%.4f, %.4f, %.4f)   (center of mass, m; within 1 cm: %s)\n", name.c_str(),
                p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), ok ? "yes" : "NO");
  }
  // Loops, couplings and tendon ranges: ours held exactly, MuJoCo's soft (its residual is the
  // scale of the agreement to expect).
  const dynamics::World& world = ours.world();
  double held = 0, soft = 0;
  for (std::size_t k = 0; k < world.loops().size(); ++k)
    held = std::max(held, std::abs(world.loop_state(static_cast<int>(k)).residual));
  for (std::size_t k = 0; k < world.couplings().size(); ++k)
    held = std::max(held, std::abs(world.coupling_state(static_cast<int>(k)).residual));
  for (std::size_t k = 0; k < world.tendons().size(); ++k)
    held = std::max(held, std::abs(world.tendon_state(static_cast<int>(k)).residual));
  for (int i = 0; i < d->nefc; ++i) {
    if (d->efc_type[i] == mjCNSTR_EQUALITY || (d->efc_type[i] == mjCNSTR_LIMIT_TENDON && d->efc_pos[i] < 0))
      soft = std::max(soft, std::abs(d->efc_pos[i]));
  }
  if (!world.loops().empty() || !world.couplings().empty() || !world.tendons().empty())
    std::printf("  loops, couplings and tendon ranges: largest residual ours %.2e, MuJoCo %.2e\n", held, soft);
  const bool ok = worst <= tolerance && height_ok;
  std::printf("%s: largest difference %.2e (tolerance %.2e)\n", ok ? "agree" : "DISAGREE", worst, tolerance);
  return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  try {
    if (mode == "--check") return Check();
    if (mode == "--bench" && argc == 2) return Bench();
    if (mode == "--ours" && argc == 4) return OursOnly(argv[2], std::stoi(argv[3]), -1);
    if (mode == "--ours" && argc == 6 && std::string(argv[4]) == "--reuse-distance") {
      return OursOnly(argv[2], std::stoi(argv[3]), std::stod(argv[5]));
    }
    if (mode == "--bench" && argc == 4 && std::string(argv[2]) == "--file") return BenchFile(argv[3], 3.0);
    if (mode == "--joints" && argc == 6) return Joints(argv[2], argv[3], std::stod(argv[4]), std::stod(argv[5]));
  } catch (const std::exception& e) {
    std::cerr << "robot_peer: " << e.what() << "\n";
    return 1;
  }
  std::cerr << "usage: robot_peer --check | --bench [--file FILE.xml]\n"
               "     | --ours quadruped|arm STEPS [--reuse-distance D]\n"
               "     | --joints FILE.xml KEYFRAME|'' SECONDS TOLERANCE\n";
  return 2;
}
