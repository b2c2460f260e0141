// An rbsim scene in MuJoCo (Debian's libmujoco-dev 2.2): the bodies as free bodies with their own
// mass and inertia, their solids as geoms, ground planes as plane geoms, gravity; MuJoCo's
// defaults otherwise (Euler integrator, pyramidal friction cones, soft contacts). Writes rbsim's
// trajectory CSV and one line of timing. A comparison tool: never a dependency of the libraries.
//
//   mujoco_peer SCENE.json [--dt S] [--out trajectory.csv]
//
// Materials (README "Peers"): MuJoCo has one friction coefficient per geom and takes the larger of
// the two geoms'; a body's geom gets the kinetic coefficient of its contact with the ground (or
// the first static body) as rbsim combines it (bodies of one material meet each other with their
// own), the planes and static geoms 0.
// MuJoCo has no restitution coefficient: a contact is a damped spring whose damping ratio ζ gives
// a bounce e = exp(−πζ/√(1−ζ²)), so ζ = −ln e / √(π² + ln² e) (e = 0: ζ = 1, critical), with
// MuJoCo's default time constant 0.02 s (solref="0.02 ζ"). e = 1 (ζ = 0) has no time constant
// (MuJoCo 2.2 refuses "0.02 0" at every step and substitutes critical damping): it is given in
// solref's direct form, "−stiffness −damping", an undamped spring of natural frequency π/(10 h)
// (a contact lasting ten steps) with a damping of 10⁻¹² (the form needs both numbers negative).
// MuJoCo's warnings go to stderr, not to a MUJOCO_LOG.TXT in the working directory.
// Static bodies: boxes as box geoms, hulls as mesh geoms, of the world body.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <unistd.h>

#include <mujoco/mujoco.h>

#include "peer_scene.h"

namespace {

using peers::PeerBody;
using peers::Vector3;

double DampingRatio(double e) {
  if (e <= 0) return 1.0;
  const double l = std::log(e);
  return -l / std::sqrt(massprops::kPi * massprops::kPi + l * l);
}

// solref for a restitution e at step h (above).
std::string Solref(double e, double h) {
  const double zeta = DampingRatio(e);
  std::ostringstream x;
  x.precision(17);
  if (zeta > 0) {
    x << "0.02 " << zeta;
  } else {
    const double omega = massprops::kPi / (10 * h);
    x << -omega * omega << " -1e-12";
  }
  return x.str();
}

void WarnOnStderr(const char* message) { std::cerr << "MuJoCo warning: " << message << "\n"; }

std::string V(const Vector3& v) {
  char b[128];
  std::snprintf(b, sizeof b, "%.17g %.17g %.17g", v.x(), v.y(), v.z());
  return b;
}

// Constraint rows: MuJoCo 2.2 keeps a dense njmax × njmax matrix (efc_AR), so rows cost memory
// quadratically: 40 a body for small scenes, 12 a body (3 pyramidal contacts) for large ones;
// MuJoCo warns when it runs out (printed below).
std::size_t Rows(std::size_t bodies) { return bodies <= 256 ? 40 * bodies + 64 : 12 * bodies; }

std::string Mjcf(const peers::PeerScene& s) {
  std::ostringstream x;
  x.precision(17);
  x << "<mujoco model='rbsim'>\n  <option timestep='" << s.dt << "' gravity='" << V(s.gravity) << "'/>\n";
  x << "  <asset>\n";  // hulls as meshes (MuJoCo collides a mesh as its convex hull)
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    if (s.bodies[i].kind != PeerBody::Kind::kHull) continue;
    x << "    <mesh name='hull" << i << "' vertex='";
    for (const Vector3& v : s.bodies[i].hull) x << V(v) << " ";
    x << "'/>\n";
  }
  for (std::size_t i = 0; i < s.statics.size(); ++i) {
    if (s.statics[i].box) continue;
    x << "    <mesh name='static" << i << "' vertex='";
    for (const Vector3& v : s.statics[i].hull) x << V(v) << " ";
    x << "'/>\n";
  }
  x << "  </asset>\n"
    << "  <size njmax='" << Rows(s.bodies.size()) << "' nconmax='" << Rows(s.bodies.size()) / 4 << "'/>\n"
    << "  <worldbody>\n";
  const dynamics::Material ground = !s.grounds.empty()   ? s.grounds[0].material
                                    : !s.statics.empty() ? s.statics[0].material
                                                         : dynamics::Material{};
  for (const scene::GroundSpec& g : s.grounds) {
    x << "    <geom type='plane' size='0 0 1' pos='" << V(g.normal * g.offset) << "' zaxis='" << V(g.normal)
      << "' friction='0 0.005 0.0001' solref='" << Solref(g.material.restitution, s.dt) << "'/>\n";
  }
  // Static bodies carry no friction of their own either (the moving geom's is the pair's).
  for (std::size_t i = 0; i < s.statics.size(); ++i) {
    const peers::PeerStatic& st = s.statics[i];
    const Eigen::Quaterniond& q = st.orientation;
    x << "    <geom ";
    if (st.box) {
      x << "type='box' size='" << V(st.half_extents) << "' pos='" << V(st.position) << "' quat='" << q.w() << " "
        << q.x() << " " << q.y() << " " << q.z() << "'";
    } else {
      x << "type='mesh' mesh='static" << i << "'";
    }
    x << " friction='0 0.005 0.0001' solref='" << Solref(st.material.restitution, s.dt) << "'/>\n";
  }
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const PeerBody& b = s.bodies[i];
    const Eigen::Quaterniond& q = b.orientation;
    const dynamics::Material m = dynamics::CombineMaterials(b.material, ground);
    x << "    <body name='" << b.name << "' pos='" << V(b.position) << "' quat='" << q.w() << " " << q.x() << " "
      << q.y() << " " << q.z() << "'>\n      <freejoint/>\n      <inertial pos='0 0 0' mass='" << b.mass
      << "' diaginertia='" << V(b.inertia) << "'/>\n      <geom ";
    switch (b.kind) {
      case PeerBody::Kind::kBox: x << "type='box' size='" << V(b.half_extents) << "'"; break;
      case PeerBody::Kind::kSphere: x << "type='sphere' size='" << b.radius << "'"; break;
      case PeerBody::Kind::kCapsule: x << "type='capsule' size='" << b.radius << " " << b.half_length << "'"; break;
      case PeerBody::Kind::kCylinder: x << "type='cylinder' size='" << b.radius << " " << b.half_length << "'"; break;
      case PeerBody::Kind::kHull: x << "type='mesh' mesh='hull" << i << "'"; break;
    }
    x << " friction='" << m.kinetic_friction << " 0.005 0.0001' solref='" << Solref(m.restitution, s.dt)
      << "'/>\n    </body>\n";
  }
  x << "  </worldbody>\n</mujoco>\n";
  return x.str();
}

}  // namespace

int main(int argc, char** argv) {
  peers::PeerArgs args;
  peers::PeerScene scene;
  if (const int status = peers::StartPeer(argc, argv, "mujoco_peer", args, scene); status >= 0) return status;
  mju_user_warning = WarnOnStderr;
  const std::string xml_path =
      (std::filesystem::temp_directory_path() / ("mujoco_peer_" + std::to_string(::getpid()) + ".xml")).string();
  std::ofstream(xml_path) << Mjcf(scene);
  char error[1000] = "";
  mjModel* m = mj_loadXML(xml_path.c_str(), nullptr, error, sizeof error);
  std::filesystem::remove(xml_path);
  if (m == nullptr) {
    std::cerr << "error: MuJoCo refused the model: " << error << "\n";
    return 1;
  }
  mjData* d = mj_makeData(m);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {  // qvel of a free joint: v (world), ω (body axes)
    const PeerBody& b = scene.bodies[i];
    const int dof = m->jnt_dofadr[m->body_jntadr[i + 1]];
    const Vector3 w_body = b.orientation.conjugate() * b.omega;
    for (int k = 0; k < 3; ++k) {
      d->qvel[dof + k] = b.velocity[k];
      d->qvel[dof + 3 + k] = w_body[k];
    }
  }
  mj_forward(m, d);
  peers::TrajectoryCsv csv;
  auto sample = [&] {
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const PeerBody& b = scene.bodies[i];
      const int q = m->jnt_qposadr[m->body_jntadr[i + 1]], dof = m->jnt_dofadr[m->body_jntadr[i + 1]];
      const Eigen::Quaterniond orientation(d->qpos[q + 3], d->qpos[q + 4], d->qpos[q + 5], d->qpos[q + 6]);
      const Vector3 w_body(d->qvel[dof + 3], d->qvel[dof + 4], d->qvel[dof + 5]);
      csv.Add(d->time, b, Vector3(d->qpos[q], d->qpos[q + 1], d->qpos[q + 2]), orientation,
              Vector3(d->qvel[dof], d->qvel[dof + 1], d->qvel[dof + 2]), orientation * w_body);
    }
  };
  const double seconds = peers::RunPeer(
      scene, args, [&] { mj_step(m, d); }, sample);
  if (d->warning[mjWARN_CONTACTFULL].number > 0 || d->warning[mjWARN_CNSTRFULL].number > 0) {
    std::cerr << "warning: MuJoCo ran out of contact or constraint rows (nconmax, njmax): contacts were dropped\n";
  }
  char version[16];
  std::snprintf(version, sizeof version, "%d", mj_version());
  peers::PrintTiming("mujoco", version, scene, seconds);
  mj_deleteData(d);
  mj_deleteModel(m);
  if (!args.out.empty() && !csv.Write(args.out)) return 1;
  return 0;
}
