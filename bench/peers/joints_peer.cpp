// Articulated bodies side by side with MuJoCo 2.2 (Debian's libmujoco-dev): the same arms built
// in libdynamics and written as a URDF that MuJoCo compiles. A comparison tool: never a
// dependency of the libraries.
//
//   joints_peer --check   the 6-link arm (links: the T-handle mesh of data/ at six densities and
//                         attitudes, inertials by massprops) limp under gravity for 1 s at
//                         h = 0.1 ms, MuJoCo's RK4 against libdynamics' implicit midpoint and
//                         RK4: joint angles every millisecond; exit 1 beyond 1e-4 rad
//   joints_peer --bench   steps per second of a 7-DOF arm and a 30-link chain, both engines,
//                         h = 1 ms, medians of three runs, and each one's error after 1 s
//   joints_peer --chains [--ours]  steps per second of 300- and 3000-link chains, both engines (or
//                        ours alone: MuJoCo takes minutes to build the longer one), h = 1 ms
//   joints_peer --urdf    prints the 6-link arm's URDF

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <mujoco/mujoco.h>

#include "dynamics/joints.h"
#include "dynamics/world.h"
#include "massprops/io/mesh_io.h"
#include "massprops/mass_properties.h"
#include "peer_timing.h"

namespace {

using massprops::Matrix3;
using massprops::Vector3;
using peers::Median3;
using peers::StepsPerSecond;

constexpr double kG = 9.81;

/// One link of a serial arm at q = 0: its mass properties in the world and the joint it hangs
/// from (a hinge at `anchor` about `axis`, world).
struct Link {
  double mass;
  Vector3 com;
  Matrix3 inertia;  ///< about the center of mass, world axes
  Vector3 anchor, axis;
  double q0;
};

std::vector<Link> MeshArm(int n) {
  const massprops::LoadedMesh loaded =
      massprops::ReadMeshFile(std::string(MASSPROPS_DATA_DIR) + "/meshes/t_handle.obj");
  const massprops::TriangleMesh mesh = massprops::Triangulate(loaded.mesh);
  const double densities[] = {2700, 7800, 1200, 4500, 2700, 8900, 1900};
  const Vector3 axes[] = {Vector3::UnitX(),
                          Vector3::UnitY(),
                          Vector3(1, 1, 0).normalized(),
                          Vector3::UnitX(),
                          Vector3(0, 1, 1).normalized(),
                          Vector3::UnitY(),
                          Vector3::UnitX()};
  const double q0[] = {0.4, -0.6, 0.8, 0.3, -0.5, 0.7, -0.2};
  std::vector<Link> arm;
  for (int i = 0; i < n; ++i) {
    const massprops::MassProperties mp = massprops::ComputeMassProperties(mesh, densities[i]);
    const Matrix3 R = Eigen::AngleAxisd(0.5 * i, Vector3(1, 2, 3).normalized()).toRotationMatrix();
    Link l;
    l.mass = mp.mass;
    l.anchor = Vector3(0, 0, -0.1 * i);
    l.com = l.anchor + Vector3(0.01 * std::sin(i), 0.01 * std::cos(i), -0.05);
    l.inertia = R * mp.inertia_com * R.transpose();
    l.axis = axes[i];
    l.q0 = q0[i];
    arm.push_back(l);
  }
  return arm;
}

std::vector<Link> BoxChain(int n) {
  std::vector<Link> chain;
  const double m = 0.1, a = 0.01, L = 0.05;
  for (int i = 0; i < n; ++i) {
    Link l;
    l.mass = m;
    l.anchor = Vector3(0, 0, -L * i);
    l.com = l.anchor + Vector3(0, 0, -L / 2);
    l.inertia = (m / 12 * Vector3(a * a + L * L, a * a + L * L, 2 * a * a)).asDiagonal();
    l.axis = i % 2 ? Vector3::UnitX() : Vector3::UnitY();
    l.q0 = 0.3 * std::sin(i);
    chain.push_back(l);
  }
  return chain;
}

dynamics::World Ours(const std::vector<Link>& links, dynamics::Integrator integrator) {
  dynamics::World w(integrator);
  for (const Link& l : links) {
    massprops::MassProperties mp;
    mp.mass = l.mass;
    mp.center_of_mass = l.com;
    mp.inertia_com = l.inertia;
    w.AddBody(dynamics::BodyFromMassProperties(mp).body);
  }
  for (std::size_t i = 0; i < links.size(); ++i) {  // PlaceJoint: at q = 0, whatever the last joint moved
    dynamics::Joint j;
    j.name = "joint" + std::to_string(i + 1);
    j.parent = static_cast<int>(i) - 1;
    j.child = static_cast<int>(i);
    w.PlaceJoint(j, links[i].anchor, links[i].axis);
    j.position = {links[i].q0};
    w.AddJoint(j);
  }
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  return w;
}

std::string V(const Vector3& v) {
  char b[128];
  std::snprintf(b, sizeof b, "%.17g %.17g %.17g", v.x(), v.y(), v.z());
  return b;
}

/// The arm as a URDF: link i's frame at its joint's anchor with the world's axes (at q = 0).
std::string Urdf(const std::vector<Link>& links) {
  std::ostringstream x;
  x.precision(17);
  x << "<?xml version='1.0'?>\n<robot name='arm'>\n"
    << "  <mujoco><compiler discardvisual='true' fusestatic='true'/></mujoco>\n  <link name='base'/>\n";
  for (std::size_t i = 0; i < links.size(); ++i) {
    const Link& l = links[i];
    const Matrix3& I = l.inertia;
    x << "  <link name='link" << i + 1 << "'>\n    <inertial>\n      <origin xyz='" << V(l.com - l.anchor)
      << "' rpy='0 0 0'/>\n      <mass value='" << l.mass << "'/>\n      <inertia ixx='" << I(0, 0) << "' ixy='"
      << I(0, 1) << "' ixz='" << I(0, 2) << "' iyy='" << I(1, 1) << "' iyz='" << I(1, 2) << "' izz='" << I(2, 2)
      << "'/>\n    </inertial>\n  </link>\n";
    const Vector3 origin = l.anchor - (i == 0 ? Vector3::Zero() : links[i - 1].anchor);
    x << "  <joint name='joint" << i + 1 << "' type='continuous'>\n    <parent link='"
      << (i == 0 ? std::string("base") : "link" + std::to_string(i)) << "'/>\n    <child link='link" << i + 1
      << "'/>\n    <origin xyz='" << V(origin) << "' rpy='0 0 0'/>\n    <axis xyz='" << V(l.axis)
      << "'/>\n  </joint>\n";
  }
  x << "</robot>\n";
  return x.str();
}

struct MuJoCo {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  MuJoCo(const std::vector<Link>& links, double h, int integrator) {
    const std::string path = "/tmp/joints_peer_" + std::to_string(::getpid()) + ".urdf";
    std::ofstream(path) << Urdf(links);
    char error[1000] = "";
    m = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
    std::remove(path.c_str());
    if (!m) throw std::runtime_error(std::string("MuJoCo refused the URDF: ") + error);
    if (m->nq != static_cast<int>(links.size()))
      throw std::runtime_error("MuJoCo compiled a different number of joints");
    m->opt.timestep = h;
    m->opt.integrator = integrator;
    m->opt.gravity[0] = 0, m->opt.gravity[1] = 0, m->opt.gravity[2] = -kG;
    m->opt.disableflags |= mjDSBL_CONTACT;
    d = mj_makeData(m);
    for (std::size_t i = 0; i < links.size(); ++i) d->qpos[i] = links[i].q0;
    mj_forward(m, d);
  }
  ~MuJoCo() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
};

int Check() {
  const std::vector<Link> arm = MeshArm(6);
  const double h = 1e-4;
  MuJoCo mj(arm, h, mjINT_RK4);
  dynamics::World mid = Ours(arm, dynamics::Integrator::kImplicitMidpoint);
  dynamics::World rk4 = Ours(arm, dynamics::Integrator::kRK4);
  double worst_mid = 0, worst_rk4 = 0, largest_swing = 0;
  for (int step = 1; step <= 10000; ++step) {
    mj_step(mj.m, mj.d);
    if (!mid.Step(h).ok || !rk4.Step(h).ok) {
      std::cerr << "a step failed\n";
      return 1;
    }
    if (step % 10 != 0) continue;
    for (std::size_t i = 0; i < arm.size(); ++i) {
      const double q = mj.d->qpos[i];
      worst_mid = std::max(worst_mid, std::fabs(mid.joint_state(static_cast<int>(i)).position[0] - q));
      worst_rk4 = std::max(worst_rk4, std::fabs(rk4.joint_state(static_cast<int>(i)).position[0] - q));
      largest_swing = std::max(largest_swing, std::fabs(q - arm[i].q0));
    }
  }
  std::printf("6-link mesh arm, 1 s limp under gravity at h = 0.1 ms (joints swing up to %.3f rad):\n", largest_swing);
  std::printf("  largest |q - q_MuJoCo RK4|: implicit midpoint %.2e rad, RK4 %.2e rad (tolerance 1e-4)\n", worst_mid,
              worst_rk4);
  const bool ok = worst_mid < 1e-4 && worst_rk4 < 1e-4 && largest_swing > 0.1;
  std::printf("%s\n", ok ? "agree" : "DISAGREE");
  return ok ? 0 : 1;
}

/// Joint angles after 1 s, every joint.
std::vector<double> AnglesAfterOneSecond(const std::vector<Link>& links, double h, int engine) {
  const int steps = static_cast<int>(std::lround(1.0 / h));
  std::vector<double> q(links.size());
  if (engine < 2) {
    dynamics::World w = Ours(links, engine == 0 ? dynamics::Integrator::kImplicitMidpoint : dynamics::Integrator::kRK4);
    for (int s = 0; s < steps; ++s) w.Step(h);
    for (std::size_t i = 0; i < q.size(); ++i) q[i] = w.joint_state(static_cast<int>(i)).position[0];
  } else {
    MuJoCo mj(links, h, engine == 2 ? mjINT_EULER : mjINT_RK4);
    for (int s = 0; s < steps; ++s) mj_step(mj.m, mj.d);
    for (std::size_t i = 0; i < q.size(); ++i) q[i] = mj.d->qpos[i];
  }
  return q;
}

int Bench() {
  const double h = 1e-3;
  const int steps = 5000;
  struct Model {
    const char* name;
    std::vector<Link> links;
  } models[] = {{"7-DOF mesh arm", MeshArm(7)}, {"30-link chain", BoxChain(30)}};
  const char* engines[] = {"ours midpoint", "ours RK4", "MuJoCo Euler", "MuJoCo RK4"};
  std::printf(
      "h = 1 ms: steps/s (medians of 3 runs of %d steps) and the largest joint-angle error after 1 s\n"
      "(against MuJoCo's RK4 at h = 10 us)\n",
      steps);
  std::printf("%-16s %-14s %10s %12s\n", "model", "engine", "steps/s", "error, rad");
  for (const Model& model : models) {
    const std::vector<double> reference = AnglesAfterOneSecond(model.links, 1e-5, 3);
    for (int engine = 0; engine < 4; ++engine) {
      const double rate = Median3([&] {
        if (engine < 2) {
          dynamics::World w =
              Ours(model.links, engine == 0 ? dynamics::Integrator::kImplicitMidpoint : dynamics::Integrator::kRK4);
          return StepsPerSecond([&] { w.Step(h); }, steps);
        }
        MuJoCo mj(model.links, h, engine == 2 ? mjINT_EULER : mjINT_RK4);
        return StepsPerSecond([&] { mj_step(mj.m, mj.d); }, steps);
      });
      const std::vector<double> q = AnglesAfterOneSecond(model.links, h, engine);
      double error = 0;
      for (std::size_t i = 0; i < q.size(); ++i) error = std::max(error, std::fabs(q[i] - reference[i]));
      std::printf("%-16s %-14s %10.0f %12.1e\n", model.name, engines[engine], rate, error);
    }
  }
  return 0;
}

// Long chains, limp from a few degrees off straight: our implicit midpoint (M⁻¹ by the O(n)
// articulated-body recursion past 64 hinges) against MuJoCo's Euler (its chain's mass matrix is dense
// too), steps per second from a short run each (a 3000-link step takes seconds to minutes: one
// or two steps), and each world's build.
int Chains(bool ours_only) {
  const double h = 1e-3;
  std::printf("h = 1 ms, limp chains of 5 cm boxes (hinges alternating x and y)\n");
  std::printf("%-16s %14s %14s %10s\n", "model", "ours midpoint", "MuJoCo Euler", "ratio");
  for (const int n : {300, 3000}) {
    const std::vector<Link> links = BoxChain(n);
    auto seconds_since = [](std::chrono::steady_clock::time_point start) {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    auto start = std::chrono::steady_clock::now();
    dynamics::World w = Ours(links, dynamics::Integrator::kImplicitMidpoint);
    const double ours_build = seconds_since(start);
    const double ours = StepsPerSecond([&] { w.Step(h); }, n <= 300 ? 200 : 20);
    if (ours_only) {
      std::printf("%-16s %14.3g %14s %10s   (built in %.2f s)\n", (std::to_string(n) + "-link chain").c_str(), ours,
                  "-", "-", ours_build);
      std::fflush(stdout);
      continue;
    }
    start = std::chrono::steady_clock::now();
    MuJoCo mj(links, h, mjINT_EULER);
    const double theirs_build = seconds_since(start);
    const double theirs = StepsPerSecond([&] { mj_step(mj.m, mj.d); }, n <= 300 ? 200 : 2);
    std::printf("%-16s %14.3g %14.3g %10.3g   (built in %.2f s and %.1f s)\n",
                (std::to_string(n) + "-link chain").c_str(), ours, theirs, theirs / ours, ours_build, theirs_build);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  try {
    if (mode == "--check") return Check();
    if (mode == "--bench") return Bench();
    if (mode == "--chains") return Chains(argc > 2 && std::string(argv[2]) == "--ours");
    if (mode == "--urdf") {
      std::cout << Urdf(MeshArm(6));
      return 0;
    }
  } catch (const std::exception& e) {
    std::cerr << "joints_peer: " << e.what() << "\n";
    return 1;
  }
  std::cerr << "usage: joints_peer --check | --bench | --chains [--ours] | --urdf\n";
  return 2;
}
