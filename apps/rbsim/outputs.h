#pragma once
// rbsim's outputs: the trajectory (CSV, JSON lines), the diagnostics over time (CSV), the plot
// (gnuplot, SVG/PNG) and the animated glTF binary (.glb). Every file is written under a
// temporary name and renamed when complete.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "massprops/report/atomic_file.h"
#include "scene/simulation.h"

namespace rbsim {

// The scene library's types (Scene, Simulation, ...) as the command's own: rbsim only formats them.
using namespace ::scene;  // NOLINT(google-build-using-namespace)

/// What the plot and the .glb need, kept in memory at the output rate.
struct Recording {
  std::vector<double> times;
  /// Per body, per sample: center of mass and mesh orientation (x, y, z, w; consecutive keys on
  /// the same side of the quaternion double cover, so that interpolation takes the short way).
  std::vector<std::vector<Eigen::Vector3f>> translations;
  std::vector<std::vector<Eigen::Vector4f>> rotations;
  std::vector<Vector3> omega_principal;    ///< of the plotted body
  std::vector<double> energy_drift;        ///< (E − E0) / |E0|
  std::vector<double> momentum_drift;      ///< (|L| − |L0|) / |L0|, L about the world origin
  std::vector<double> kinetic, potential;  ///< J
  dynamics::Diagnostics start;             ///< at the first sample
  /// With `contacts` set before the first sample: per sample, the last step's contact points as
  /// (x, y, z, fx, fy, fz), the force on the first body (impulse / dt, N), and per body whether
  /// it is asleep.
  bool contacts = false;
  std::vector<std::vector<float>> contact_forces;
  /// Per spatial tendon (in the world's order, fixed ones empty): its path's world points, x y z
  /// per point, sample after sample.
  std::vector<std::vector<float>> tendon_paths;
  std::vector<std::vector<std::uint8_t>> asleep;
  /// Lines the page shows under its plots (a drop's resting poses), set after the run.
  std::vector<std::string> notes;

  void Add(const Simulation& sim, const dynamics::World& world, const dynamics::Diagnostics& d);
};

/// Streams the per-sample files (trajectory.csv, trajectory.jsonl, diagnostics.csv, and joints.csv
/// with csv when the scene has joints) and the per-step contacts.jsonl into `dir`.
class TrajectoryWriter {
 public:
  TrajectoryWriter(const std::string& dir, const std::vector<OutputKind>& outputs, bool joints = false);
  void Add(const Simulation& sim, const dynamics::World& world, const dynamics::Diagnostics& d);
  /// contacts.jsonl (with the contacts output): the contacts of step `step`, just taken.
  void AddStep(const Simulation& sim, std::int64_t step);
  /// Renames the finished files into place and returns their paths.
  std::vector<std::string> Commit();

 private:
  /// constraints.csv: each loop, coupling and tendon per sample (with csv, when the world has any).
  void AddConstraints(const dynamics::World& world, double time);
  std::unique_ptr<massprops::report::AtomicFile> csv_, jsonl_, diagnostics_, joints_, contacts_, constraints_;
  std::string dir_;
  dynamics::Diagnostics start_;
  bool started_ = false;
  std::string line_;
};

/// The CSV header of trajectory.csv (documented in the README).
extern const char* const kTrajectoryCsvHeader;
extern const char* const kDiagnosticsCsvHeader;
/// joints.csv: per joint per sample, its position q1..q7 and velocity v1..v6 (as many as the
/// joint type has, the rest empty) and the last step's impulses.
extern const char* const kJointsCsvHeader;
/// constraints.csv: per loop, coupling and tendon per sample, its kind ("loop", "coupling",
/// "tendon"), residual (a loop's gap in m or rad, a coupling's y − y(x), a tendon's length beyond
/// its range), length (a tendon's; a coupling's follower coordinate) and last step's impulse.
extern const char* const kConstraintsCsvHeader;

/// Writes the run as one self-contained HTML page that plays it offline (html.cpp): the bodies,
/// static bodies and grounds, a time slider, the contact forces, sleeping bodies, the diagnostics.
/// @throws std::runtime_error naming the path.
void WriteHtml(const std::string& path, const Simulation& sim, const Recording& rec);

/// Writes the bodies' meshes and their animation (one key per sample) as a glTF 2.0 binary.
/// @throws std::runtime_error naming the path.
void WriteGlb(const std::string& path, const Simulation& sim, const Recording& rec);

/// True when a `gnuplot` executable is on the PATH.
bool HaveGnuplot();
/// Plots ω (principal axes) of the plotted body, the energy drift and the |L| drift against time,
/// with gnuplot, into an SVG or PNG file (by the extension). @throws std::runtime_error.
void WritePlot(const std::string& path, const Simulation& sim, const Recording& rec);

}  // namespace rbsim
