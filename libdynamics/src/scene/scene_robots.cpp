// The scene's "robots": a URDF, SDFormat or MJCF file placed in the world, its base, initial
// joint positions, motors and colliders (docs/robots.md); and the scene of `rbsim ROBOT.urdf`.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "json_fields.h"
#include "scene/scene.h"

#include "massprops/io/mesh_io.h"

namespace scene {

using json_fields::Fields;
using nlohmann::json;

namespace {

constexpr double kDegree = massprops::kPi / 180.0;

// {"joint": number, ...} in SI (`key`) or degrees (`key_deg`), into `out`.
void ReadPositions(Fields& f, const std::string& key, double unit, std::map<std::string, double>& out) {
  const json* v = f.Get(key);
  if (!v) return;
  if (!v->is_object()) f.Fail(key, "must be an object {\"joint name\": number, ...}");
  for (auto it = v->begin(); it != v->end(); ++it) {
    const double x = f.CheckNumber(key + "." + it.key(), it.value(), nullptr);
    if (!out.emplace(it.key(), x * unit).second) f.Fail(key, "joint '" + it.key() + "' is given twice");
  }
}

RobotSpec ReadRobot(const json& j, const std::string& path, const std::string& file, const std::string& base_dir,
                    std::vector<std::string>& warnings, std::set<std::string>& names) {
  Fields f(j, path, file);
  RobotSpec r;
  r.field = path;
  const std::string given = f.String("file", "");
  if (given.empty()) f.Fail("file", "is required: a URDF, SDFormat or MJCF file");
  std::filesystem::path p(given);
  if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
  if (const std::string problem = MeshFileProblem(p); !problem.empty()) f.Fail("file", "'" + given + "' " + problem);
  r.path = p.lexically_normal().string();
  r.name = f.String("name", p.stem().string());
  if (r.name.empty()) f.Fail("name", "must not be empty");
  if (!names.insert(r.name).second) f.Fail("name", "'" + r.name + "' is used by another robot");
  r.fill = f.Bool("fill", false);
  if (f.Has("density") && !r.fill) f.Fail("density", "is for \"fill\": true (the inertials are otherwise as written)");
  r.fill_options.density = f.Number("density", 1000.0, "positive");
  if (const json* packages = f.Get("packages")) {  // {"NAME": "DIR"}, relative to the scene's folder
    if (!packages->is_object()) f.Fail("packages", "must be an object {\"package name\": \"folder\", ...}");
    for (auto it = packages->begin(); it != packages->end(); ++it) {
      if (!it.value().is_string() || it.value().get<std::string>().empty()) {
        f.Fail("packages." + it.key(), "must be a folder's path");
      }
      std::filesystem::path dir(it.value().get<std::string>());
      if (dir.is_relative()) dir = std::filesystem::path(base_dir) / dir;
      std::error_code e;
      if (!std::filesystem::is_directory(dir, e)) {
        f.Fail("packages." + it.key(), "'" + it.value().get<std::string>() + "' is not a folder");
      }
      r.fill_options.packages.emplace_back(it.key(), dir.lexically_normal().string());
    }
  }
  if (f.Has("position")) {
    r.position_given = true;
    r.options.pose.translation = f.Vec3("position", Vector3::Zero());
  }
  f.Get("position");
  r.options.pose.rotation = ReadOrientation(f, "orientation", warnings).toRotationMatrix();
  const std::string base = f.String("base", "as_written", {"as_written", "fixed", "floating"});
  r.options.base = base == "fixed"      ? dynamics::RobotOptions::Base::kFixed
                   : base == "floating" ? dynamics::RobotOptions::Base::kFloating
                                        : dynamics::RobotOptions::Base::kAsWritten;
  ReadPositions(f, "positions", 1.0, r.options.positions);
  std::map<std::string, double> degrees;
  ReadPositions(f, "positions_deg", kDegree, degrees);
  for (const auto& [name, q] : degrees) {
    if (!r.options.positions.emplace(name, q).second) {
      f.Fail("positions_deg", "joint '" + name + "' is also in 'positions'");
    }
  }
  if (const json* m = f.Get("motors")) {
    if (!m->is_object()) f.Fail("motors", "must be an object {\"joint name\": {motor}, ...}");
    for (auto it = m->begin(); it != m->end(); ++it) {
      Fields o(it.value(), f.Path("motors") + "." + it.key(), file);
      r.options.motors[it.key()] = ReadMotor(o, true);
    }
  }
  r.options.keyframe = f.String("keyframe", "");  // an MJCF <key>'s name: qpos, qvel, ctrl
  const std::string collision = f.String("collision", "hull", {"hull", "mesh"});
  r.options.mesh_colliders = collision == "mesh";
  r.material_given = f.Has("material");
  r.options.material = ReadMaterial(f);
  f.Done();
  return r;
}

}  // namespace

std::vector<RobotSpec> ReadRobots(const json& robots, const std::string& file, const std::string& base_dir,
                                  std::vector<std::string>& warnings) {
  if (!robots.is_array()) throw SceneError(file + ": robots: must be an array of robots");
  std::vector<RobotSpec> out;
  std::set<std::string> names;
  for (std::size_t i = 0; i < robots.size(); ++i) {
    out.push_back(ReadRobot(robots[i], "robots[" + std::to_string(i) + "]", file, base_dir, warnings, names));
  }
  return out;
}

namespace {

// The name of an XML document's root element, read from its first 64 KiB past a byte-order mark,
// the declaration, comments, processing instructions and a DOCTYPE; "" when it is not XML.
std::string RootElement(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(65536, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  std::size_t i = head.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
  while (true) {
    while (i < head.size() && std::isspace(static_cast<unsigned char>(head[i]))) ++i;
    if (i >= head.size() || head[i] != '<') return "";
    const char* close = head.compare(i, 4, "<!--") == 0 ? "-->"
                        : head.compare(i, 2, "<?") == 0 ? "?>"
                        : head.compare(i, 2, "<!") == 0 ? ">"
                                                        : nullptr;
    if (!close) break;
    const std::size_t end = head.find(close, i + 2);
    if (end == std::string::npos) return "";
    i = end + std::strlen(close);
  }
  std::size_t end = ++i;
  while (end < head.size() && (std::isalnum(static_cast<unsigned char>(head[end])) || head[end] == '_' ||
                               head[end] == ':' || head[end] == '-' || head[end] == '.')) {
    ++end;
  }
  return head.substr(i, end - i);
}

}  // namespace

InputKind ClassifyInput(const std::string& path) {
  std::error_code ec;
  if (path.empty() || !std::filesystem::is_regular_file(path, ec)) return InputKind::kUnknown;
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".json") return InputKind::kScene;
  const std::string root = RootElement(path);
  if (root == "robot" || root == "sdf" || root == "mujoco") return InputKind::kRobot;
  // A robot file by its name whose content is not one: its reader says what is wrong.
  if (ext == ".urdf" || ext == ".sdf" || ext == ".xacro") return InputKind::kRobot;
  if (massprops::IsMeshFile(path)) return InputKind::kMesh;
  return InputKind::kUnknown;
}

bool IsRobotFile(const std::string& path) { return ClassifyInput(path) == InputKind::kRobot; }

Scene RobotScene(const std::string& path, const RobotFileOptions& options) {
  Scene scene;
  scene.file = std::filesystem::absolute(path).lexically_normal().string();  // its messages name the file
  scene.duration = 3.0;
  scene.dt = 1e-3;
  scene.outputs = DefaultOutputs();
  RobotSpec r;
  r.field = "robot";
  r.path = scene.file;
  r.name = std::filesystem::path(path).stem().string();
  r.fill = options.fill;
  r.fill_options.packages = options.packages;
  r.options.base = options.fixed_base ? dynamics::RobotOptions::Base::kFixed : dynamics::RobotOptions::Base::kAsWritten;
  r.options.keyframe = options.keyframe;
  scene.robots.push_back(std::move(r));
  ForceSpec gravity;
  gravity.kind = ForceKind::kGravity;
  gravity.field = "gravity";
  gravity.vector = Vector3(0, 0, -9.81);
  scene.forces.push_back(gravity);
  scene.grounds.push_back(GroundSpec{});
  scene.default_ground = true;
  return scene;
}

}  // namespace scene
