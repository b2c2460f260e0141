// rbsim: simulate rigid bodies made from mesh files (or closed-form solids).
//
//   rbsim PART.stl [PART...] [--count N] [--on BIN.obj] ...  (parts dropped until they rest: drop_cli.cpp)
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
#include "drop_cli.h"
#include "load_flags.h"
#include "massprops/robot/robot.h"
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

// Prints the warnings so far, one line each, and forgets them.
void FlushWarnings(std::vector<std::string>& warnings) {
  for (const auto& w : warnings) std::cerr << "warning: " << massprops::app::OneLine(w) << "\n";
  warnings.clear();
}

// An early end of the command with its exit status, the message printed already.
struct Exit {
  int status;
};

// The command line, as parsed.
struct Flags {
  std::vector<std::string> inputs;  // a scene, a robot file, or parts
  rbsim::DropFlags drop;
  std::string mesh, omega_text, omega_frame = "world", velocity_text, out_dir, integrator, outputs_text;
  rbsim::RobotFileOptions robot;
  std::vector<std::string> packages;  // NAME=DIR, as given
  /// The mesh files' load options, and --threads (rbsim's default: one thread).
  std::unique_ptr<massprops::app::LoadFlags> load;
  std::optional<double> dt, duration, rate;
  bool quiet = false;
  int threads = 1;
};

// The scene file or robot file, and what a robot file takes.
CLI::Option* DeclareSceneFlags(CLI::App& app, Flags& f) {
  auto* scene_opt = app.add_option("inputs", f.inputs,
                                   "Mesh or CAD files (parts dropped on the ground until they rest), a scene file "
                                   "(JSON), or a robot file (URDF, SDFormat, MJCF) set on the ground");
  app.add_flag("--fill", f.robot.fill,
               "Robot file: compute every link's inertial from its geometry first (as massprops fill)")
      ->needs(scene_opt);
  app.add_flag("--fixed-base", f.robot.fixed_base, "Robot file: weld its root link to the world where it starts")
      ->needs(scene_opt);
  app.add_option("--keyframe", f.robot.keyframe,
                 "Robot file (MJCF): start from this <key>: its qpos places the robot and its joints, its ctrl "
                 "drives the actuators")
      ->needs(scene_opt);
  app.add_option("--package", f.packages,
                 "Robot file: NAME=DIR, the folder of package://NAME/ (URDF) or model://NAME/ (SDFormat), searched "
                 "before ROS_PACKAGE_PATH and AMENT_PREFIX_PATH (repeatable)")
      ->needs(scene_opt);
  return scene_opt;
}

// The quick path: one mesh spun torque-free.
void DeclareMeshFlags(CLI::App& app, Flags& f, CLI::Option* scene_opt) {
  auto* mesh_opt = app.add_option("--mesh", f.mesh, "Quick path: spin this one mesh torque-free (no scene file)")
                       ->excludes(scene_opt);
  f.load = std::make_unique<massprops::app::LoadFlags>(
      app, std::initializer_list<std::string_view>{"unit", "density", "mass", "repair", "allow_open", "parts"},
      "Parts and --mesh: ");
  app.add_option("--omega", f.omega_text, "--mesh: initial angular velocity wx,wy,wz in rad/s")->needs(mesh_opt);
  app.add_option("--omega-frame", f.omega_frame,
                 "--mesh: axes of --omega: world (= the file's axes at t = 0), principal (I1 <= I2 <= I3)")
      ->check(CLI::IsMember({"world", "body", "principal"}))
      ->needs(mesh_opt);
  app.add_option("--velocity", f.velocity_text, "--mesh: initial velocity vx,vy,vz in m/s")->needs(mesh_opt);
}

// What overrides the scene, and where the outputs go.
void DeclareRunFlags(CLI::App& app, Flags& f) {
  app.add_option("--dt", f.dt, "Time step, s (overrides the scene)")->check(massprops::app::Positive());
  app.add_option("--duration", f.duration, "Simulated time, s (overrides the scene)")
      ->check(massprops::app::Positive());
  app.add_option("--integrator", f.integrator, "Integrator (overrides the scene): " + dynamics::IntegratorNames());
  app.add_option("--rate", f.rate, "Output rate, samples per simulated second (overrides the scene)")
      ->check(massprops::app::Positive());
  app.add_option("--out", f.out_dir, "Write every output of the run into this directory (created if missing)");
  app.add_option("--outputs", f.outputs_text,
                 "Which outputs, comma-separated: csv, jsonl, diagnostics, svg, png, glb, contacts (contacts.jsonl, "
                 "each step's contact points), html (run.html, a page that plays the run in a browser) "
                 "(overrides the scene; default csv,diagnostics,svg,png,glb)");
  app.add_flag("-q,--quiet", f.quiet, "No progress bar");
}

// A vector flag's three numbers. @throws Exit (2) naming the flag.
massprops::Vector3 VectorFlag(const std::string& text, const char* flag, const char* names) {
  massprops::Vector3 v = massprops::Vector3::Zero();
  if (!text.empty() && !ParseVec3(text, v)) {
    massprops::app::PrintError(std::string(flag) + ": expected three finite numbers " + names + ", got '" + text + "'");
    throw Exit{massprops::app::kBadArguments};
  }
  return v;
}

// The typed scene of `--mesh`: one body spun torque-free, as a scene file with these fields would
// give. @throws Exit for bad flags or a mesh file that is not there.
rbsim::Scene MeshScene(const Flags& f, std::vector<std::string>& warnings) {
  const massprops::Vector3 omega = VectorFlag(f.omega_text, "--omega", "wx,wy,wz");
  const massprops::Vector3 velocity = VectorFlag(f.velocity_text, "--velocity", "vx,vy,vz");
  rbsim::Scene scene;
  scene.file = "<command line>";
  scene.duration = f.duration ? *f.duration : 10.0;
  // Default step: at most 1 ms and at most 0.01 rad of turn per step.
  scene.dt = omega.stableNorm() > 0 ? std::min(1e-3, 0.01 / omega.stableNorm()) : 1e-3;
  if (f.dt) scene.dt = *f.dt;
  if (!f.dt && !(scene.duration / scene.dt <= 1e9)) {
    std::ostringstream why;
    why << "--omega: |omega| = " << omega.stableNorm() << " rad/s asks for steps of " << scene.dt
        << " s (0.01 rad of turn each), " << scene.duration / scene.dt << " of them for " << scene.duration
        << " s, more than 10^9; give a smaller --omega, or --dt and --duration";
    massprops::app::PrintError(why.str());
    throw Exit{massprops::app::kBadArguments};
  }
  scene.outputs = rbsim::DefaultOutputs();
  const std::filesystem::path path = std::filesystem::absolute(f.mesh).lexically_normal();
  if (const std::string problem = rbsim::MeshFileProblem(path); !problem.empty()) {
    massprops::app::PrintError(std::string("--mesh: '") + f.mesh + "' " + problem);
    throw Exit{1};
  }
  rbsim::BodySpec body;
  body.name = std::filesystem::path(f.mesh).stem().string();
  body.field = "bodies[0]";
  const massprops::LoadOptions load = f.load->Options();
  body.shape.source = dynamics::MeshSource{path.string(), load.repair, load.allow_open, load.parts};
  body.shape.unit = load.unit;
  body.shape.unit_stated = load.unit_stated;
  body.shape.mass = load.mass;
  body.velocity = velocity;
  body.angular_velocity = omega;
  body.angular_velocity_frame = rbsim::ParseVectorFrame(f.omega_frame);
  scene.bodies.push_back(std::move(body));
  rbsim::CheckTiming(scene, warnings);
  return scene;
}

// The command line's overrides of the scene, validated like the scene's own fields. @throws Exit.
void ApplyOverrides(const Flags& f, rbsim::Scene& scene, std::vector<std::string>& warnings) {
  if (f.dt) scene.dt = *f.dt;
  if (f.duration) scene.duration = *f.duration;
  if (f.rate) scene.output_rate = *f.rate;
  if (!f.integrator.empty()) {
    try {
      scene.integrator = dynamics::ParseIntegrator(f.integrator);
    } catch (const std::invalid_argument& e) {
      massprops::app::PrintError(std::string("--integrator: ") + e.what());
      throw Exit{massprops::app::kBadArguments};
    }
  }
  if (!f.outputs_text.empty()) {
    scene.outputs.clear();
    std::stringstream list(f.outputs_text);
    std::string name;
    while (std::getline(list, name, ',')) {
      try {
        scene.outputs.push_back(rbsim::ParseOutputName(name));
      } catch (const std::invalid_argument& e) {
        massprops::app::PrintError(std::string("--outputs: ") + e.what());
        throw Exit{massprops::app::kBadArguments};
      }
    }
  }
  if (f.dt || f.duration || f.rate) rbsim::CheckTiming(scene, warnings);
}

// What the inputs are: one scene file, one robot file, or parts (mesh and CAD files). @throws Exit
// (2) naming an input that is none of these, or a scene or robot given with others.
rbsim::InputKind KindOf(const Flags& f) {
  rbsim::InputKind kind = rbsim::InputKind::kMesh;
  for (const std::string& in : f.inputs) {
    const rbsim::InputKind k = rbsim::ClassifyInput(in);
    if (k == rbsim::InputKind::kUnknown) {
      const std::string problem = rbsim::MeshFileProblem(in);
      if (!problem.empty() && f.inputs.size() == 1 && std::filesystem::path(in).extension() == ".json") {
        return rbsim::InputKind::kScene;  // the scene reader says what is wrong with it
      }
      massprops::app::PrintError(in + ": " +
                                 (problem.empty() ? "not a scene (.json), a robot description (URDF, SDFormat or MJCF: "
                                                    "XML whose root is <robot>, <sdf> or <mujoco>) or a mesh or CAD "
                                                    "file (STL, OBJ, PLY, OFF, 3MF, glTF, STEP, IGES, ...)"
                                                  : problem));
      throw Exit{problem.empty() ? massprops::app::kBadArguments : 1};
    }
    if (k != rbsim::InputKind::kMesh && f.inputs.size() > 1) {
      massprops::app::PrintError(
          in + ": a scene or robot file runs alone; give it by itself, or give only parts (mesh files)");
      throw Exit{massprops::app::kBadArguments};
    }
    if (k != rbsim::InputKind::kMesh) kind = k;
  }
  return kind;
}

// Flags that belong to another kind of input: an error naming them. @throws Exit (2).
void CheckFlagsFit(const Flags& f, const CLI::App& app, rbsim::InputKind kind) {
  const bool robot_flags = f.robot.fill || f.robot.fixed_base || !f.robot.keyframe.empty() || !f.packages.empty();
  if (robot_flags && kind != rbsim::InputKind::kRobot) {
    massprops::app::PrintError(
        std::string("--fill, --fixed-base, --keyframe, --package: for a robot file (URDF, SDFormat, MJCF), not "
                    "a scene or parts (a scene's robot entry takes \"packages\")"));
    throw Exit{massprops::app::kBadArguments};
  }
  const bool parts = kind == rbsim::InputKind::kMesh && !f.inputs.empty();
  if (rbsim::AnyDropFlag(app) && !parts) {
    massprops::app::PrintError(std::string(
        "--count, --height, --orientation, --seed, --on, --friction, --restitution, --rest-speed, "
        "--separate, --save-scene: for parts dropped (rbsim PART.stl ...), not a scene, a robot or --mesh"));
    throw Exit{massprops::app::kBadArguments};
  }
  if (f.drop.separate && app.count("--parts") == 0) {
    massprops::app::PrintError(std::string("--separate: for an assembly read by its parts: give --parts too"));
    throw Exit{massprops::app::kBadArguments};
  }
  for (const char* flag : {"--unit", "--density", "--mass", "--repair", "--allow-open", "--parts"}) {
    if (app.count(flag) > 0 && !parts && f.mesh.empty()) {
      massprops::app::PrintError(std::string(flag) +
                                 ": for parts (rbsim PART.stl) and --mesh; a scene gives it per body, a robot file per "
                                 "mesh");
      throw Exit{massprops::app::kBadArguments};
    }
  }
}

// The scene of a drop, written out with --save-scene (whole or not at all). @throws Exit.
rbsim::Scene DropSceneOf(const Flags& f, std::vector<std::string>& warnings) {
  rbsim::DropOptions options;
  if (const std::string problem = rbsim::ToDropOptions(f.drop, f.inputs, options); !problem.empty()) {
    massprops::app::PrintError(problem);
    throw Exit{massprops::app::kBadArguments};
  }
  options.load = f.load->Options();
  options.load.num_threads = f.threads;
  if (f.dt) options.dt = *f.dt;
  if (f.duration) options.duration = *f.duration;
  return rbsim::DropScene(options, warnings);
}

// The scene the command line asks for: parts, a scene file, a robot file, or --mesh. @throws
// Exit, or SceneError and the others for a scene that cannot run.
rbsim::Scene SceneOf(const Flags& f, const CLI::App& app, std::vector<std::string>& warnings) {
  const rbsim::InputKind kind = KindOf(f);
  CheckFlagsFit(f, app, kind);
  rbsim::Scene scene;
  if (kind == rbsim::InputKind::kRobot) {
    const std::string& file = f.inputs.front();
    massprops::DetectRobotFormat(file);  // names the file when it is no robot description
    rbsim::RobotFileOptions robot = f.robot;
    for (const std::string& p : f.packages) {
      const auto mapping = massprops::PackageMapping(p);
      if (!mapping) {
        massprops::app::PrintError(std::string("--package takes NAME=DIR, got '") + p + "'");
        throw Exit{massprops::app::kBadArguments};
      }
      robot.packages.push_back(*mapping);
    }
    scene = rbsim::RobotScene(file, robot);
  } else if (kind == rbsim::InputKind::kScene) {
    scene = rbsim::LoadScene(f.inputs.front(), warnings);
  } else if (!f.inputs.empty()) {
    scene = DropSceneOf(f, warnings);
  } else {
    scene = MeshScene(f, warnings);
  }
  ApplyOverrides(f, scene, warnings);
  if (!f.drop.save_scene.empty()) {
    try {
      massprops::report::CheckOutputPath(f.drop.save_scene, f.inputs);
      massprops::report::WriteFileAtomically(f.drop.save_scene, rbsim::DropSceneJson(scene));
    } catch (const std::exception& e) {
      massprops::app::PrintError(std::string("--save-scene ") + e.what());
      throw Exit{1};
    }
  }
  return scene;
}

bool Wants(const rbsim::Scene& scene, rbsim::OutputKind k) {
  return std::find(scene.outputs.begin(), scene.outputs.end(), k) != scene.outputs.end();
}

// Whole or nothing: the .glb, the page and the plots are made in a staging folder, the trajectory
// files under temporary names; only when every one succeeded are they all renamed into place.
// Returns the files written. @throws Exit (1) when one could not be written.
std::vector<std::string> WriteOutputs(const Flags& f, const rbsim::Simulation& sim, const rbsim::Recording& recording,
                                      rbsim::TrajectoryWriter* writer, const rbsim::RunStats& stats) {
  std::vector<std::string> written;
  const std::string& out_dir = f.out_dir;
  const std::string staging = out_dir + "/.rbsim-staging-" + std::to_string(::getpid());
  try {
    std::vector<std::pair<std::string, std::string>> staged;  // (made, final)
    auto stage = [&](const char* name) {
      std::filesystem::create_directories(staging);
      staged.emplace_back(staging + "/" + name, out_dir + "/" + name);
      return staged.back().first;
    };
    const rbsim::Scene& scene = sim.scene;
    if (!out_dir.empty() && Wants(scene, rbsim::OutputKind::kGlb))
      rbsim::WriteGlb(stage("animation.glb"), sim, recording);
    if (!out_dir.empty() && Wants(scene, rbsim::OutputKind::kHtml)) rbsim::WriteHtml(stage("run.html"), sim, recording);
    for (auto [kind, name] :
         {std::pair{rbsim::OutputKind::kPlotSvg, "plot.svg"}, std::pair{rbsim::OutputKind::kPlotPng, "plot.png"}}) {
      if (!out_dir.empty() && Wants(scene, kind)) rbsim::WritePlot(stage(name), sim, recording);
    }
    if (!out_dir.empty() && scene.until_rest) {
      massprops::report::WriteFileAtomically(stage("summary.json"), rbsim::RestJson(sim, stats));
    }
    if (writer) written = writer->Commit();
    for (const auto& [from, to] : staged) {
      std::filesystem::rename(from, to);
      written.push_back(to);
    }
  } catch (const std::exception& e) {
    std::error_code ec;
    std::filesystem::remove_all(staging, ec);
    massprops::app::PrintError(std::string(e.what()) + "; no output files were written");
    throw Exit{1};
  }
  if (!out_dir.empty()) {
    std::error_code ec;
    std::filesystem::remove_all(staging, ec);
  }
  return written;
}

// The trajectory writer for --out (none without it). @throws Exit (1) naming the folder.
std::unique_ptr<rbsim::TrajectoryWriter> WriterFor(const Flags& f, const rbsim::Simulation& sim) {
  if (f.out_dir.empty()) return nullptr;
  try {
    std::filesystem::create_directories(f.out_dir);
    return std::make_unique<rbsim::TrajectoryWriter>(f.out_dir, sim.scene.outputs, !sim.world().joints().empty());
  } catch (const std::exception& e) {
    massprops::app::PrintError(std::string("--out ") + f.out_dir + ": " + e.what());
    throw Exit{1};
  }
}

// Runs to the end, sampling into the writer and the recording. @throws Exit (1 failed, 130
// interrupted).
rbsim::RunStats RunScene(const Flags& f, rbsim::Simulation& sim, rbsim::TrajectoryWriter* writer,
                         rbsim::Recording* recording) {
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  rbsim::RunStats stats;
  try {
    massprops::app::Progress progress("rbsim", "", !f.quiet);
    stats = rbsim::Run(
        sim,
        [&](const dynamics::World& world, const dynamics::Diagnostics& d) {
          if (writer) writer->Add(sim, world, d);
          if (recording) recording->Add(sim, world, d);
        },
        [&progress](double fraction) { progress.Fraction(fraction); }, &g_stop,
        [&](std::int64_t step) {
          if (writer) writer->AddStep(sim, step);
        });
  } catch (const std::exception& e) {
    massprops::app::PrintError(sim.scene.file + ": " + e.what() + "; no output files were written");
    throw Exit{1};
  }
  if (stats.interrupted) {
    std::cerr << "rbsim: interrupted at t = " << sim.world().time() << " s; no output files were written\n";
    throw Exit{130};
  }
  return stats;
}

// Builds, runs and writes a valid scene; the exit status.
int Simulate(const Flags& f, const rbsim::Scene& scene, std::vector<std::string>& warnings) {
  const bool plot =
      !f.out_dir.empty() && (Wants(scene, rbsim::OutputKind::kPlotSvg) || Wants(scene, rbsim::OutputKind::kPlotPng));
  if (plot && !rbsim::HaveGnuplot()) {
    massprops::app::PrintError(std::string(
        "--outputs: the plot needs gnuplot, which is not on the PATH (apt-get install gnuplot-nox), or leave "
        "svg and png out of the outputs"));
    return 1;
  }
  std::optional<rbsim::Simulation> sim;
  try {
    sim.emplace(rbsim::BuildSimulation(scene, warnings, f.threads));
  } catch (const std::exception& e) {
    FlushWarnings(warnings);
    massprops::app::PrintError(e.what());
    return 1;
  }
  FlushWarnings(warnings);
  if (!f.out_dir.empty() && Wants(scene, rbsim::OutputKind::kGlb)) {
    std::int64_t triangles = 0;
    for (const auto& b : sim->bodies) triangles += b.display.F.rows();
    if (triangles > 2000000) {
      std::cerr
          << "warning: the .glb will carry " << triangles << " triangles (about " << triangles * 72 / 1000000
          << " MB of vertices); viewers may be slow: decimate the mesh for viewing, or leave glb out of --outputs\n";
    }
  }
  std::unique_ptr<rbsim::TrajectoryWriter> writer = WriterFor(f, *sim);
  rbsim::Recording recording;
  const bool record =
      !f.out_dir.empty() && (plot || Wants(scene, rbsim::OutputKind::kGlb) || Wants(scene, rbsim::OutputKind::kHtml));
  recording.contacts = Wants(scene, rbsim::OutputKind::kHtml);
  const rbsim::RunStats stats = RunScene(f, *sim, writer.get(), record ? &recording : nullptr);
  if (scene.until_rest) {  // the resting poses under the page's plots
    std::istringstream lines(rbsim::RestReport(*sim, stats));
    for (std::string line; std::getline(lines, line);) recording.notes.push_back(line.substr(2));
  }
  const std::vector<std::string> written = WriteOutputs(f, *sim, recording, writer.get(), stats);
  for (const std::string& fell : stats.fell_through) std::cerr << "warning: " << massprops::app::OneLine(fell) << "\n";
  std::cout << rbsim::Summary(*sim, stats);
  if (scene.until_rest) std::cout << rbsim::RestReport(*sim, stats);
  if (f.out_dir.empty()) {
    std::cout << "  (no --out DIR: no trajectory, plot or .glb written)\n";
  } else {
    for (const auto& p : written) std::cout << "  wrote " << p << "\n";
  }
  return 0;
}

}  // namespace

// rbsim's threads (the drops of `rbsim poses`, the contact workers) allocate small blocks side by
// side: each gets its own malloc arena (apps/common/large_pages.cpp).
extern "C" const bool massprops_app_one_arena = false;

namespace {

// rbsim on parts, a scene, a robot file or --mesh.
int SimulateMain(int argc, char** argv) {
  CLI::App app{
      "rbsim: simulate rigid bodies made from mesh files, with trajectory, diagnostics, plot and an "
      "animated .glb.\nParts dropped: docs/scenes.md ('The `rbsim` command'); scene files: docs/scenes.md ('rbsim "
      "scenes'); robot files: docs/robots.md."};
  app.set_version_flag("--version", std::string("rbsim ") + massprops::kVersion);
  Flags f;
  DeclareMeshFlags(app, f, DeclareSceneFlags(app, f));
  DeclareRunFlags(app, f);
  rbsim::DeclareDropFlags(app, f.drop);
  massprops::app::LoadFlags threads(app, {"threads"});
  threads.Flag("threads")->default_str("1");
  if (const int status = massprops::app::ParseArguments(app, argc, argv); status >= 0) return status;
  if (threads.Given("threads")) f.threads = threads.Options().num_threads;
  if (f.inputs.empty() && f.mesh.empty()) {
    massprops::app::PrintError(
        std::string("arguments: give mesh files to drop, a scene file, a robot file, or --mesh FILE to spin one "
                    "part (see --help)"));
    return massprops::app::kBadArguments;
  }
  std::vector<std::string> warnings;
  try {
    rbsim::Scene scene;
    try {
      scene = SceneOf(f, app, warnings);
    } catch (const Exit&) {
      throw;
    } catch (const std::exception& e) {
      FlushWarnings(warnings);
      massprops::app::PrintError(e.what());
      return 1;
    }
    FlushWarnings(warnings);
    return Simulate(f, scene, warnings);
  } catch (const Exit& e) {
    return e.status;
  }
}

}  // namespace

int main(int argc, char** argv) {
  return massprops::app::Dispatch(argc, argv, {{"poses", rbsim::PosesMain}}, SimulateMain);
}
