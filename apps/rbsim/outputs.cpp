// The definitions of outputs.h: rbsim's outputs.

#include "outputs.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace rbsim {

const char* const kTrajectoryCsvHeader = "time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,w1,w2,w3";
const char* const kJointsCsvHeader =
    "time,joint,type,q1,q2,q3,q4,q5,q6,q7,v1,v2,v3,v4,v5,v6,limit_impulse,drive_impulse";
const char* const kConstraintsCsvHeader = "time,constraint,kind,residual,length,impulse";
const char* const kDiagnosticsCsvHeader =
    "time,kinetic_energy,potential_energy,energy,px,py,pz,Lx,Ly,Lz,energy_drift,p_drift,L_drift";

namespace {

// Shortest text that reads back to the same double.
void Put(std::string& s, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, r.ptr);
}
void PutList(std::string& s, std::initializer_list<double> values, char sep = ',') {
  bool first = true;
  for (double v : values) {
    if (!first) s += sep;
    first = false;
    Put(s, v);
  }
}
std::string JsonString(const std::string& in) {
  std::string out = "\"";
  for (char c : in) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
      continue;
    }
    out += c;
  }
  return out + "\"";
}

}  // namespace

void Recording::Add(const Simulation& sim, const dynamics::World& world, const dynamics::Diagnostics& d) {
  const auto& bodies = world.bodies();
  if (translations.empty()) {
    translations.resize(bodies.size());
    rotations.resize(bodies.size());
  }
  times.push_back(d.time);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const BodyState s = StateOf(sim.bodies[b], bodies[b]);
    translations[b].push_back(s.position.cast<float>());
    Eigen::Vector4d q(s.orientation.x(), s.orientation.y(), s.orientation.z(), s.orientation.w());
    if (!rotations[b].empty() && q.cast<float>().dot(rotations[b].back()) < 0) q = -q;
    rotations[b].push_back(q.cast<float>().normalized());
    if (static_cast<int>(b) == sim.scene.plot_body) omega_principal.push_back(s.omega_principal);
  }
  if (times.size() == 1) start = d;
  tendon_paths.resize(world.tendons().size());
  for (std::size_t t = 0; t < world.tendons().size(); ++t) {
    for (const dynamics::BodyFrame& f : world.tendons()[t].path) {
      const Vector3 x = dynamics::InWorld(bodies, f).origin;
      for (int k = 0; k < 3; ++k) tendon_paths[t].push_back(static_cast<float>(x[k]));
    }
  }
  const dynamics::Diagnostics& d0 = start;
  const double e0 = std::abs(d0.total_energy) > 0 ? std::abs(d0.total_energy) : 1.0;
  energy_drift.push_back((d.total_energy - d0.total_energy) / e0);
  kinetic.push_back(d.kinetic_energy);
  potential.push_back(d.potential_energy);
  if (contacts) {
    std::vector<float> forces;
    const double h = sim.scene.dt;
    const Vector3 up = sim.scene.up == 'x'   ? Vector3::UnitX()
                       : sim.scene.up == 'y' ? Vector3::UnitY()
                                             : Vector3::UnitZ();
    for (const dynamics::ContactReport& c : sim.physics.Contacts()) {
      // The force on the moving body at a ground or static contact; between two bodies, on the
      // one it pushes up (either is the contact's force: the other's is its opposite).
      const Vector3 f = (c.b >= 0 && c.impulse.dot(up) < 0 ? -c.impulse : c.impulse) / h;
      for (double v : {c.point.x(), c.point.y(), c.point.z(), f.x(), f.y(), f.z()}) {
        forces.push_back(static_cast<float>(v));
      }
    }
    contact_forces.push_back(std::move(forces));
    std::vector<std::uint8_t> sleeping(bodies.size());
    for (std::size_t b = 0; b < bodies.size(); ++b) sleeping[b] = sim.physics.asleep(static_cast<int>(b)) ? 1 : 0;
    asleep.push_back(std::move(sleeping));
  }
  const double l0 = d0.angular_momentum.norm();
  momentum_drift.push_back(l0 > 0 ? (d.angular_momentum.norm() - l0) / l0 : d.angular_momentum.norm());
}

TrajectoryWriter::TrajectoryWriter(const std::string& dir, const std::vector<OutputKind>& outputs, bool joints) {
  auto want = [&](OutputKind k) { return std::find(outputs.begin(), outputs.end(), k) != outputs.end(); };
  using massprops::report::AtomicFile;
  dir_ = dir;
  if (want(OutputKind::kCsv)) {
    csv_ = std::make_unique<AtomicFile>(dir + "/trajectory.csv");
    csv_->stream() << kTrajectoryCsvHeader << "\n";
    if (joints) {
      joints_ = std::make_unique<AtomicFile>(dir + "/joints.csv");
      joints_->stream() << kJointsCsvHeader << "\n";
    }
  }
  if (want(OutputKind::kJsonl)) jsonl_ = std::make_unique<AtomicFile>(dir + "/trajectory.jsonl");
  if (want(OutputKind::kContacts)) contacts_ = std::make_unique<AtomicFile>(dir + "/contacts.jsonl");
  if (want(OutputKind::kDiagnostics)) {
    diagnostics_ = std::make_unique<AtomicFile>(dir + "/diagnostics.csv");
    diagnostics_->stream() << kDiagnosticsCsvHeader << "\n";
  }
}

void TrajectoryWriter::Add(const Simulation& sim, const dynamics::World& world, const dynamics::Diagnostics& d) {
  if (!started_) start_ = d, started_ = true;
  const auto& bodies = world.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const BodyState s = StateOf(sim.bodies[b], bodies[b]);
    if (csv_) {
      line_.clear();
      Put(line_, d.time);
      line_ += ',';
      line_ += sim.bodies[b].name;
      line_ += ',';
      PutList(line_,
              {s.position.x(), s.position.y(), s.position.z(), s.orientation.w(), s.orientation.x(), s.orientation.y(),
               s.orientation.z(), s.velocity.x(), s.velocity.y(), s.velocity.z(), s.omega_world.x(), s.omega_world.y(),
               s.omega_world.z(), s.omega_principal.x(), s.omega_principal.y(), s.omega_principal.z()});
      line_ += '\n';
      csv_->stream() << line_;
    }
    if (jsonl_) {
      line_ = "{\"time\":";
      Put(line_, d.time);
      line_ += ",\"body\":" + JsonString(sim.bodies[b].name) + ",\"position\":[";
      PutList(line_, {s.position.x(), s.position.y(), s.position.z()});
      line_ += "],\"quaternion\":[";
      PutList(line_, {s.orientation.w(), s.orientation.x(), s.orientation.y(), s.orientation.z()});
      line_ += "],\"velocity\":[";
      PutList(line_, {s.velocity.x(), s.velocity.y(), s.velocity.z()});
      line_ += "],\"omega\":[";
      PutList(line_, {s.omega_world.x(), s.omega_world.y(), s.omega_world.z()});
      line_ += "],\"omega_principal\":[";
      PutList(line_, {s.omega_principal.x(), s.omega_principal.y(), s.omega_principal.z()});
      line_ += "]}\n";
      jsonl_->stream() << line_;
    }
  }
  for (std::size_t j = 0; joints_ && j < world.joints().size(); ++j) {
    const dynamics::JointState js = world.joint_state(static_cast<int>(j));
    line_.clear();
    Put(line_, d.time);
    line_ += ',' + world.joints()[j].name + ',' + dynamics::JointTypeName(world.joints()[j].type);
    for (std::size_t k = 0; k < 7; ++k) {
      line_ += ',';
      if (k < js.position.size()) Put(line_, js.position[k]);
    }
    for (std::size_t k = 0; k < 6; ++k) {
      line_ += ',';
      if (k < js.velocity.size()) Put(line_, js.velocity[k]);
    }
    line_ += ',';
    PutList(line_, {js.limit_impulse, js.drive_impulse});
    line_ += '\n';
    joints_->stream() << line_;
  }
  if (csv_) AddConstraints(world, d.time);
  if (diagnostics_) {
    const dynamics::Drift drift = dynamics::DriftSince(start_, d);
    line_.clear();
    PutList(line_, {d.time, d.kinetic_energy, d.potential_energy, d.total_energy, d.linear_momentum.x(),
                    d.linear_momentum.y(), d.linear_momentum.z(), d.angular_momentum.x(), d.angular_momentum.y(),
                    d.angular_momentum.z(), drift.energy, drift.linear_momentum, drift.angular_momentum});
    line_ += '\n';
    diagnostics_->stream() << line_;
  }
}

void TrajectoryWriter::AddConstraints(const dynamics::World& world, double time) {
  if (world.loops().empty() && world.couplings().empty() && world.tendons().empty()) return;
  if (!constraints_) {
    constraints_ = std::make_unique<massprops::report::AtomicFile>(dir_ + "/constraints.csv");
    constraints_->stream() << kConstraintsCsvHeader << "\n";
  }
  auto row = [&](const std::string& name, const char* kind, const dynamics::ConstraintState& s) {
    line_.clear();
    Put(line_, time);
    line_ += ',' + name + ',' + kind + ',';
    PutList(line_, {s.residual, s.length, s.impulse});
    line_ += '\n';
    constraints_->stream() << line_;
  };
  for (std::size_t k = 0; k < world.loops().size(); ++k)
    row(world.loops()[k].name, "loop", world.loop_state(static_cast<int>(k)));
  for (std::size_t k = 0; k < world.couplings().size(); ++k)
    row(world.couplings()[k].name, "coupling", world.coupling_state(static_cast<int>(k)));
  for (std::size_t k = 0; k < world.tendons().size(); ++k)
    row(world.tendons()[k].name, "tendon", world.tendon_state(static_cast<int>(k)));
}

void TrajectoryWriter::AddStep(const Simulation& sim, std::int64_t step) {
  if (!contacts_) return;
  line_ = "{\"step\":" + std::to_string(step) + ",\"time\":";
  Put(line_, sim.world().time());
  line_ += ",\"contacts\":[";
  bool first = true;
  for (const dynamics::ContactReport& c : sim.physics.Contacts()) {
    line_ += first ? "{\"a\":" : ",{\"a\":";
    first = false;
    line_ += JsonString(sim.bodies[static_cast<std::size_t>(c.a)].name) + ",\"b\":";
    line_ += c.b >= 0 ? JsonString(sim.bodies[static_cast<std::size_t>(c.b)].name) : std::string("null");
    line_ += ",\"point\":[";
    PutList(line_, {c.point.x(), c.point.y(), c.point.z()});
    line_ += "],\"normal\":[";
    PutList(line_, {c.normal.x(), c.normal.y(), c.normal.z()});
    line_ += "],\"impulse\":[";
    PutList(line_, {c.impulse.x(), c.impulse.y(), c.impulse.z()});
    line_ += "],\"torque\":[";
    PutList(line_, {c.torque.x(), c.torque.y(), c.torque.z()});
    line_ += "]}";
  }
  line_ += "]}\n";
  contacts_->stream() << line_;
}

std::vector<std::string> TrajectoryWriter::Commit() {
  std::vector<std::string> paths;
  for (auto* f : {csv_.get(), jsonl_.get(), diagnostics_.get(), joints_.get(), contacts_.get(), constraints_.get()}) {
    if (!f) continue;
    f->Commit();
    paths.push_back(f->path());
  }
  return paths;
}

}  // namespace rbsim
