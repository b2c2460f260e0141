// rbsim poses: on which face a part comes to rest, and how often (dynamics/poses.h).
//
//   rbsim poses PART [--unit U] [--density D | --mass M] [--drops N] [--height H] [--seed S]
//                    [--ground MU_S,MU_K,E] [--material MU_S,MU_K,E] [--collision hull|mesh]
//                    [--threads N] [--format table|json|html] [--out DIR]

#include "poses_cli.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bodies/pose_part.h"
#include "cli.h"
#include "dynamics/poses.h"
#include "html.h"
#include "load_flags.h"
#include "massprops/io/load.h"
#include "massprops/report/atomic_file.h"
#include "massprops/report/words.h"
#include "massprops/wording.h"
#include "pose_picture.h"

namespace rbsim {
namespace {

namespace dp = dynamics::poses;
using massprops::Vector3;

// "0.6,0.5,0.2": static friction, kinetic friction, restitution.
bool ParseMaterial(const std::string& text, dynamics::Material& m, std::string& why) {
  double v[3];
  char extra;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &v[0], &v[1], &v[2], &extra) != 3 ||
      !(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]))) {
    why = "expected three numbers MU_S,MU_K,E (static friction, kinetic friction, restitution), got '" + text + "'";
    return false;
  }
  if (const auto fault = dynamics::CheckMaterial(dynamics::Material{v[0], v[1], v[2]})) {
    why = "the " + fault->field + " " + fault->problem + ", got '" + text + "'";
    return false;
  }
  m = dynamics::Material{v[0], v[1], v[2]};
  return true;
}

std::string Vec(const Vector3& v, const char* format = "%+.4f") {
  char b[96];
  std::snprintf(b, sizeof b, "(%s, %s, %s)", format, format, format);
  char out[128];
  std::snprintf(out, sizeof out, b, v.x() + 0.0, v.y() + 0.0, v.z() + 0.0);  // + 0.0: no "-0"
  return out;
}

// The likely poses (at most 12: the quasi-static estimate's and the drops' largest) at rest side by
// side on the plane z = 0, in the run viewer's page: one sample, each pose a body named with its
// share.
std::string PosesPage(const std::string& name, const massprops::TriangleMesh& mesh, const dp::Part& part,
                      const dp::Estimate& estimate, const dp::Tally& tally, bool have_drops) {
  std::vector<std::size_t> order(estimate.poses.size());
  for (std::size_t p = 0; p < order.size(); ++p) order[p] = p;
  auto share = [&](std::size_t p) {
    return have_drops
               ? static_cast<double>(tally.counts[p]) / static_cast<double>(std::max<std::int64_t>(tally.drops, 1))
               : estimate.poses[p].quasi_static;
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return share(a) > share(b); });
  if (order.size() > 12) order.resize(12);
  const Vector3 com = part.mass_properties.center_of_mass;
  massprops::TriangleMesh centred = mesh;  // about the center of mass, as the schema has bodies
  for (Eigen::Index v = 0; v < centred.V.rows(); ++v) centred.V.row(v) -= com.transpose();
  const double size = centred.V.rows() > 0 ? 2 * centred.V.rowwise().norm().maxCoeff() : 1.0;
  const Vector3 palette[] = {{0.85, 0.33, 0.10}, {0.00, 0.45, 0.74}, {0.47, 0.67, 0.19}, {0.49, 0.18, 0.56},
                             {0.93, 0.69, 0.13}, {0.30, 0.75, 0.93}, {0.64, 0.08, 0.18}, {0.50, 0.50, 0.50}};
  nlohmann::json bodies = nlohmann::json::array();
  Eigen::AlignedBox3d bounds;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const dp::Pose& pose = estimate.poses[order[k]];
    const Vector3 at = pose.rotation * com + pose.translation + Vector3(1.5 * size * static_cast<double>(k), 0, 0);
    const Eigen::Quaterniond q(pose.rotation);
    char label[96];
    std::snprintf(label, sizeof label, "pose %zu: %s %.1f %%", order[k] + 1, have_drops ? "drops" : "quasi-static",
                  100 * share(order[k]));
    bodies.push_back(ViewerBody(label, palette[k % 8], centred, {at.cast<float>()},
                                {Eigen::Vector4f(static_cast<float>(q.x()), static_cast<float>(q.y()),
                                                 static_cast<float>(q.z()), static_cast<float>(q.w()))}));
    bounds.extend(at + Vector3::Constant(size / 2));
    bounds.extend(at - Vector3::Constant(size / 2));
  }
  // The plane under them.
  massprops::TriangleMesh plane;
  const double margin = size;
  plane.V.resize(4, 3);
  plane.V << bounds.min().x() - margin, -size - margin, 0, bounds.max().x() + margin, -size - margin, 0,
      bounds.max().x() + margin, size + margin, 0, bounds.min().x() - margin, size + margin, 0;
  plane.F.resize(2, 3);
  plane.F << 0, 1, 2, 0, 2, 3;
  nlohmann::json data;
  data["version"] = 1;
  data["title"] = name + ": resting poses";
  data["up"] = {0, 0, 1};
  data["times"] = {0.0};
  data["bodies"] = std::move(bodies);
  data["statics"] = nlohmann::json::array({ViewerStatic("plane", Vector3(0.8, 0.78, 0.72), plane)});
  data["bounds"] = ViewerBounds(bounds);
  data["diagnostics"] = {{"kinetic", {0.0}}, {"potential", {0.0}}, {"energy_drift", {0.0}}, {"momentum_drift", {0.0}}};
  return ViewerPage("rbsim poses: " + name, data);
}

}  // namespace

namespace {

// The command line of `rbsim poses`, as parsed.
struct PosesFlags {
  std::string part_file, ground_text = "0.6,0.5,0", material_text = "0.6,0.5,0", collision = "hull", format = "table",
                         out_dir;
  std::unique_ptr<massprops::app::LoadFlags> load;  // --unit, --density, --mass, --repair, --threads
  double height = 0.1, dt = 1e-3, max_time = 20;
  std::int64_t drops = 1000;
  std::uint64_t seed = 1;
  bool quiet = false;
};

void DeclarePosesFlags(CLI::App& app, PosesFlags& f) {
  app.add_option("part", f.part_file, "The part: a closed mesh file")->required();
  f.load = std::make_unique<massprops::app::LoadFlags>(
      app, std::initializer_list<std::string_view>{"unit", "density", "mass", "repair", "threads"});
  app.add_option("--drops", f.drops, "Simulated drops (0: the quasi-static estimate only)")
      ->check(CLI::Range(std::int64_t{0}, std::int64_t{100000000}));
  app.add_option("--height", f.height, "Height of the part's lowest point above the plane at release, m")
      ->check(massprops::app::NonNegative());
  app.add_option("--seed", f.seed, "Seed of the drops' orientations (drop k is the same for any batch or thread)");
  app.add_option("--ground", f.ground_text, "The plane's material MU_S,MU_K,E (default 0.6,0.5,0)");
  app.add_option("--material", f.material_text, "The part's material MU_S,MU_K,E (default 0.6,0.5,0)");
  app.add_option("--collision", f.collision, "What the part collides as: its convex hull, or its mesh as it is")
      ->check(CLI::IsMember({"hull", "mesh"}));
  app.add_option("--dt", f.dt, "Time step of the drops, s")->check(massprops::app::Positive());
  app.add_option("--max-time", f.max_time, "Simulated seconds a drop may take to come to rest")
      ->check(massprops::app::Positive());
  app.add_option("--format", f.format,
                 "table, json, or html (a page that shows each likely pose at rest, side by side, in a browser)")
      ->check(CLI::IsMember({"table", "json", "html"}));
  app.add_option("--out", f.out_dir, "Write a picture of each pose (pose_1.svg, ...) and poses.json into this folder");
  app.add_flag("-q,--quiet", f.quiet, "Print only the result (there is no progress display)");
}

// The part through the pipeline (the same checks as massprops), whole (full_check: the hull and
// the pictures need the mesh).
massprops::LoadOptions PartLoadOptions(const PosesFlags& f) { return f.load->Options(); }

// A picture of each pose, named as `pictures` says (a large mesh drawn as its convex hull: one SVG
// polygon a triangle), and poses.json in `out_dir`.
void WritePoseFiles(const std::string& out_dir, const std::string& name, const massprops::TriangleMesh& file_mesh,
                    const dp::Part& part, const dp::Estimate& estimate, const std::vector<std::string>& pictures,
                    const std::string& json) {
  std::filesystem::create_directories(out_dir);
  // A picture is one SVG polygon a triangle: a large mesh is drawn as its convex hull.
  constexpr Eigen::Index kMostTriangles = 100000;
  const bool as_hull = file_mesh.F.rows() > kMostTriangles;
  massprops::TriangleMesh drawn;
  if (as_hull) {
    drawn.V.resize(static_cast<Eigen::Index>(part.hull_vertices.size()), 3);
    drawn.F.resize(static_cast<Eigen::Index>(part.hull_triangles.size()), 3);
    for (std::size_t v = 0; v < part.hull_vertices.size(); ++v)
      drawn.V.row(static_cast<Eigen::Index>(v)) = part.hull_vertices[v].transpose();
    for (std::size_t t = 0; t < part.hull_triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) drawn.F(static_cast<Eigen::Index>(t), k) = part.hull_triangles[t][k];
  }
  for (std::size_t p = 0; p < estimate.poses.size(); ++p) {
    std::ostringstream title;
    title << name << ": pose " << p + 1 << ", resting on the face with normal "
          << Vec(estimate.poses[p].normal, "%+.3f");
    if (as_hull) title << " (its convex hull drawn: the mesh has " << file_mesh.F.rows() << " triangles)";
    std::vector<Vector3> outline;
    for (int v : estimate.poses[p].outline) outline.push_back(part.hull_vertices[static_cast<std::size_t>(v)]);
    WritePosePicture(out_dir + "/" + pictures[p], as_hull ? drawn : file_mesh, estimate.poses[p], outline, title.str());
  }
  massprops::report::WriteFileAtomically(out_dir + "/poses.json", json + "\n");
}

// The table: the part, the drops, each likely pose with its shares and intervals, the rest
// transforms.
void PrintPoses(const PosesFlags& f, const std::string& name, const dynamics::PosesReport& report,
                const dynamics::Material& ground, const dynamics::Material& material, double seconds) {
  const dp::Part& part = report.pose_part;
  const dp::Estimate& estimate = report.estimate;
  const dp::Tally& tally = report.tally;
  const std::int64_t drops = f.drops;
  const double height = f.height, dt = f.dt, max_time = f.max_time;
  const std::uint64_t seed = f.seed;
  const std::string& collision = f.collision;
  const bool have_drops = drops > 0;
  auto drop_share = [&](std::size_t p) {
    return have_drops ? static_cast<double>(tally.counts[p]) / static_cast<double>(tally.drops) : 0.0;
  };
  std::printf("%s: %.6g kg, center of mass %s m; convex hull of %zu faces, %zu stable\n", name.c_str(),
              part.mass_properties.mass, Vec(part.mass_properties.center_of_mass, "%.6g").c_str(),
              estimate.faces.normals.size(), estimate.poses.size());
  if (have_drops) {
    std::printf(
        "drops: %lld from %g m (seed %llu, dt %g s, %s), ground %g/%g/%g, part %g/%g/%g (mu_s/mu_k/e); "
        "%lld not settled in %g s, %lld at rest on no stable face; mean time to rest %.2f s; %.1f s wall\n",
        static_cast<long long>(drops), height, static_cast<unsigned long long>(seed), dt, collision.c_str(),
        ground.static_friction, ground.kinetic_friction, ground.restitution, material.static_friction,
        material.kinetic_friction, material.restitution, static_cast<long long>(tally.not_settled), max_time,
        static_cast<long long>(tally.other_face), tally.mean_time, seconds);
  }
  std::printf("%-5s %-29s %12s %8s %17s %17s %10s\n", "pose", "normal (part axes)", "quasi-static", "drops",
              "95% interval", "joint 95%", "height m");
  // Faceted parts have many tiny stable faces: the table shows the likely ones, JSON has all.
  auto shown = [&](std::size_t p) {
    return p < 12 || estimate.poses[p].quasi_static >= 0.005 || (have_drops && tally.counts[p] > 0);
  };
  std::size_t hidden = 0;
  double hidden_quasi_static = 0;
  for (std::size_t p = 0; p < estimate.poses.size(); ++p) {
    const dp::Pose& pose = estimate.poses[p];
    if (!shown(p)) {
      ++hidden;
      hidden_quasi_static += pose.quasi_static;
      continue;
    }
    if (have_drops) {
      char a[40], b[40];
      std::snprintf(a, sizeof a, "[%.4f, %.4f]", tally.binomial[p].low, tally.binomial[p].high);
      std::snprintf(b, sizeof b, "[%.4f, %.4f]", tally.simultaneous[p].low, tally.simultaneous[p].high);
      std::printf("%-5zu %-29s %12.4f %8.4f %17s %17s %10.4g\n", p + 1, Vec(pose.normal).c_str(), pose.quasi_static,
                  drop_share(p), a, b, pose.height);
    } else {
      std::printf("%-5zu %-29s %12.4f %8s %17s %17s %10.4g\n", p + 1, Vec(pose.normal).c_str(), pose.quasi_static, "-",
                  "-", "-", pose.height);
    }
  }
  if (hidden > 0) {
    std::printf("  ... %zu more stable faces, quasi-static %.4f together, no drop rested on them\n", hidden,
                hidden_quasi_static);
  }
  // The rest transforms of the poses shown: part coordinates → world, the plane z = 0.
  std::printf("rest transforms, x_world = R x_part + t (R as a quaternion w, x, y, z; the plane z = 0):\n");
  for (std::size_t p = 0; p < estimate.poses.size(); ++p) {
    const dp::Pose& pose = estimate.poses[p];
    if (!shown(p)) continue;
    const Eigen::Quaterniond q(pose.rotation);
    std::printf("  pose %-3zu R (%+.6f, %+.6f, %+.6f, %+.6f)  t %s m\n", p + 1, q.w() + 0.0, q.x() + 0.0, q.y() + 0.0,
                q.z() + 0.0, Vec(pose.translation, "%.6g").c_str());
  }
}

}  // namespace

int PosesMain(int argc, char** argv) {
  CLI::App app{
      "rbsim poses: on which face of its convex hull a part comes to rest on a plane, and how often — the "
      "quasi-static estimate (solid angles from the center of mass and the topple graph) and N simulated drops from "
      "uniformly random orientations, with 95 % intervals (docs/scenes.md ('Resting poses')).",
      "rbsim poses"};
  PosesFlags f;
  DeclarePosesFlags(app, f);
  if (const int status = massprops::app::ParseArguments(app, argc, argv); status >= 0) return status;
  dynamics::Material ground, material;
  std::string why;
  if (!ParseMaterial(f.ground_text, ground, why)) {
    massprops::app::PrintError(std::string("--ground: ") + why);
    return massprops::app::kBadArguments;
  }
  if (!ParseMaterial(f.material_text, material, why)) {
    massprops::app::PrintError(std::string("--material: ") + why);
    return massprops::app::kBadArguments;
  }
  dynamics::PosesReport report;
  report.part = f.part_file;
  report.collision = f.collision == "mesh" ? dynamics::PoseCollision::kMesh : dynamics::PoseCollision::kHull;
  report.drops = f.drops;
  massprops::TriangleMesh file_mesh;  // the part in its file's axes, metres
  const std::string name = std::filesystem::path(f.part_file).filename().string();
  std::vector<std::string> warnings;
  try {
    report.pose_part =
        dynamics::LoadPosePart(f.part_file, PartLoadOptions(f), report.collision, material,
                               massprops::report::WordsFor(massprops::report::FrontEnd::kPoses), warnings, &file_mesh);
  } catch (const std::exception& e) {
    for (const auto& w : warnings) std::cerr << "warning: " << massprops::app::OneLine(w) << "\n";
    massprops::app::PrintError(e.what());
    return 1;
  }
  for (const auto& w : warnings) std::cerr << "warning: " << massprops::app::OneLine(w) << "\n";
  const dp::Part& part = report.pose_part;
  dp::DropOptions& options = report.options;
  options.height = f.height;
  options.seed = f.seed;
  options.ground = ground;
  options.dt = f.dt;
  options.max_time = f.max_time;
  options.threads = PartLoadOptions(f).num_threads;
  double seconds = 0;
  try {
    report.estimate = dp::QuasiStatic(part);
    const auto start = std::chrono::steady_clock::now();
    const std::vector<dp::DropOutcome> outcomes = dp::Drop(part, report.estimate, options, 0, f.drops);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report.tally = dp::Count(outcomes, report.estimate.poses.size());
  } catch (const std::exception& e) {
    massprops::app::PrintError(f.part_file + ": " + e.what());
    return 1;
  }
  const dp::Estimate& estimate = report.estimate;
  if (!f.out_dir.empty()) {
    for (std::size_t p = 0; p < estimate.poses.size(); ++p)
      report.pictures.push_back("pose_" + std::to_string(p + 1) + ".svg");
  }
  const std::string json = dynamics::PosesJson(report, 2);
  if (!f.out_dir.empty()) {
    try {
      WritePoseFiles(f.out_dir, name, file_mesh, part, estimate, report.pictures, json);
    } catch (const std::exception& e) {
      massprops::app::PrintError(std::string("--out ") + f.out_dir + ": " + e.what());
      return 1;
    }
  }
  if (f.format == "json") {
    std::cout << json << "\n";
    return 0;
  }
  if (f.format == "html") {
    std::cout << PosesPage(name, file_mesh, part, estimate, report.tally, f.drops > 0);
    return 0;
  }
  PrintPoses(f, name, report, ground, material, seconds);
  if (f.out_dir.empty()) std::printf("(a picture of each pose: --out DIR)\n");
  if (!f.out_dir.empty())
    std::printf("  wrote %s/pose_1.svg ... pose_%zu.svg, poses.json\n", f.out_dir.c_str(), estimate.poses.size());
  return 0;
}

}  // namespace rbsim
