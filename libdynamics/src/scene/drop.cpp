// The definitions of scene/drop.h: parts dropped and run until they rest.

#include "scene/drop.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

#include <nlohmann/json.hpp>

#include "massprops/io/load.h"
#include "massprops/report/words.h"

namespace scene {
namespace {

using massprops::VertexMatrix;

// A part as read: its vertices in metres about its center of mass, in its file's axes.
struct PartShape {
  std::string path;  // absolute
  VertexMatrix V;
  double radius = 0;  // farthest corner from the center of mass
  Vector3 com = Vector3::Zero();
  Vector3 low = Vector3::Zero(), high = Vector3::Zero();  // file bounds, metres
  struct Member {  // with LoadOptions::parts: each part's name and center of mass (metres, file axes)
    std::string name;
    Vector3 com;
  };
  std::vector<Member> members;
};

PartShape ReadPart(const std::string& file, const massprops::LoadOptions& load, const massprops::Vocabulary& words) {
  const std::filesystem::path path = std::filesystem::absolute(file).lexically_normal();
  if (const std::string problem = MeshFileProblem(path); !problem.empty()) {
    throw SceneError(file + ": " + problem);
  }
  massprops::LoadOptions o = load;
  o.full_check = true;  // the whole surface, to place it
  massprops::SolidResult r;
  try {
    r = massprops::LoadSolid(path.string(), o);
  } catch (const std::exception& e) {
    throw SceneError(massprops::WordedError(e, words));
  }
  if (!r.validity.valid) {
    throw SceneError(file + ": the inertia is not that of a real body (" + r.validity.reason + ")");
  }
  PartShape p;
  p.path = path.string();
  p.com = r.mp.center_of_mass;
  for (const massprops::SolidResult& part : r.parts) p.members.push_back({part.part, part.mp.center_of_mass});
  const double scale = massprops::MetresPerUnit(r.unit);
  p.V = r.loaded.mesh.V * scale;
  p.low = p.V.colwise().minCoeff().transpose();
  p.high = p.V.colwise().maxCoeff().transpose();
  p.V.rowwise() -= p.com.transpose();
  p.radius = p.V.rows() > 0 ? p.V.rowwise().norm().maxCoeff() : 0.0;
  return p;
}

// A unit quaternion that the scene reader's normalization keeps bit for bit (it normalizes what
// it reads; repeated until nothing changes, so that a saved drop reads back the same bits).
Quaternion Settled(Quaternion q) {
  for (int i = 0; i < 8; ++i) {
    const double largest = q.coeffs().cwiseAbs().maxCoeff();
    const Quaternion next = Quaternion(q.w() / largest, q.x() / largest, q.y() / largest, q.z() / largest).normalized();
    if (next.coeffs() == q.coeffs()) break;
    q = next;
  }
  return q;
}

// Uniformly random rotations (Shoemake's subgroup algorithm) from 53-bit draws of a seeded
// Mersenne twister: the same seed, the same rotations on every platform.
class RandomRotations {
 public:
  explicit RandomRotations(std::uint64_t seed) : rng_(seed) {}
  Quaternion Next() {
    const double u1 = Uniform(), u2 = 2 * massprops::kPi * Uniform(), u3 = 2 * massprops::kPi * Uniform();
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    return Quaternion(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3));
  }

 private:
  double Uniform() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }
  std::mt19937_64 rng_;
};

Quaternion StartOrientation(const DropOptions& o, RandomRotations& random) {
  switch (o.orientation) {
    case DropOrientation::kRandom: return Settled(random.Next());
    case DropOrientation::kAxisAngle: return Settled(Quaternion(Eigen::AngleAxisd(o.angle, o.axis.normalized())));
    case DropOrientation::kFile: break;
  }
  return Quaternion::Identity();
}

// The lowest point of a part turned by q, relative to its center of mass.
double Lowest(const PartShape& p, const Quaternion& q) {
  const Vector3 up = q.conjugate() * Vector3::UnitZ();  // world +z in the part's axes
  return p.V.rows() > 0 ? (p.V * up).minCoeff() : 0.0;
}

// Where the grid's cells go: `columns` × `rows` a layer, centred on `centre`, layers `cell` apart.
struct Layout {
  int columns = 1, rows = 1;
  double cell = 0;
  Vector3 centre = Vector3::Zero();  // z: the first layer's floor
  Vector3 Cell(int k) const {
    const int per_layer = columns * rows;
    const int layer = k / per_layer, in_layer = k % per_layer;
    const int c = in_layer % columns, r = in_layer / columns;
    return centre + Vector3((c - 0.5 * (columns - 1)) * cell, (r - 0.5 * (rows - 1)) * cell, layer * cell);
  }
};

Layout LayoutFor(int n, double cell, const std::optional<PartShape>& on, double height) {
  Layout l;
  l.cell = cell;
  if (on) {  // as many as fit inside its footprint, in layers above its top
    const Vector3 size = on->high - on->low;
    l.columns = std::max(1, static_cast<int>(size.x() / cell));
    l.rows = std::max(1, static_cast<int>(size.y() / cell));
    l.columns = std::min(l.columns, n);
    l.rows = std::min(l.rows, (n + l.columns - 1) / l.columns);
    l.centre = Vector3(0.5 * (on->low.x() + on->high.x()), 0.5 * (on->low.y() + on->high.y()), on->high.z() + height);
  } else {
    l.columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    l.rows = (n + l.columns - 1) / l.columns;
    l.centre = Vector3(0, 0, height);
  }
  return l;
}

ShapeSpec MeshShape(const std::string& path, const massprops::LoadOptions& load, int part = -1) {
  ShapeSpec s;
  s.source = dynamics::MeshSource{path, load.repair, load.allow_open, load.parts, part};
  s.unit = load.unit;
  s.unit_stated = load.unit_stated;
  s.mass = load.mass;
  return s;
}

void CheckOptions(const DropOptions& o) {
  if (o.files.empty()) throw SceneError("rbsim: no part to drop");
  if (o.count < 1) throw SceneError("--count: must be 1 or more");
  if (o.separate && !o.load.parts) throw SceneError("--separate: for an assembly read by its parts (--parts)");
  if (!(o.height >= 0) || !std::isfinite(o.height)) throw SceneError("--height: must be a finite length >= 0");
  if (o.orientation == DropOrientation::kAxisAngle && !(o.axis.norm() > 0)) {
    throw SceneError("--orientation: the axis must not be the zero vector");
  }
}

}  // namespace

Scene DropScene(const DropOptions& o, std::vector<std::string>& warnings) {
  CheckOptions(o);
  std::vector<PartShape> parts;
  const massprops::Vocabulary& words = o.words ? *o.words : massprops::report::CliVocabulary();
  for (const std::string& f : o.files) parts.push_back(ReadPart(f, o.load, words));
  std::optional<PartShape> on;
  if (!o.on.empty()) on = ReadPart(o.on, o.load, words);
  Scene scene;
  scene.file = "<command line>";
  scene.dt = o.dt;
  scene.duration = o.duration;
  scene.outputs = DefaultOutputs();
  scene.until_rest = o.rest;
  scene.words = &words;
  // A part sleeps once it meets the rest rule (a pile settles from the bottom up): it costs
  // nothing until something wakes it.
  scene.contact.sleeping = true;
  scene.contact.sleep_speed = o.rest.speed;
  scene.contact.sleep_time = o.rest.hold;
  scene.contact_given = true;
  scene.forces.push_back(ForceSpec{});  // gravity, the scenes' default g
  scene.forces.back().vector = Vector3(0, 0, -9.80665);
  scene.forces.back().field = "forces[0]";
  GroundSpec ground;
  ground.offset = on ? on->low.z() : 0.0;
  ground.material = o.material;
  scene.grounds.push_back(ground);
  if (on) {
    StaticSpec st;
    st.name = std::filesystem::path(o.on).stem().string();
    st.field = "static[0]";
    st.shape = MeshShape(on->path, o.load);
    st.collision.kind = CollisionKind::kItself;
    st.collision.material = o.material;
    scene.statics.push_back(std::move(st));
  }
  double radius = 0;
  for (const PartShape& p : parts) radius = std::max(radius, p.radius);
  const int n = static_cast<int>(parts.size()) * o.count;
  const double cell = 2 * radius + std::max(o.height, 0.05 * radius);
  const Layout layout = LayoutFor(n, cell, on, o.height);
  RandomRotations random(o.seed);
  for (int k = 0; k < n; ++k) {
    const PartShape& p = parts[static_cast<std::size_t>(k / o.count)];
    const std::string stem = std::filesystem::path(o.files[static_cast<std::size_t>(k / o.count)]).stem().string();
    const std::string name = o.count > 1 ? stem + "#" + std::to_string(k % o.count + 1) : stem;
    const Quaternion q = StartOrientation(o, random);
    Vector3 at = layout.Cell(k);                        // where the file's (or assembly's) center of mass starts
    if (n == 1 && !on) at.head<2>() = p.com.head<2>();  // one part: dropped from where its file puts it
    at.z() -= Lowest(p, q);
    const bool separate = o.separate && !p.members.empty();
    for (std::size_t m = 0; m < (separate ? p.members.size() : 1); ++m) {
      BodySpec b;
      b.name = separate ? name + "/" + p.members[m].name : name;
      for (const BodySpec& other : scene.bodies)
        if (other.name == b.name) b.name += "@" + std::to_string(scene.bodies.size() + 1);
      b.field = "bodies[" + std::to_string(scene.bodies.size()) + "]";
      b.shape = MeshShape(p.path, o.load, separate ? static_cast<int>(m) : -1);
      b.orientation = q;
      b.position = separate ? Vector3(at + q * (p.members[m].com - p.com)) : at;  // a part where the file has it
      b.collision.kind = CollisionKind::kItself;
      b.collision.material = o.material;
      scene.bodies.push_back(std::move(b));
    }
  }
  CheckTiming(scene, warnings);
  return scene;
}

namespace {

nlohmann::json MaterialJson(const dynamics::Material& m) {
  return {
      {"static_friction", m.static_friction}, {"kinetic_friction", m.kinetic_friction}, {"restitution", m.restitution}};
}

nlohmann::json ShapeJson(const ShapeSpec& s) {
  nlohmann::json j;
  const auto& mesh = std::get<dynamics::MeshSource>(s.source);
  j["mesh"] = mesh.path;
  if (s.unit_stated) j["unit"] = massprops::UnitName(s.unit);
  if (const auto* m = std::get_if<massprops::TotalMass>(&s.mass)) {
    j["mass"] = m->value;
  } else {
    j["density"] = std::get<massprops::Density>(s.mass).value;
  }
  if (mesh.repair) j["repair"] = true;
  if (mesh.allow_open) j["allow_open"] = true;
  if (mesh.parts) j["parts"] = true;
  if (mesh.part >= 0) j["part"] = mesh.part;
  return j;
}

}  // namespace

std::string DropSceneJson(const Scene& scene) {
  nlohmann::json j;
  j["description"] = "rbsim: parts dropped until they rest (rbsim --save-scene)";
  j["dt"] = scene.dt;
  j["duration"] = scene.duration;
  if (scene.until_rest) j["until_rest"] = {{"speed", scene.until_rest->speed}, {"hold", scene.until_rest->hold}};
  j["contact"] = {{"sleeping", scene.contact.sleeping},
                  {"sleep_speed", scene.contact.sleep_speed},
                  {"sleep_time", scene.contact.sleep_time}};
  j["forces"] = nlohmann::json::array();
  for (const ForceSpec& f : scene.forces) {
    j["forces"].push_back({{"type", "gravity"}, {"g", {f.vector.x(), f.vector.y(), f.vector.z()}}});
  }
  for (const GroundSpec& g : scene.grounds) {
    j["ground"] = {{"normal", {g.normal.x(), g.normal.y(), g.normal.z()}},
                   {"offset", g.offset},
                   {"material", MaterialJson(g.material)}};
  }
  j["bodies"] = nlohmann::json::array();
  for (const BodySpec& b : scene.bodies) {
    nlohmann::json body = ShapeJson(b.shape);
    body["name"] = b.name;
    body["position"] = {b.position->x(), b.position->y(), b.position->z()};
    body["orientation"] = {b.orientation.w(), b.orientation.x(), b.orientation.y(), b.orientation.z()};
    body["collision"] = "itself";
    body["material"] = MaterialJson(b.collision.material);
    j["bodies"].push_back(std::move(body));
  }
  for (const StaticSpec& st : scene.statics) {
    nlohmann::json s = ShapeJson(st.shape);
    s["name"] = st.name;
    s["collision"] = "itself";
    s["material"] = MaterialJson(st.collision.material);
    j["static"].push_back(std::move(s));
  }
  return j.dump(2) + "\n";
}

std::vector<RestingPose> RestingPoses(const Simulation& sim) {
  std::vector<RestingPose> out;
  const double floor = sim.scene.grounds.empty() ? 0.0 : sim.scene.grounds.front().offset;
  for (std::size_t k = 0; k < sim.bodies.size() && k < sim.world().bodies().size(); ++k) {
    const SimBody& body = sim.bodies[k];
    const dynamics::RigidBody& rb = sim.world().bodies()[k];
    const BodyState st = StateOf(body, rb);
    const Matrix3 R = st.orientation.toRotationMatrix();  // part axes → world
    RestingPose p;
    p.name = body.name;
    p.down_in_part = R.transpose() * -Vector3::UnitZ();
    p.com_height = st.position.z() - floor;
    p.tilt = std::acos(std::clamp(R(2, 2), -1.0, 1.0));
    const massprops::TriangleMesh& m = body.display;
    const double r = Reach(body);
    p.speed = FastestPointSpeed(rb, r);
    // The corners within 1e-3 of its size of its lowest point: one, on a line, or a face.
    const Eigen::VectorXd z = m.V * R.row(2).transpose();
    const double lowest = z.size() > 0 ? z.minCoeff() : 0.0, tolerance = 2e-3 * r;
    std::vector<Vector3> down;
    for (Eigen::Index v = 0; v < z.size(); ++v)
      if (z[v] <= lowest + tolerance) down.push_back(R * m.V.row(v).transpose());
    // The lowest corner a and the one farthest from it, b: one point, a line, or a face.
    const Vector3 a = down.empty() ? Vector3::Zero() : down.front();  // (none: a body without a mesh)
    Vector3 b = a;
    for (const Vector3& d : down)
      if ((d - a).norm() > (b - a).norm()) b = d;
    p.support = (b - a).norm() <= tolerance ? "corner" : "edge";
    if (p.support == "edge") {
      const Vector3 u = (b - a).normalized();
      for (const Vector3& d : down)
        if (((d - a) - u * u.dot(d - a)).norm() > tolerance) p.support = "face";
    }
    // On the floor on an edge or corner, the center of mass right above it: balanced.
    const bool on_floor = lowest + st.position.z() - floor <= tolerance;
    if (on_floor && p.support != "face") {
      Vector3 off = -a;  // from the support to the center of mass (at the origin here), across
      if ((b - a).norm() > 0) off -= (b - a).normalized() * (b - a).normalized().dot(off);
      p.balanced = std::hypot(off.x(), off.y()) <= 1e-6 * r;
    }
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace scene
