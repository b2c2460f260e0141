// rbsim: simulate rigid bodies made from mesh files (or closed-form solids).
//
//   rbsim SCENE.json [--dt S] [--duration S] [--integrator NAME] [--rate HZ] [--out DIR]
//   rbsim ROBOT.urdf|.sdf|.xml [--fill] [--fixed-base] ...  (a robot dropped on the ground)
//   rbsim --mesh part.stl --omega 0,10,0.01 [--omega-frame world|body|principal] [--duration S] ...
//   rbsim poses PART [--drops N] ...   (resting-pose statistics: poses_cli.cpp)
//
// Nothing runs until the scene is valid; errors are one line naming the scene file and the field.
// Exit status: 0 done, 1 invalid scene or failed output, 2 bad arguments, 130 interrupted.

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "cli.h"
#include "massprops/robot.h"
#include "massprops/version.h"
#include "outputs.h"
#include "poses_cli.h"
#include "progress.h"
#include "scene/scene.h"
#include "scene/simulation.h"

namespace {

std::atomic<bool> g_stop{false};
extern "C" void OnSignal(int) { g_stop.store(true); }

bool ParseVec3(const std::string& text, massprops::Vector3& out) {
  double v[3];
  char extra;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &v[0], &v[1], &v[2], &extra) != 3) return false;
  out = massprops::Vector3(v[0], v[1], v[2]);
  return out.allFinite();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "poses") return rbsim::PosesMain(argc - 1, argv + 1);
  CLI::App app{
      "rbsim: simulate rigid bodies made from mesh files, with trajectory, diagnostics, plot and an "
      "animated .glb.\nScene schema: see the README (section 'rbsim scenes')."};
  app.set_version_flag("--version", std::string("rbsim ") + massprops::kVersion);
  std::string scene_file, mesh, unit = "m", omega_text, omega_frame = "world", velocity_text, out_dir, integrator,
                                outputs_text;
  double density = 1000, mass = 0;
  std::optional<double> dt, duration, rate;
  bool repair = false, allow_open = false, quiet = false, fill = false, fixed_base = false;
  int threads = 1;
  auto* scene_opt = app.add_option("scene", scene_file,
                                   "Scene file (JSON), or a robot file (URDF, SDFormat, MJCF) to drop on the ground");
  app.add_flag("--fill", fill, "Robot file: compute every link's inertial from its geometry first (as massprops fill)")
      ->needs(scene_opt);
  app.add_flag("--fixed-base", fixed_base, "Robot file: weld its root link to the world")->needs(scene_opt);
  std::string keyframe;
  app.add_option("--keyframe", keyframe,
                 "Robot file (MJCF): start from this <key>: its qpos places the robot and its joints, its ctrl "
                 "drives the actuators")
      ->needs(scene_opt);
  auto* mesh_opt =
      app.add_option("--mesh", mesh, "Quick path: spin this one mesh torque-free (no scene file)")->excludes(scene_opt);
  std::vector<std::string> units;
  for (massprops::LengthUnit u : massprops::kAllLengthUnits) units.emplace_back(massprops::UnitName(u));
  app.add_option("--unit", unit, "--mesh: unit of the file's coordinates")
      ->check(CLI::IsMember(units))
      ->needs(mesh_opt);
  auto* density_opt = app.add_option("--density", density, "--mesh: density, kg/m^3")
                          ->check(massprops::app::Positive())
                          ->needs(mesh_opt);
  app.add_option("--mass", mass, "--mesh: total mass, kg")
      ->check(massprops::app::Positive())
      ->excludes(density_opt)
      ->needs(mesh_opt);
  app.add_flag("--repair", repair, "--mesh: repair the mesh first (as massprops --repair)")->needs(mesh_opt);
  app.add_flag("--allow-open", allow_open, "--mesh: simulate even an open mesh (its inertia is then not trustworthy)")
      ->needs(mesh_opt);
  app.add_option("--omega", omega_text, "--mesh: initial angular velocity wx,wy,wz in rad/s")->needs(mesh_opt);
  app.add_option("--omega-frame", omega_frame,
                 "--mesh: axes of --omega: world (= the file's axes at t = 0), principal (I1 <= I2 <= I3)")
      ->check(CLI::IsMember({"world", "body", "principal"}))
      ->needs(mesh_opt);
  app.add_option("--velocity", velocity_text, "--mesh: initial velocity vx,vy,vz in m/s")->needs(mesh_opt);
  app.add_option("--dt", dt, "Time step, s (overrides the scene)")->check(massprops::app::Positive());
  app.add_option("--duration", duration, "Simulated time, s (overrides the scene)")->check(massprops::app::Positive());
  app.add_option("--integrator", integrator, "Integrator (overrides the scene): " + dynamics::IntegratorNames());
  app.add_option("--rate", rate, "Output rate, samples per simulated second (overrides the scene)")
      ->check(massprops::app::Positive());
  app.add_option("--out", out_dir, "Write every output of the run into this directory (created if missing)");
  app.add_option("--outputs", outputs_text,
                 "Which outputs, comma-separated: csv, jsonl, diagnostics, svg, png, glb, contacts (contacts.jsonl, "
                 "each step's contact points), html (run.html, a page that plays the run in a browser) "
                 "(overrides the scene; default csv,diagnostics,svg,png,glb)");
  app.add_option("--threads", threads, "Worker threads for mesh loading and large worlds (0 = all cores)")
      ->check(massprops::app::NonNegative());
  app.add_flag("-q,--quiet", quiet, "No progress bar");
  if (const int status = massprops::app::ParseArguments(app, argc, argv); status >= 0) return status;
  if (scene_file.empty() && mesh.empty()) {
    std::cerr << "error: arguments: give a scene file, or --mesh FILE for the quick path (see --help)\n";
    return massprops::app::kBadArguments;
  }

  std::vector<std::string> warnings;
  auto flush_warnings = [&warnings] {
    for (const auto& w : warnings) std::cerr << "warning: " << massprops::app::OneLine(w) << "\n";
    warnings.clear();
  };
  rbsim::Scene scene;
  try {
    const std::string extension = std::filesystem::path(scene_file).extension().string();
    const bool robot_file = !scene_file.empty() && extension != ".json" && std::filesystem::is_regular_file(scene_file);
    if ((fill || fixed_base || !keyframe.empty()) && !robot_file) {
      std::cerr << "error: --fill, --fixed-base, --keyframe: for a robot file (URDF, SDFormat, MJCF), not a scene\n";
      return massprops::app::kBadArguments;
    }
    if (robot_file) {
      massprops::DetectRobotFormat(scene_file);  // names the file when it is no robot description
      scene = rbsim::RobotScene(scene_file, fill, fixed_base, keyframe);
    } else if (!scene_file.empty()) {
      scene = rbsim::LoadScene(scene_file, warnings);
    } else {
      massprops::Vector3 omega = massprops::Vector3::Zero(), velocity = massprops::Vector3::Zero();
      if (!omega_text.empty() && !ParseVec3(omega_text, omega)) {
        std::cerr << "error: --omega: expected three finite numbers wx,wy,wz, got '"
                  << massprops::app::OneLine(omega_text) << "'\n";
        return massprops::app::kBadArguments;
      }
      if (!velocity_text.empty() && !ParseVec3(velocity_text, velocity)) {
        std::cerr << "error: --velocity: expected three finite numbers vx,vy,vz, got '"
                  << massprops::app::OneLine(velocity_text) << "'\n";
        return massprops::app::kBadArguments;
      }
      // The typed scene of one body, as a scene file with these fields would give.
      scene.file = "<command line>";
      scene.duration = duration ? *duration : 10.0;
      // Default step: at most 1 ms and at most 0.01 rad of turn per step.
      scene.dt = omega.stableNorm() > 0 ? std::min(1e-3, 0.01 / omega.stableNorm()) : 1e-3;
      if (dt) scene.dt = *dt;
      if (!dt && !(scene.duration / scene.dt <= 1e9)) {
        std::cerr << "error: --omega: |omega| = " << omega.stableNorm() << " rad/s asks for steps of " << scene.dt
                  << " s (0.01 rad of turn each), " << scene.duration / scene.dt << " of them for " << scene.duration
                  << " s, more than 10^9; give a smaller --omega, or --dt and --duration\n";
        return massprops::app::kBadArguments;
      }
      scene.outputs = rbsim::DefaultOutputs();
      const std::filesystem::path path = std::filesystem::absolute(mesh).lexically_normal();
      if (const std::string problem = rbsim::MeshFileProblem(path); !problem.empty()) {
        std::cerr << "error: --mesh: '" << massprops::app::OneLine(mesh) << "' " << problem << "\n";
        return 1;
      }
      rbsim::BodySpec body;
      body.name = std::filesystem::path(mesh).stem().string();
      body.field = "bodies[0]";
      body.shape.source = dynamics::MeshSource{path.string(), repair, allow_open};
      body.shape.unit = massprops::ParseLengthUnit(unit);
      body.shape.unit_stated = app.count("--unit") > 0;
      body.shape.mass =
          mass > 0 ? massprops::MassSpec(massprops::TotalMass{mass}) : massprops::MassSpec(massprops::Density{density});
      body.velocity = velocity;
      body.angular_velocity = omega;
      body.angular_velocity_frame = rbsim::ParseVectorFrame(omega_frame);
      scene.bodies.push_back(std::move(body));
      rbsim::CheckTiming(scene, warnings);
    }
    // Overrides, validated like the scene's own fields.
    if (dt) scene.dt = *dt;
    if (duration) scene.duration = *duration;
    if (rate) scene.output_rate = *rate;
    if (!integrator.empty()) {
      try {
        scene.integrator = dynamics::ParseIntegrator(integrator);
      } catch (const std::invalid_argument& e) {
        std::cerr << "error: --integrator: " << massprops::app::OneLine(e.what()) << "\n";
        return massprops::app::kBadArguments;
      }
    }
    if (!outputs_text.empty()) {
      scene.outputs.clear();
      std::stringstream list(outputs_text);
      std::string name;
      while (std::getline(list, name, ',')) {
        try {
          scene.outputs.push_back(rbsim::ParseOutputName(name));
        } catch (const std::invalid_argument& e) {
          std::cerr << "error: --outputs: " << massprops::app::OneLine(e.what()) << "\n";
          return massprops::app::kBadArguments;
        }
      }
    }
    if (dt || duration || rate) rbsim::CheckTiming(scene, warnings);
  } catch (const std::exception& e) {
    flush_warnings();
    std::cerr << "error: " << massprops::app::OneLine(e.what()) << "\n";
    return 1;
  }
  flush_warnings();

  auto wants = [&scene](rbsim::OutputKind k) {
    return std::find(scene.outputs.begin(), scene.outputs.end(), k) != scene.outputs.end();
  };
  const bool plot = !out_dir.empty() && (wants(rbsim::OutputKind::kPlotSvg) || wants(rbsim::OutputKind::kPlotPng));
  if (plot && !rbsim::HaveGnuplot()) {
    std::cerr
        << "error: --outputs: the plot needs gnuplot, which is not on the PATH (apt-get install gnuplot-nox), or leave "
           "svg and png out of the outputs\n";
    return 1;
  }

  std::optional<rbsim::Simulation> sim;
  try {
    sim.emplace(rbsim::BuildSimulation(scene, warnings, threads));
  } catch (const std::exception& e) {
    flush_warnings();
    std::cerr << "error: " << massprops::app::OneLine(e.what()) << "\n";
    return 1;
  }
  flush_warnings();

  if (!out_dir.empty() && wants(rbsim::OutputKind::kGlb)) {
    std::int64_t triangles = 0;
    for (const auto& b : sim->bodies) triangles += b.display.F.rows();
    if (triangles > 2000000) {
      std::cerr
          << "warning: the .glb will carry " << triangles << " triangles (about " << triangles * 72 / 1000000
          << " MB of vertices); viewers may be slow: decimate the mesh for viewing, or leave glb out of --outputs\n";
    }
  }

  std::unique_ptr<rbsim::TrajectoryWriter> writer;
  rbsim::Recording recording;
  const bool record = !out_dir.empty() && (plot || wants(rbsim::OutputKind::kGlb) || wants(rbsim::OutputKind::kHtml));
  recording.contacts = wants(rbsim::OutputKind::kHtml);
  try {
    if (!out_dir.empty()) {
      std::filesystem::create_directories(out_dir);
      writer = std::make_unique<rbsim::TrajectoryWriter>(out_dir, scene.outputs, !sim->world().joints().empty());
    }
  } catch (const std::exception& e) {
    std::cerr << "error: --out " << massprops::app::OneLine(out_dir) << ": " << massprops::app::OneLine(e.what())
              << "\n";
    return 1;
  }

  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  rbsim::RunStats stats;
  try {
    massprops::app::Progress progress("rbsim", "", !quiet);
    stats = rbsim::Run(
        *sim,
        [&](const dynamics::World& world, const dynamics::Diagnostics& d) {
          if (writer) writer->Add(*sim, world, d);
          if (record) recording.Add(*sim, world, d);
        },
        [&progress](double f) { progress.Fraction(f); }, &g_stop,
        [&](std::int64_t step) {
          if (writer) writer->AddStep(*sim, step);
        });
  } catch (const std::exception& e) {
    std::cerr << "error: " << massprops::app::OneLine(scene.file) << ": " << e.what()
              << "; no output files were written\n";
    return 1;
  }
  if (stats.interrupted) {
    std::cerr << "rbsim: interrupted at t = " << sim->world().time() << " s; no output files were written\n";
    return 130;
  }

  // Whole or nothing: the .glb and the plots are made in a staging folder, the trajectory files
  // under temporary names; only when every one succeeded are they all renamed into place.
  std::vector<std::string> written;
  const std::string staging = out_dir + "/.rbsim-staging-" + std::to_string(::getpid());
  try {
    std::vector<std::pair<std::string, std::string>> staged;  // (made, final)
    auto stage = [&](const char* name) {
      std::filesystem::create_directories(staging);
      staged.emplace_back(staging + "/" + name, out_dir + "/" + name);
      return staged.back().first;
    };
    if (!out_dir.empty() && wants(rbsim::OutputKind::kGlb)) rbsim::WriteGlb(stage("animation.glb"), *sim, recording);
    if (!out_dir.empty() && wants(rbsim::OutputKind::kHtml)) rbsim::WriteHtml(stage("run.html"), *sim, recording);
    for (auto [kind, name] :
         {std::pair{rbsim::OutputKind::kPlotSvg, "plot.svg"}, std::pair{rbsim::OutputKind::kPlotPng, "plot.png"}}) {
      if (!out_dir.empty() && wants(kind)) rbsim::WritePlot(stage(name), *sim, recording);
    }
    if (writer) written = writer->Commit();
    for (const auto& [from, to] : staged) {
      std::filesystem::rename(from, to);
      written.push_back(to);
    }
  } catch (const std::exception& e) {
    std::error_code ec;
    std::filesystem::remove_all(staging, ec);
    std::cerr << "error: " << massprops::app::OneLine(e.what()) << "; no output files were written\n";
    return 1;
  }
  if (!out_dir.empty()) {
    std::error_code ec;
    std::filesystem::remove_all(staging, ec);
  }
  for (const std::string& f : stats.fell_through) std::cerr << "warning: " << massprops::app::OneLine(f) << "\n";
  std::cout << rbsim::Summary(*sim, stats);
  if (out_dir.empty()) {
    std::cout << "  (no --out DIR: no trajectory, plot or .glb written)\n";
  } else {
    for (const auto& p : written) std::cout << "  wrote " << p << "\n";
  }
  return 0;
}
