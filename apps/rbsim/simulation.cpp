#include "simulation.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "dynamics/forces.h"
#include "massprops/composition.h"
#include "massprops/implicit.h"
#include "massprops/io.h"
#include "massprops/monte_carlo.h"
#include "massprops/solids.h"
#include "report.h"

namespace rbsim {
namespace {

using massprops::MassProperties;
using massprops::TriangleMesh;

std::string Num(double v, const char* fmt = "%.6g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// A distinct, readable colour per body (a few hues of a qualitative palette).
Vector3 DefaultColor(std::size_t i) {
  static const double kPalette[][3] = {{0.90, 0.62, 0.00}, {0.34, 0.71, 0.91}, {0.00, 0.62, 0.45},
                                       {0.80, 0.47, 0.65}, {0.94, 0.89, 0.26}, {0.84, 0.37, 0.00}};
  const auto& c = kPalette[i % 6];
  return Vector3(c[0], c[1], c[2]);
}

// A solid from its closed form (exact mass properties) and a tessellation to look at.
void LoadSolid(const ShapeSpec& s, SimBody& body) {
  namespace so = massprops::solids;
  constexpr int kN = 24;
  MassProperties unit;  // at density 1
  const std::string& t = s.solid_type;
  if (t == "box") {
    body.display = massprops::Triangulate(so::Box(s.size));
    unit = so::BoxProperties(s.size, 1.0);
    body.source = "box " + Num(s.size.x()) + " x " + Num(s.size.y()) + " x " + Num(s.size.z()) + " m";
  } else if (t == "sphere") {
    body.display = so::Sphere(s.radius, kN);
    unit = so::SphereProperties(s.radius, 1.0);
    body.source = "sphere r=" + Num(s.radius) + " m";
  } else if (t == "ellipsoid") {
    body.display = so::Ellipsoid(s.size, kN);
    unit = so::EllipsoidProperties(s.size, 1.0);
    body.source = "ellipsoid " + Num(s.size.x()) + ", " + Num(s.size.y()) + ", " + Num(s.size.z()) + " m";
  } else if (t == "cylinder") {
    body.display = so::Cylinder(s.radius, s.height, kN);
    unit = so::CylinderProperties(s.radius, s.height, 1.0);
    body.source = "cylinder r=" + Num(s.radius) + " h=" + Num(s.height) + " m";
  } else if (t == "cone") {
    body.display = so::Cone(s.radius, s.height, kN);
    unit = so::ConeProperties(s.radius, s.height, 1.0);
    body.source = "cone r=" + Num(s.radius) + " h=" + Num(s.height) + " m (apex at z=+3h/4)";
  } else if (t == "torus") {
    body.display = so::Torus(s.major_radius, s.minor_radius, kN);
    unit = so::TorusProperties(s.major_radius, s.minor_radius, 1.0);
    body.source = "torus R=" + Num(s.major_radius) + " r=" + Num(s.minor_radius) + " m";
  } else if (t == "capsule") {
    body.display = so::Capsule(s.radius, s.height, kN);
    unit = so::CapsuleProperties(s.radius, s.height, 1.0);
    body.source = "capsule r=" + Num(s.radius) + " length=" + Num(s.height) + " m";
  } else {
    throw std::logic_error("unknown solid type " + t);  // the parser admits no other
  }
  const double density = s.mass > 0 ? s.mass / unit.volume : s.density;
  body.mp = unit;
  body.mp.mass = unit.volume * density;
  body.mp.inertia_com = unit.inertia_com * density;
  body.mp.density = density;
}

void LoadMesh(const ShapeSpec& s, SimBody& body, const std::string& where,
              std::vector<std::string>& warnings, int threads) {
  massprops::app::Options opt;
  opt.unit = s.unit;
  opt.density = s.density;
  opt.mass = s.mass;
  opt.repair = s.repair;
  opt.allow_open = s.allow_open;
  opt.full_check = true;  // load the mesh whole: the .glb needs it
  opt.quiet = true;
  opt.threads = threads;
  massprops::app::Report r;
  try {
    r = massprops::app::Compute(s.mesh_file, opt);
  } catch (const std::exception& e) {
    std::string what = e.what();
    // massprops' advice names its flags; in a scene they are keys.
    for (const auto& [flag, key] : {std::pair<std::string, std::string>{"--repair", "\"repair\": true"},
                                    {"--allow-open", "\"allow_open\": true"}}) {
      for (auto pos = what.find(flag); pos != std::string::npos; pos = what.find(flag, pos + key.size())) {
        what.replace(pos, flag.size(), key);
      }
    }
    throw SceneError(where + ".mesh: " + what);
  }
  for (const auto& w : r.warnings) warnings.push_back(where + ".mesh: " + s.mesh_file + ": " + w);
  if (!r.validity.valid) {
    throw SceneError(where + ".mesh: " + s.mesh_file + ": the inertia is not that of a real body (" +
                     r.validity.reason + ")");
  }
  body.mp = r.mp;
  const double scale = massprops::app::MetresPerUnit(s.unit);
  body.display = massprops::Triangulate(r.loaded.mesh);
  for (Eigen::Index i = 0; i < body.display.V.rows(); ++i) {
    body.display.V.row(i) = (scale * body.display.V.row(i).transpose() - r.mp.center_of_mass).transpose();
  }
  body.source = s.mesh_file + " (unit " + s.unit + ", " + std::to_string(body.display.F.rows()) + " triangles)";
}

// An implicit solid: mass properties by quasi-Monte Carlo to a relative standard error of 1e-4,
// and a marching-tetrahedra surface to look at.
void LoadImplicit(const ShapeSpec& s, SimBody& body, const std::string& where, std::vector<std::string>& warnings,
                  int threads) {
  using namespace massprops;
  const ImplicitPtr shape = implicit::Scaled(implicit::ParseShape(s.implicit), app::MetresPerUnit(s.unit));
  MonteCarloOptions mc;
  mc.tolerance = 1e-4;
  mc.max_samples = std::int64_t{1} << 27;
  mc.fixed_mass = s.mass;
  mc.num_threads = threads;
  MassPropertiesEstimate e;
  try {
    e = EstimateMassProperties(*shape, s.density, mc);
  } catch (const std::exception& ex) {
    throw SceneError(where + ".implicit: " + ex.what());
  }
  if (!e.tolerance_met) {
    warnings.push_back(where + ".implicit: mass properties known to a relative standard error of " +
                       Num(e.MaxRelativeError(), "%.2g") + " only (" + std::to_string(e.samples) + " points)");
  }
  body.mp = e.value;
  body.display = implicit::Polygonize(*shape, 64);
  body.display.V.rowwise() -= body.mp.center_of_mass.transpose();
  body.source = s.implicit + " (unit " + s.unit + "; QMC, relative standard error " + Num(e.MaxRelativeError(), "%.1g") + ")";
}

}  // namespace

Simulation BuildSimulation(const Scene& scene, std::vector<std::string>& warnings, int threads) {
  Simulation sim;
  sim.scene = scene;
  sim.world.set_integrator(scene.integrator);
  sim.world.set_num_threads(threads);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& spec = scene.bodies[i];
    const std::string where = scene.file + ": " + spec.field;
    SimBody body;
    body.name = spec.name;
    body.color = spec.color.value_or(DefaultColor(i));
    if (!spec.shape.mesh_file.empty()) {
      LoadMesh(spec.shape, body, where, warnings, threads);
    } else if (!spec.shape.implicit.empty()) {
      LoadImplicit(spec.shape, body, where, warnings, threads);
    } else {
      LoadSolid(spec.shape, body);
    }
    body.principal = massprops::ComputePrincipalInertia(body.mp.inertia_com);
    dynamics::RigidBody rb;
    try {
      rb = dynamics::BodyFromMassProperties(body.mp);
    } catch (const std::exception& e) {
      throw SceneError(where + ": " + e.what());
    }
    rb.orientation = (spec.orientation * rb.orientation).normalized();
    rb.position = spec.position.value_or(body.mp.center_of_mass);
    rb.velocity = spec.velocity;
    Vector3 omega = spec.angular_velocity;
    if (spec.angular_velocity_frame == VectorFrame::kBody) omega = spec.orientation * omega;
    if (spec.angular_velocity_frame == VectorFrame::kPrincipal) omega = rb.orientation * omega;
    rb.SetAngularVelocity(omega);
    try {
      sim.world.AddBody(rb);
    } catch (const std::exception& e) {
      throw SceneError(where + ": " + e.what());
    }
    sim.bodies.push_back(std::move(body));
  }

  // Mesh coordinates → body (principal) coordinates, x_B = R_MBᵀ (x_M − com).
  auto to_body = [&](int b, const Vector3& p_mesh) {
    const SimBody& sb = sim.bodies[static_cast<std::size_t>(b)];
    return Vector3(sb.principal.axes.transpose() * (p_mesh - sb.mp.center_of_mass));
  };
  auto note = [](std::string& list, const std::string& what) {
    if (list.find(what) == std::string::npos) list += (list.empty() ? "" : ", ") + what;
  };
  for (const ForceSpec& f : scene.forces) {
    const int body = f.bodies.empty() ? -1 : f.bodies[0];
    if (f.type == "gravity") {
      sim.world.AddForce(dynamics::Gravity(f.vector));
      sim.momentum_conserved = false;
      note(sim.external, "gravity");
    } else if (f.type == "linear_damping" || f.type == "angular_damping") {
      sim.world.AddForce(f.type == "linear_damping" ? dynamics::LinearDamping(f.coefficient, body)
                                                    : dynamics::AngularDamping(f.coefficient, body));
      if (f.coefficient > 0) {
        sim.energy_conserved = sim.momentum_conserved = false;
        note(sim.nonconservative, "damping");
        note(sim.external, "damping");
      }
    } else if (f.type == "force") {
      const SimBody& sb = sim.bodies[static_cast<std::size_t>(body)];
      const Vector3 point = f.point ? to_body(body, *f.point) : Vector3::Zero();
      const Vector3 vec = f.body_frame ? Vector3(sb.principal.axes.transpose() * f.vector) : f.vector;
      sim.world.AddForce(dynamics::PointForce(body, point, vec, f.body_frame));
      sim.energy_conserved = sim.momentum_conserved = false;
      note(sim.nonconservative, "applied forces");
      note(sim.external, "applied forces");
    } else if (f.type == "torque") {
      if (f.body_frame) {
        const Vector3 tau_b = sim.bodies[static_cast<std::size_t>(body)].principal.axes.transpose() * f.vector;
        sim.world.AddForce(dynamics::ForceCallback(
            [body, tau_b](double, const std::vector<dynamics::RigidBody>& bodies, std::vector<dynamics::Wrench>& out) {
              const auto b = static_cast<std::size_t>(body);
              out[b].torque += bodies[b].orientation * tau_b;
            }));
      } else {
        sim.world.AddForce(dynamics::ConstantTorque(body, f.vector));
      }
      sim.energy_conserved = sim.momentum_conserved = false;
      note(sim.nonconservative, "applied torques");
      note(sim.external, "applied torques");
    } else if (f.type == "spring") {
      if (f.bodies.size() == 2) {
        sim.world.AddForce(dynamics::SpringBetween(f.bodies[0], to_body(f.bodies[0], f.points[0]), f.bodies[1],
                                                   to_body(f.bodies[1], f.points[1]), f.coefficient,
                                                   f.rest_length, f.damping));
      } else {
        sim.world.AddForce(dynamics::SpringToWorld(body, to_body(body, f.point.value_or(Vector3::Zero())),
                                                   f.anchor, f.coefficient, f.rest_length, f.damping));
        sim.momentum_conserved = false;
        note(sim.external, "springs to the world");
      }
      if (f.damping > 0) {
        sim.energy_conserved = false;
        note(sim.nonconservative, "spring damping");
      }
    }
  }
  return sim;
}

BodyState StateOf(const SimBody& body, const dynamics::RigidBody& rb) {
  BodyState s;
  s.position = rb.position;
  // q_mesh = q_B · R_MBᵀ: maps mesh axes to world.
  s.orientation = (rb.orientation * Quaternion(body.principal.axes.transpose())).normalized();
  s.velocity = rb.velocity;
  s.omega_world = rb.AngularVelocity();
  s.omega_principal = rb.BodyAngularVelocity();
  return s;
}

std::int64_t StepCount(const Scene& scene) {
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(scene.duration / scene.dt - 1e-9)));
}

std::int64_t SampleEvery(const Scene& scene) {
  return std::max<std::int64_t>(1, std::llround(1.0 / (scene.output_rate * scene.dt)));
}

RunStats Run(Simulation& sim,
             const std::function<void(const dynamics::World&, const dynamics::Diagnostics&)>& on_sample,
             const std::function<void(double)>& on_progress, const std::atomic<bool>* stop) {
  RunStats stats;
  const auto t0 = std::chrono::steady_clock::now();
  const std::int64_t n = StepCount(sim.scene);
  const std::int64_t every = SampleEvery(sim.scene);
  auto sample = [&] {
    const dynamics::Diagnostics d = sim.world.Diagnose();
    if (stats.samples == 0) stats.start = d;
    const dynamics::Drift drift = dynamics::DriftSince(stats.start, d);
    stats.max_drift.energy = std::max(stats.max_drift.energy, std::abs(drift.energy));
    stats.max_drift.linear_momentum = std::max(stats.max_drift.linear_momentum, std::abs(drift.linear_momentum));
    stats.max_drift.angular_momentum = std::max(stats.max_drift.angular_momentum, std::abs(drift.angular_momentum));
    stats.end = d;
    ++stats.samples;
    on_sample(sim.world, d);
  };
  sample();
  const std::int64_t progress_every = std::max<std::int64_t>(1, n / 1000);
  for (std::int64_t i = 1; i <= n; ++i) {
    const dynamics::StepStatus status = sim.world.Step(sim.scene.dt);
    stats.max_substeps = std::max(stats.max_substeps, status.substeps);
    stats.steps = i;
    if (i % every == 0 || i == n) sample();
    if (i % progress_every == 0) {
      if (on_progress) on_progress(static_cast<double>(i) / static_cast<double>(n));
      if (stop && stop->load(std::memory_order_relaxed)) {
        stats.interrupted = true;
        break;
      }
    }
  }
  stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return stats;
}

std::string Summary(const Simulation& sim, const RunStats& stats) {
  std::ostringstream out;
  const auto& s = stats.start;
  const auto& e = stats.end;
  const dynamics::Drift end = dynamics::DriftSince(s, e);
  out << "rbsim: " << sim.scene.file << ": " << sim.bodies.size() << (sim.bodies.size() == 1 ? " body, " : " bodies, ")
      << dynamics::IntegratorName(sim.scene.integrator) << ", dt " << Num(sim.scene.dt) << " s, "
      << stats.steps << " steps to t = " << Num(e.time) << " s in " << Num(stats.wall_seconds, "%.3g") << " s ("
      << Num(static_cast<double>(stats.steps * static_cast<std::int64_t>(sim.bodies.size())) /
                 std::max(stats.wall_seconds, 1e-9), "%.3g")
      << " body-steps/s)\n";
  if (stats.max_substeps > 1) {
    out << "  note: the implicit solve needed up to " << stats.max_substeps
        << " sub-steps in some steps: dt is large for these spin rates\n";
  }
  auto vec = [](const Vector3& v) { return "[" + Num(v.x(), "%.9g") + ", " + Num(v.y(), "%.9g") + ", " + Num(v.z(), "%.9g") + "]"; };
  const std::string energy_note = sim.energy_conserved ? "conserved by this scene's physics"
                                                       : "not conserved here: " + sim.nonconservative;
  const std::string momentum_note = sim.momentum_conserved ? "conserved by this scene's physics"
                                                           : "not conserved here: " + sim.external;
  out << "                       start              end                drift (end)   drift (max)\n";
  char line[256];
  std::snprintf(line, sizeof line, "  energy, J            % .9e  % .9e  % .2e     %.2e   %s\n", s.total_energy,
                e.total_energy, end.energy, stats.max_drift.energy, energy_note.c_str());
  out << line;
  std::snprintf(line, sizeof line, "  |p|, kg m/s          % .9e  % .9e  % .2e     %.2e   %s\n",
                s.linear_momentum.norm(), e.linear_momentum.norm(), end.linear_momentum,
                stats.max_drift.linear_momentum, momentum_note.c_str());
  out << line;
  std::snprintf(line, sizeof line, "  |L|, kg m^2/s        % .9e  % .9e  % .2e     %.2e   %s\n",
                s.angular_momentum.norm(), e.angular_momentum.norm(), end.angular_momentum,
                stats.max_drift.angular_momentum, momentum_note.c_str());
  out << line;
  out << "  (start, end: E, |p| and |L| (L about the world origin); drift: (E - E0)/|E0|, |p - p0|/|p0|, |L - L0|/|L0|)\n";
  out << "  L end " << vec(e.angular_momentum) << "\n";
  return out.str();
}

}  // namespace rbsim
