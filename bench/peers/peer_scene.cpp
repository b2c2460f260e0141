// The rbsim scenes a peer engine can run (peer_scene.h).

#include "peer_scene.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <stdexcept>

#include "massprops/repair/repair.h"
#include "massprops/report/atomic_file.h"
#include "outputs.h"
#include "scene/simulation.h"

namespace peers {

PeerScene LoadPeerScene(const std::string& path, double dt) {
  std::vector<std::string> warnings;
  scene::Scene scene = scene::LoadScene(path, warnings);
  if (dt > 0) scene.dt = dt;
  auto refuse = [&](const std::string& what) {
    return std::runtime_error(path + ": " + what +
                              ": a peer engine runs "
                              "box, sphere, capsule and cylinder solids, convex hulls, static boxes and hulls, ground "
                              "planes and gravity");
  };
  if (!scene.pairs.empty()) throw refuse("pair materials");
  if (!scene.joints.empty()) throw refuse("joints");
  if (!scene.robots.empty()) throw refuse("robots (bench/peers/robot_peer runs robots)");
  PeerScene out;
  out.file = path;
  out.dt = scene.dt;
  out.duration = scene.duration;
  out.output_rate = scene.output_rate;
  out.grounds = scene.grounds;
  out.steps = scene::StepCount(scene);
  out.sample_every = scene::SampleEvery(scene);
  for (const scene::ForceSpec& f : scene.forces) {
    if (f.kind != scene::ForceKind::kGravity || !f.bodies.empty()) {
      throw refuse(f.field + " (" + scene::ForceName(f.kind) + ")");
    }
    out.gravity += f.vector;
  }
  const scene::Simulation sim = scene::BuildSimulation(scene, warnings, 1);
  // Static bodies: drawn in the world after the ground planes' two shades each.
  for (std::size_t k = 0; k < scene.statics.size(); ++k) {
    const scene::StaticSpec& spec = scene.statics[k];
    const massprops::TriangleMesh& drawn = sim.statics[2 * scene.grounds.size() + k].display;
    PeerStatic st;
    st.name = spec.name;
    st.material = spec.collision.material;
    const bool box_solid = spec.shape.solid() && std::holds_alternative<massprops::primitive::Box>(*spec.shape.solid());
    if (spec.collision.kind == scene::CollisionKind::kHull) {
      st.box = false;
      const massprops::PolygonMesh hull = massprops::ConvexHull(massprops::ToPolygonMesh(drawn));
      for (Eigen::Index v = 0; v < hull.V.rows(); ++v) st.hull.push_back(hull.V.row(v).transpose());
    } else if (box_solid && spec.collision.kind == scene::CollisionKind::kAuto) {
      // Its box in its own axes, from the drawn corners (world) turned back.
      const Matrix3 R = spec.orientation.toRotationMatrix();
      Eigen::AlignedBox<double, 3> local;
      for (Eigen::Index v = 0; v < drawn.V.rows(); ++v) local.extend(R.transpose() * drawn.V.row(v).transpose());
      st.half_extents = local.sizes() / 2;
      st.position = R * local.center();
      st.orientation = spec.orientation;
    } else {
      throw refuse(spec.field + " (a static body other than a box solid or a hull)");
    }
    out.statics.push_back(st);
  }
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const scene::BodySpec& spec = scene.bodies[i];
    namespace pr = massprops::primitive;
    const scene::SimBody& sb = sim.bodies[i];
    const scene::BodyState s = scene::StateOf(sb, sim.world().bodies()[i]);
    PeerBody b;
    b.name = spec.name;
    b.mass = sb.mp.mass;
    b.position = s.position;
    b.velocity = s.velocity;
    b.omega = s.omega_world;
    b.material = spec.collision.material;
    b.principal_axes = sb.principal.axes;
    if (spec.collision.kind == scene::CollisionKind::kHull) {
      // The hull in the principal frame, where the inertia is diagonal: x_B = R_MBᵀ (x_M − com).
      b.kind = PeerBody::Kind::kHull;
      b.frame = sb.principal.axes;
      b.inertia = sb.principal.moments;
      b.orientation = sim.world().bodies()[i].orientation;
      const massprops::PolygonMesh hull = massprops::ConvexHull(massprops::ToPolygonMesh(sb.display));
      for (Eigen::Index v = 0; v < hull.V.rows(); ++v)
        b.hull.push_back(b.frame.transpose() * hull.V.row(v).transpose());
      out.bodies.push_back(b);
      continue;
    }
    const massprops::Primitive* solid = spec.shape.solid();
    if (solid == nullptr) throw refuse(spec.field + " (a mesh or implicit shape colliding as other than its hull)");
    if (spec.collision.kind != scene::CollisionKind::kAuto) throw refuse(spec.field + ".collision");
    namespace pr = massprops::primitive;
    const double scale = massprops::MetresPerUnit(spec.shape.unit);
    if (const auto* box = std::get_if<pr::Box>(solid)) {
      b.kind = PeerBody::Kind::kBox;
      b.half_extents = scale * box->size / 2;
    } else if (const auto* sphere = std::get_if<pr::Sphere>(solid)) {
      b.kind = PeerBody::Kind::kSphere;
      b.radius = scale * sphere->radius;
    } else if (const auto* capsule = std::get_if<pr::Capsule>(solid)) {
      b.kind = PeerBody::Kind::kCapsule;
      b.radius = scale * capsule->radius;
      b.half_length = scale * capsule->length / 2;
    } else if (const auto* cylinder = std::get_if<pr::Cylinder>(solid)) {
      b.kind = PeerBody::Kind::kCylinder;
      b.radius = scale * cylinder->radius;
      b.half_length = scale * cylinder->height / 2;
    } else {
      throw refuse(spec.field + ".solid (" + std::string(massprops::PrimitiveName(*solid)) + ")");
    }
    b.inertia = sb.mp.inertia_com.diagonal();  // a primitive's own axes are principal
    b.orientation = s.orientation;
    out.bodies.push_back(b);
  }
  return out;
}

void TrajectoryCsv::Add(double time, const PeerBody& body, const Vector3& x, const Quaternion& q_frame,
                        const Vector3& v, const Vector3& w) {
  if (text_.empty()) text_ = std::string(rbsim::kTrajectoryCsvHeader) + "\n";
  const Quaternion q = (q_frame * Quaternion(body.frame.transpose())).normalized();  // the mesh's: q_WF R_FM
  const Vector3 wp = body.principal_axes.transpose() * (q.conjugate() * w);          // principal axes
  char line[640];
  std::snprintf(line, sizeof line,
                "%.17g,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,"
                "%.17g\n",
                time, body.name.c_str(), x.x(), x.y(), x.z(), q.w(), q.x(), q.y(), q.z(), v.x(), v.y(), v.z(), w.x(),
                w.y(), w.z(), wp.x(), wp.y(), wp.z());
  text_ += line;
}

bool TrajectoryCsv::Write(const std::string& path) const {
  try {
    massprops::report::WriteFileAtomically(path, text_);
    return true;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return false;
  }
}

bool ParsePeerArgs(int argc, char** argv, const char* program, PeerArgs& args) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--threads" && i + 1 < argc) {
      char* end = nullptr;
      const long n = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || n < 1 || n > 256) {
        std::cerr << "error: --threads: expected a whole number from 1 to 256\n";
        return false;
      }
      args.threads = static_cast<int>(n);
    } else if ((a == "--dt" || a == "--out") && i + 1 < argc) {
      if (a == "--out") {
        args.out = argv[++i];
      } else {
        char* end = nullptr;
        args.dt = std::strtod(argv[++i], &end);
        if (*end != '\0' || !(args.dt > 0) || !std::isfinite(args.dt)) {
          std::cerr << "error: --dt: expected a positive number of seconds\n";
          return false;
        }
      }
    } else if (!a.empty() && a[0] != '-' && args.scene.empty()) {
      args.scene = a;
    } else {
      std::cerr << "usage: " << program << " SCENE.json [--dt S] [--out trajectory.csv] [--threads N (rbsim only)]\n";
      return false;
    }
  }
  if (args.scene.empty()) {
    std::cerr << "usage: " << program << " SCENE.json [--dt S] [--out trajectory.csv] [--threads N (rbsim only)]\n";
    return false;
  }
  try {  // (before the run, not after it)
    if (!args.out.empty()) massprops::report::CheckOutputPath(args.out, {args.scene});
  } catch (const std::exception& e) {
    std::cerr << "error: --out " << e.what() << "\n";
    return false;
  }
  return true;
}

int StartPeer(int argc, char** argv, const char* program, PeerArgs& args, PeerScene& scene) {
  if (!ParsePeerArgs(argc, argv, program, args)) return 2;
  try {
    scene = LoadPeerScene(args.scene, args.dt);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return -1;
}

double RunPeer(const PeerScene& scene, const PeerArgs& args, const std::function<void()>& step,
               const std::function<void()>& sample) {
  if (!args.out.empty()) sample();
  double seconds = 0;
  for (std::int64_t s = 1; s <= scene.steps; ++s) {
    const auto start = std::chrono::steady_clock::now();
    step();
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!args.out.empty() && (s % scene.sample_every == 0 || s == scene.steps)) sample();
  }
  return seconds;
}

void PrintTiming(const char* engine, const char* version, const PeerScene& scene, double seconds) {
  std::printf(
      "{\"engine\": \"%s\", \"version\": \"%s\", \"dt\": %.17g, \"steps\": %lld, \"bodies\": %zu, "
      "\"wall_seconds\": %.6g, \"steps_per_second\": %.6g}\n",
      engine, version, scene.dt, static_cast<long long>(scene.steps), scene.bodies.size(), seconds,
      seconds > 0 ? static_cast<double>(scene.steps) / seconds : 0.0);
}

}  // namespace peers
