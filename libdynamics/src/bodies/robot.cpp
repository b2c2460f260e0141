// Robots in a world (robot.h): links lumped by fixed joints into bodies, their colliders, and the
// joints between the bodies.

#include "bodies/robot.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "massprops/repair/repair.h"
#include "massprops/units.h"
#include "robot_constraints.h"

namespace dynamics {
namespace {

using internal::FrameOf;
using massprops::Placement;
using massprops::RobotJoint;
using massprops::RobotJointType;
using massprops::RobotModel;

// A group of links welded together (by fixed joints between links): one body.
struct Group {
  int root = 0;                    // its topmost link
  std::vector<int> links;          // in model order
  std::vector<Placement> in_root;  // each link's frame in the root link's frame
  double mass = 0;
  Vector3 com = Vector3::Zero();      // root link frame
  Matrix3 inertia = Matrix3::Zero();  // about com, root link axes
  Placement body_in_root;             // the body frame (principal axes at com) in the root link frame
  Vector3 moments = Vector3::Zero();
};

Quaternion QuaternionOf(const Matrix3& R) { return Quaternion(R).normalized(); }

// A geometry's points (metres, its own frame) and, for a mesh, its triangles.
struct Points {
  std::vector<Vector3> vertices;
  std::vector<std::array<int, 3>> triangles;
};

// A mesh collider needs a closed, oriented surface (its signed distance field); a hull needs only
// the points. A mesh that is no solid as written (repeated faces, a hole) still gives its hull,
// with a note naming the link and the file; as a mesh collider it is repaired, or refused.
massprops::TriangleMesh ReadCollisionMesh(const massprops::RobotGeometry& g, const massprops::RobotMesh& m,
                                          const massprops::LoadOptions& load, bool hull, double& metres,
                                          std::vector<std::string>& notes) {
  massprops::LoadOptions options = load;
  options.mass = massprops::Density{1.0};
  try {
    const massprops::SolidResult r = massprops::LoadSolid(m.path, options);
    metres = massprops::MetresPerUnit(r.unit);
    return massprops::Triangulate(r.loaded.mesh);
  } catch (const massprops::LoadError& e) {  // read, but no solid as it stands (a malformed file is thrown on)
    if (!hull) {
      if (options.repair)
        throw std::invalid_argument(g.where + ": a mesh collider needs a closed surface: " + e.what());
      options.repair = true;
      try {
        const massprops::SolidResult r = massprops::LoadSolid(m.path, options);
        metres = massprops::MetresPerUnit(r.unit);
        notes.push_back(g.where + ": " + m.path + " repaired for its mesh collider (" + e.what() + ")");
        return massprops::Triangulate(r.loaded.mesh);
      } catch (const std::exception& again) {
        throw std::invalid_argument(g.where + ": a mesh collider needs a closed surface, and " + m.path +
                                    " could not be repaired: " + again.what());
      }
    }
    // Its points are all the hull takes.
    const massprops::LoadedMesh read = massprops::ReadMeshFile(m.path);
    metres = massprops::MetresPerUnit(read.declared_unit && !load.unit_stated ? *read.declared_unit : load.unit);
    notes.push_back(g.where + ": " + e.what() + " — it collides as the convex hull of its points, which needs no more");
    return massprops::Triangulate(read.mesh);
  }
}

// As ReadCollisionMesh, every other fault named by the link and geometry as well as the file.
massprops::TriangleMesh ReadCollisionMeshNamed(const massprops::RobotGeometry& g, const massprops::RobotMesh& m,
                                               const massprops::LoadOptions& load, bool hull, double& metres,
                                               std::vector<std::string>& notes) {
  try {
    return ReadCollisionMesh(g, m, load, hull, metres, notes);
  } catch (const std::invalid_argument&) {
    throw;  // (named already)
  } catch (const std::exception& e) {
    throw std::invalid_argument(g.where + ": " + e.what());
  }
}

// A mesh's points in metres (`metres` per its unit) scaled by `axes`, with its triangles.
Points PointsFrom(const massprops::TriangleMesh& mesh, double metres, const Vector3& axes) {
  Points out;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    out.vertices.push_back(metres * Vector3(mesh.V.row(i).transpose()).cwiseProduct(axes));
  }
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    out.triangles.push_back(
        {static_cast<int>(mesh.F(f, 0)), static_cast<int>(mesh.F(f, 1)), static_cast<int>(mesh.F(f, 2))});
  }
  if (axes.prod() < 0) {
    for (auto& t : out.triangles) std::swap(t[1], t[2]);  // a mirroring scale turns the faces inside out
  }
  return out;
}

// A geometry's points (metres, its own frame) and, for a mesh, its triangles.
Points PointsOf(const massprops::RobotGeometry& g, const RobotOptions& options, std::vector<std::string>& notes) {
  massprops::TriangleMesh mesh;
  double scale = 1;
  Vector3 axes = Vector3::Ones();
  if (const auto* p = std::get_if<massprops::Primitive>(&g.shape)) {
    mesh = massprops::Tessellate(*p, 24);
  } else {
    const auto& m = std::get<massprops::RobotMesh>(g.shape);
    mesh = ReadCollisionMeshNamed(g, m, options.load, !options.mesh_colliders, scale, notes);
    axes = m.scale;
  }
  return PointsFrom(mesh, scale, axes);
}

// A collision geometry of a group, placed in the group's body frame, with its points (each mesh
// read once: the collider and the drawn shape both take them from here).
struct PlacedGeometry {
  const massprops::RobotGeometry* geometry;
  Placement pose;
  Points points;
};

std::vector<PlacedGeometry> GeometriesOf(const RobotModel& model, const Group& g, const RobotOptions& options,
                                         std::vector<std::string>& notes) {
  std::vector<PlacedGeometry> out;
  const Placement root_to_body = g.body_in_root.Inverse();
  for (std::size_t k = 0; k < g.links.size(); ++k) {
    for (const auto& geometry : model.links[static_cast<std::size_t>(g.links[k])].collisions) {
      out.push_back(
          {&geometry, root_to_body.Then(g.in_root[k]).Then(geometry.pose), PointsOf(geometry, options, notes)});
    }
  }
  return out;
}

// A friction the file gives (MJCF), MuJoCo's way: one coefficient, mixed by the larger.
Material FileFriction(double mu, double restitution) { return Material{mu, mu, restitution, true}; }

// A geometry's material: the file's friction (MJCF: MuJoCo's, mixed by the larger) with the
// options' restitution, else the options' material.
Material MaterialOf(const massprops::RobotGeometry& geometry, const RobotOptions& options) {
  if (!geometry.friction) return options.material;
  return FileFriction(*geometry.friction, options.material.restitution);
}

// One collision geometry as a collider in the body frame: a primitive as itself, a mesh as its
// convex hull, or as the mesh itself (a signed distance field) when asked.
Collider GeometryCollider(const PlacedGeometry& placed, const RobotOptions& options) {
  Collider c;
  c.material = MaterialOf(*placed.geometry, options);
  c.rotation = placed.pose.rotation;
  c.translation = placed.pose.translation;
  c.filter = {placed.geometry->contype, placed.geometry->conaffinity};
  if (const auto* p = std::get_if<massprops::Primitive>(&placed.geometry->shape)) {
    if (const auto* box = std::get_if<massprops::primitive::Box>(p)) {
      c.shape = shape::Box{box->size / 2};
      return c;
    }
    if (const auto* s = std::get_if<massprops::primitive::Sphere>(p)) {
      c.shape = shape::Sphere{s->radius};
      return c;
    }
    if (const auto* s = std::get_if<massprops::primitive::Capsule>(p)) {
      c.shape = shape::Capsule{s->radius, s->length / 2};
      return c;
    }
    if (const auto* s = std::get_if<massprops::primitive::Cylinder>(p)) {
      c.shape = shape::Cylinder{s->radius, s->height / 2};
      return c;
    }
  }
  if (options.mesh_colliders && std::holds_alternative<massprops::RobotMesh>(placed.geometry->shape)) {
    c.shape = MakeMesh(placed.points.vertices, placed.points.triangles);
    return c;
  }
  // The convex hull of its points (an ellipsoid's tessellation, a mesh), in its own frame.
  massprops::PolygonMesh cloud;
  const std::vector<Vector3>& points = placed.points.vertices;
  cloud.V.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) cloud.V.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  std::vector<int> corners(points.size());
  std::iota(corners.begin(), corners.end(), 0);
  cloud.AddFace(corners);  // (the hull takes the corners of faces)
  c.shape = ConvexOf(massprops::ConvexHull(cloud));
  return c;
}

// The collider of a group in its body frame (none: no collision geometry): its one geometry, or
// a compound of them all, each colliding on its own as the file gives it.
std::optional<Collider> ColliderOf(const std::vector<PlacedGeometry>& geometries, const RobotOptions& options) {
  if (geometries.empty()) return std::nullopt;
  if (geometries.size() == 1) return GeometryCollider(geometries.front(), options);
  Collider c;
  c.material = options.material;
  c.filter = {~0u, ~0u};  // every bit: each part's own decide (a part's filter is ANDed with this)
  shape::Compound compound;
  for (const PlacedGeometry& placed : geometries) {
    compound.parts.push_back(GeometryCollider(placed, options));
    if (placed.geometry->friction) compound.part_materials = true;
  }
  c.shape = std::move(compound);
  return c;
}

// The group's collision geometry as triangles in its body frame (for pictures and placement).
massprops::TriangleMesh ShapeOf(const std::vector<PlacedGeometry>& geometries) {
  std::vector<Vector3> v;
  std::vector<std::array<int, 3>> t;
  for (const PlacedGeometry& placed : geometries) {
    const int base = static_cast<int>(v.size());
    for (const Vector3& p : placed.points.vertices) v.push_back(placed.pose.rotation * p + placed.pose.translation);
    for (const auto& tri : placed.points.triangles) t.push_back({base + tri[0], base + tri[1], base + tri[2]});
  }
  massprops::TriangleMesh mesh;
  mesh.V.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) mesh.V.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
  mesh.F.resize(static_cast<Eigen::Index>(t.size()), 3);
  for (std::size_t i = 0; i < t.size(); ++i) {
    mesh.F.row(static_cast<Eigen::Index>(i)) << t[i][0], t[i][1], t[i][2];
  }
  return mesh;
}

// A keyframe's state per model joint: q and q̇ (empty: not given), and the actuators' controls.
struct KeyState {
  std::vector<std::vector<double>> q, v;
  std::vector<double> ctrl;
};

// A 1-dof joint moved to q: the child turned or slid along the axis (other joints: not moved).
Placement JointMotion(const RobotJoint& j, double q) {
  switch (j.type) {
    case RobotJointType::kRevolute:
    case RobotJointType::kContinuous: return {Eigen::AngleAxisd(q, j.axis).toRotationMatrix(), Vector3::Zero()};
    case RobotJointType::kPrismatic: return {Matrix3::Identity(), q * j.axis};
    default: return {};
  }
}

// The simulator's joint type of a file's joint type.
JointType JointTypeOf(massprops::RobotJointType t) {
  switch (t) {
    case RobotJointType::kFixed: return JointType::kFixed;
    case RobotJointType::kRevolute:
    case RobotJointType::kContinuous: return JointType::kRevolute;
    case RobotJointType::kPrismatic: return JointType::kPrismatic;
    case RobotJointType::kBall: return JointType::kSpherical;
    case RobotJointType::kFloating: return JointType::kFree;
  }
  return JointType::kFixed;
}

// The keyframe `name` split over the joints in MuJoCo's order (the model's joints are in body
// order, as MuJoCo's qpos is). @throws std::invalid_argument for a missing key or sizes that do
// not match the robot.
KeyState KeyframeState(const RobotModel& model, const std::string& name) {
  KeyState s;
  s.q.resize(model.joints.size());
  s.v.resize(model.joints.size());
  s.ctrl.assign(model.actuators.size(), 0.0);
  if (name.empty()) return s;
  const auto it = std::find_if(model.keyframes.begin(), model.keyframes.end(),
                               [&](const massprops::RobotKeyframe& k) { return k.name == name; });
  if (it == model.keyframes.end()) {
    std::string names;
    for (const auto& k : model.keyframes) names += (names.empty() ? "" : ", ") + k.name;
    throw std::invalid_argument(model.path + ": no keyframe named '" + name + "' (" +
                                (names.empty() ? std::string("the file has none") : "it has: " + names) + ")");
  }
  std::size_t nq = 0, nv = 0;
  for (const RobotJoint& j : model.joints) {
    nq += static_cast<std::size_t>(JointPositionSize(JointTypeOf(j.type)));
    nv += static_cast<std::size_t>(JointVelocitySize(JointTypeOf(j.type)));
  }
  auto check = [&](const std::vector<double>& x, std::size_t n, const char* what) {
    if (!x.empty() && x.size() != n) {
      throw std::invalid_argument(model.path + ": keyframe '" + name + "': " + what + " has " +
                                  std::to_string(x.size()) + " numbers; the robot's joints take " + std::to_string(n));
    }
  };
  check(it->qpos, nq, "qpos");
  check(it->qvel, nv, "qvel");
  check(it->ctrl, model.actuators.size(), "ctrl");
  std::size_t at_q = 0, at_v = 0;
  for (std::size_t k = 0; k < model.joints.size(); ++k) {
    const auto n = static_cast<std::size_t>(JointPositionSize(JointTypeOf(model.joints[k].type)));
    const auto m = static_cast<std::size_t>(JointVelocitySize(JointTypeOf(model.joints[k].type)));
    if (!it->qpos.empty()) s.q[k].assign(it->qpos.begin() + at_q, it->qpos.begin() + at_q + n);
    if (!it->qvel.empty()) s.v[k].assign(it->qvel.begin() + at_v, it->qvel.begin() + at_v + m);
    at_q += n, at_v += m;
  }
  if (!it->ctrl.empty()) s.ctrl = it->ctrl;
  return s;
}

// A joint drive from an MJCF actuator at control `ctrl` (robot_model.h's general form): a PD servo
// where the bias pulls back, a damper toward a rate where only the velocity does, else a constant
// effort. None (a note) for a bias that pushes away, which no servo here follows.
std::optional<JointMotor> ActuatorMotor(const massprops::RobotActuator& a, double ctrl, const std::string& path,
                                        std::vector<std::string>& notes) {
  if (a.ctrlrange) ctrl = std::clamp(ctrl, a.ctrlrange->first, a.ctrlrange->second);
  const double g = a.gear, kp = -g * g * a.bias[1], kd = -g * g * a.bias[2], constant = g * (a.gain * ctrl + a.bias[0]);
  if (kp < 0 || kd < 0) {
    notes.push_back(path + ": actuator '" + a.name + "': a bias that pushes away from its target is not simulated");
    return std::nullopt;
  }
  JointMotor m;
  if (kp > 0) {
    m.mode = JointMotor::Mode::kPosition;
    m.kp = kp, m.kd = kd, m.target = constant / kp;
  } else if (kd > 0) {
    m.mode = JointMotor::Mode::kPosition;
    m.kd = kd, m.target_velocity = constant / kd;
  } else {
    m.mode = JointMotor::Mode::kEffort;
    m.target = constant;
  }
  if (a.forcerange) {
    m.max_effort = std::abs(g) * std::max(std::abs(a.forcerange->first), std::abs(a.forcerange->second));
    if (a.forcerange->first != -a.forcerange->second) {
      notes.push_back(path + ": actuator '" + a.name + "': its force range is taken as ±" +
                      std::to_string(m.max_effort / std::abs(g)) + " (symmetric)");
    }
    if (!(m.max_effort > 0)) return std::nullopt;  // a zero range: no force
  }
  return m;
}

}  // namespace

std::vector<massprops::TriangleMesh> VisualShapes(const RobotModel& model, const RobotInWorld& added,
                                                  const massprops::LoadOptions& load, std::vector<std::string>& notes) {
  const int first_body = added.bodies.empty() ? 0 : added.bodies.front();
  std::vector<std::vector<PlacedGeometry>> placed(added.bodies.size());
  for (std::size_t l = 0; l < model.links.size() && l < added.link_in_body.size(); ++l) {
    const auto body = static_cast<std::size_t>(added.body_of_link[l] - first_body);
    for (const massprops::RobotGeometry& g : model.links[l].visuals) {
      Points points;
      try {
        if (const auto* m = std::get_if<massprops::RobotMesh>(&g.shape)) {
          const massprops::LoadedMesh file = massprops::ReadMeshFile(m->path);
          const double metres =
              massprops::MetresPerUnit(file.declared_unit && !load.unit_stated ? *file.declared_unit : load.unit);
          points = PointsFrom(massprops::Triangulate(file.mesh), metres, m->scale);
        } else {
          points = PointsFrom(massprops::Tessellate(std::get<massprops::Primitive>(g.shape), 24), 1, Vector3::Ones());
        }
      } catch (const std::exception& e) {
        notes.push_back(g.where + ": not drawn: " + e.what());
        continue;
      }
      placed[body].push_back({&g, added.link_in_body[l].Then(g.pose), std::move(points)});
    }
  }
  std::vector<massprops::TriangleMesh> out;
  for (const std::vector<PlacedGeometry>& p : placed) out.push_back(ShapeOf(p));
  return out;
}

bool PlacedByItsFile(const RobotModel& model, const RobotOptions& options) {
  if (model.format != massprops::RobotFormat::kUrdf || !options.keyframe.empty()) return true;
  return std::any_of(model.joints.begin(), model.joints.end(),
                     [](const RobotJoint& j) { return j.parent < 0 && j.type != RobotJointType::kFloating; });
}

massprops::Placement PlaceAboveGround(const RobotModel& model, const RobotOptions& options,
                                      const std::vector<Ground>& grounds, double clearance) {
  if (PlacedByItsFile(model, options) || grounds.empty()) return options.pose;
  // Where its lowest point is at the pose as given (a scratch world), then raised.
  ContactWorld scratch;
  const RobotInWorld trial = AddRobot(scratch, model, options);
  const Vector3 up = grounds.front().normal;
  double floor = -std::numeric_limits<double>::infinity();
  for (const Ground& g : grounds) {
    if (g.normal.isApprox(up)) floor = std::max(floor, g.offset);
  }
  double lowest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < trial.bodies.size(); ++k) {
    const RigidBody& b = scratch.world().bodies()[static_cast<std::size_t>(trial.bodies[k])];
    const massprops::TriangleMesh& m = trial.shapes[k];
    for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
      lowest = std::min(lowest, up.dot(b.orientation * Vector3(m.V.row(v).transpose()) + b.position));
    }
  }
  massprops::Placement pose = options.pose;
  if (std::isfinite(lowest)) pose.translation += up * (floor + clearance - lowest);
  return pose;
}

Ground GroundOf(const massprops::RobotGround& ground) {
  Ground g(ground.normal, ground.offset, {}, {ground.contype, ground.conaffinity});
  if (ground.friction) g.material = FileFriction(*ground.friction, 0);
  return g;
}

Collider TerrainCollider(const massprops::RobotTerrain& terrain) {
  Collider c;
  try {
    shape::Mesh mesh = MeshOf(terrain.mesh);
    c.shape = MakeMesh(std::move(mesh.vertices), std::move(mesh.triangles));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(terrain.where + ": " + e.what());
  }
  if (terrain.friction) c.material = FileFriction(*terrain.friction, 0);
  c.filter = {terrain.contype, terrain.conaffinity};
  return c;
}

namespace {

// Every joint the options name is the robot's. @throws std::invalid_argument naming it.
void CheckNamedJoints(const RobotModel& model, const RobotOptions& options) {
  auto check_named = [&](const std::string& name, const char* what) {
    if (std::none_of(model.joints.begin(), model.joints.end(), [&](const RobotJoint& j) { return j.name == name; })) {
      throw std::invalid_argument(model.path + ": " + what + " names the joint '" + name +
                                  "', which the robot has not");
    }
  };
  for (const auto& entry : options.positions) check_named(entry.first, "positions");
  for (const auto& entry : options.motors) check_named(entry.first, "motors");
}

// The links lumped into bodies: the joint above each link, the links in an order where parents
// come first, and the groups of links welded by fixed joints between links.
struct Lumping {
  std::vector<int> joint_above;  // each link's joint (-1: none)
  std::vector<int> order;        // parents first
  std::vector<int> group_of;     // each link's group
  std::vector<Group> groups;

  // Whether a link is welded to its parent link (and so lumped into its group).
  bool Welded(const RobotModel& model, int link) const {
    const int j = joint_above[static_cast<std::size_t>(link)];
    return j >= 0 && model.joints[static_cast<std::size_t>(j)].type == RobotJointType::kFixed &&
           model.joints[static_cast<std::size_t>(j)].parent >= 0;
  }
  std::size_t IndexInGroup(int link) const {
    const Group& g = groups[static_cast<std::size_t>(group_of[static_cast<std::size_t>(link)])];
    return static_cast<std::size_t>(std::find(g.links.begin(), g.links.end(), link) - g.links.begin());
  }
  // A link's frame in its body's frame.
  Placement LinkInBody(int link) const {
    const Group& g = groups[static_cast<std::size_t>(group_of[static_cast<std::size_t>(link)])];
    return g.body_in_root.Inverse().Then(g.in_root[IndexInGroup(link)]);
  }
};

// Phase 1: links in parent-first order, lumped into groups by fixed joints between links.
// @throws std::invalid_argument for joints that form a loop.
Lumping LumpLinks(const RobotModel& model) {
  const std::size_t nl = model.links.size();
  Lumping out;
  out.joint_above.assign(nl, -1);
  for (std::size_t k = 0; k < model.joints.size(); ++k)
    out.joint_above[static_cast<std::size_t>(model.joints[k].child)] = static_cast<int>(k);
  std::vector<char> placed(nl, 0);
  while (out.order.size() < nl) {
    const std::size_t before = out.order.size();
    for (std::size_t i = 0; i < nl; ++i) {
      if (placed[i]) continue;
      const int j = out.joint_above[i];
      const int parent = j >= 0 ? model.joints[static_cast<std::size_t>(j)].parent : -1;
      if (parent < 0 || placed[static_cast<std::size_t>(parent)]) {
        placed[i] = 1;
        out.order.push_back(static_cast<int>(i));
      }
    }
    if (out.order.size() == before) throw std::invalid_argument(model.path + ": its joints form a loop");
  }
  out.group_of.assign(nl, -1);
  for (const int link : out.order) {
    const auto l = static_cast<std::size_t>(link);
    if (out.Welded(model, link)) {
      const RobotJoint& j = model.joints[static_cast<std::size_t>(out.joint_above[l])];
      const int g = out.group_of[static_cast<std::size_t>(j.parent)];
      Group& group = out.groups[static_cast<std::size_t>(g)];
      const auto at = std::find(group.links.begin(), group.links.end(), j.parent) - group.links.begin();
      group.in_root.push_back(
          group.in_root[static_cast<std::size_t>(at)].Then(j.parent_to_joint).Then(j.joint_to_child));
      group.links.push_back(link);
      out.group_of[l] = g;
    } else {
      Group group;
      group.root = link;
      group.links = {link};
      group.in_root = {Placement{}};
      out.group_of[l] = static_cast<int>(out.groups.size());
      out.groups.push_back(group);
    }
  }
  return out;
}

// Phase 2: a group's mass, center of mass and inertia (its links' inertials combined); its
// principal frame. @throws std::invalid_argument for a group without mass or a tensor that is not
// positive definite.
void CombineInertials(const RobotModel& model, Group& g) {
  for (std::size_t k = 0; k < g.links.size(); ++k) {
    const auto& inertial = model.links[static_cast<std::size_t>(g.links[k])].inertial;
    if (!inertial) continue;
    const Placement& p = g.in_root[k];
    const Vector3 c = p.rotation * inertial->center_of_mass + p.translation;
    g.com = (g.mass * g.com + inertial->mass * c) / (g.mass + inertial->mass);
    g.mass += inertial->mass;
  }
  const std::string name = model.links[static_cast<std::size_t>(g.root)].name;
  if (!(g.mass > 0)) {
    throw std::invalid_argument(model.path + ": link '" + name +
                                "' has no mass (no inertial, nor any link welded to it): give it an inertial, or "
                                "compute them from the geometry (--fill)");
  }
  for (std::size_t k = 0; k < g.links.size(); ++k) {
    const auto& inertial = model.links[static_cast<std::size_t>(g.links[k])].inertial;
    if (!inertial) continue;
    const Placement& p = g.in_root[k];
    const Vector3 d = p.rotation * inertial->center_of_mass + p.translation - g.com;
    g.inertia += p.rotation * inertial->inertia * p.rotation.transpose() +
                 inertial->mass * (d.squaredNorm() * Matrix3::Identity() - d * d.transpose());
  }
  const Eigen::SelfAdjointEigenSolver<Matrix3> eig(g.inertia);
  g.moments = eig.eigenvalues();
  Matrix3 axes = eig.eigenvectors();
  if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
  if (!(g.moments.minCoeff() > 0) || !g.moments.allFinite()) {
    throw std::invalid_argument(model.path + ": link '" + name +
                                "' has an inertia that is not positive definite (principal moments " +
                                std::to_string(g.moments.x()) + ", " + std::to_string(g.moments.y()) + ", " +
                                std::to_string(g.moments.z()) + " kg·m²)");
  }
  g.body_in_root = Placement{axes, g.com};
}

// Phase 3: where each group's root link is at q = 0. A joint to the world (URDF's "world" link,
// SDFormat's, an MJCF top body's) places the root where the file does, relative to the pose,
// whether the base is as written, fixed or floating; a keyframe's free-joint pose places its root
// as MuJoCo's qpos does (x y z, w x y z in the world).
std::vector<Placement> PlaceRoots(const RobotModel& model, const RobotOptions& options, const Lumping& lumps,
                                  const KeyState& key) {
  const std::vector<Group>& groups = lumps.groups;
  std::vector<Placement> root_in_world(groups.size());
  auto link_in_world = [&](int link) {  // (its group's root placed already)
    const auto g = static_cast<std::size_t>(lumps.group_of[static_cast<std::size_t>(link)]);
    return root_in_world[g].Then(groups[g].in_root[lumps.IndexInGroup(link)]);
  };
  for (const int link : lumps.order) {
    const auto l = static_cast<std::size_t>(link);
    const auto g = static_cast<std::size_t>(lumps.group_of[l]);
    if (groups[g].root != link) continue;
    const int j = lumps.joint_above[l];
    if (j < 0) {
      root_in_world[g] = options.pose.Then(model.links[l].placement.value_or(Placement{}));
      continue;
    }
    const RobotJoint& joint = model.joints[static_cast<std::size_t>(j)];
    const Placement parent = joint.parent >= 0 ? link_in_world(joint.parent) : options.pose;
    root_in_world[g] =
        parent.Then(joint.parent_to_joint).Then(JointMotion(joint, joint.ref)).Then(joint.joint_to_child);
  }
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const int j = lumps.joint_above[static_cast<std::size_t>(groups[g].root)];
    if (j < 0 || model.joints[static_cast<std::size_t>(j)].type != RobotJointType::kFloating) continue;
    const std::vector<double>& q = key.q[static_cast<std::size_t>(j)];
    if (q.size() != 7) continue;
    const Quaternion turn = Quaternion(q[3], q[4], q[5], q[6]).normalized();
    root_in_world[g] = options.pose.Then(Placement{turn.toRotationMatrix(), Vector3(q[0], q[1], q[2])});
  }
  return root_in_world;
}

// Phase 4: a body for each group, with its collider, at its root's place; a keyframe's free-joint
// qvel, as MuJoCo's: the root frame's velocity in the world, then its angular velocity in its own
// axes (the center of mass moves with the frame).
void AddBodies(ContactWorld& world, const RobotModel& model, const RobotOptions& options, const Lumping& lumps,
               const std::vector<Placement>& root_in_world, const KeyState& key, RobotInWorld& out) {
  for (std::size_t g = 0; g < lumps.groups.size(); ++g) {
    const Group& group = lumps.groups[g];
    const Placement body = root_in_world[g].Then(group.body_in_root);
    RigidBody b;
    b.mass = group.mass;
    b.inertia = group.moments;
    b.position = body.translation;
    b.orientation = QuaternionOf(body.rotation);
    const int above = lumps.joint_above[static_cast<std::size_t>(group.root)];
    if (above >= 0 && model.joints[static_cast<std::size_t>(above)].type == RobotJointType::kFloating &&
        key.v[static_cast<std::size_t>(above)].size() == 6) {
      const std::vector<double>& v = key.v[static_cast<std::size_t>(above)];
      const Vector3 omega = root_in_world[g].rotation * Vector3(v[3], v[4], v[5]);
      b.velocity = Vector3(v[0], v[1], v[2]) + omega.cross(body.translation - root_in_world[g].translation);
      b.SetAngularVelocity(omega);
    }
    const std::vector<PlacedGeometry> geometries = GeometriesOf(model, group, options, out.notes);
    const std::optional<Collider> collider = ColliderOf(geometries, options);
    out.bodies.push_back(collider ? world.AddBody(b, *collider) : world.AddBody(b));
    out.body_names.push_back(model.links[static_cast<std::size_t>(group.root)].name);
    out.shapes.push_back(ShapeOf(geometries));
    out.body_in_link.push_back(group.body_in_root);
  }
}

// The drive of joint k: the options' motor (its effort bounded by the file's limit when it names
// none), else the file's actuator on it (MJCF) at the keyframe's control (0 without one).
JointMotor MotorOf(const RobotModel& model, const RobotOptions& options, std::size_t k, const KeyState& key,
                   std::vector<std::string>& notes) {
  const RobotJoint& rj = model.joints[k];
  JointMotor motor;
  if (const auto it = options.motors.find(rj.name); it != options.motors.end()) {
    motor = it->second;
    if (!std::isfinite(motor.max_effort) && rj.effort > 0) motor.max_effort = rj.effort;
    return motor;
  }
  for (std::size_t a = 0; a < model.actuators.size(); ++a) {
    if (model.actuators[a].joint != static_cast<int>(k)) continue;
    if (motor.mode != JointMotor::Mode::kOff) {
      notes.push_back(model.path + ": joint '" + rj.name + "' has several actuators: the first drives it");
      break;
    }
    if (const auto m = ActuatorMotor(model.actuators[a], key.ctrl[a], model.path, notes)) motor = *m;
  }
  return motor;
}

// Phase 5: model joint k as the world's joint between the bodies its links became (none: a
// floating root, a free body). @throws std::invalid_argument for positions given to a joint that
// takes more than one number.
std::optional<Joint> JointOf(const RobotModel& model, const RobotOptions& options, const Lumping& lumps,
                             const RobotInWorld& out, std::size_t k, const KeyState& key,
                             std::vector<std::string>& notes) {
  const RobotJoint& rj = model.joints[k];
  const bool fixed_base = options.base == RobotOptions::Base::kFixed;
  const bool floating_base = options.base == RobotOptions::Base::kFloating;
  Joint j;
  j.name = rj.name;
  j.child = out.body_of_link[static_cast<std::size_t>(rj.child)];
  j.parent = rj.parent >= 0 ? out.body_of_link[static_cast<std::size_t>(rj.parent)] : -1;
  Placement parent_frame;
  if (rj.parent >= 0) {
    parent_frame = lumps.LinkInBody(rj.parent).Then(rj.parent_to_joint);
  } else {
    // A floating base is a free body (the file's free joint to the world, or none): the same
    // motion, stepped in the body's own coordinates whatever the format.
    if (floating_base || (rj.type == RobotJointType::kFloating && !fixed_base)) return std::nullopt;
    parent_frame = options.pose.Then(rj.parent_to_joint);
  }
  j.parent_frame = FrameOf(parent_frame);
  j.child_frame = FrameOf(lumps.LinkInBody(rj.child).Then(rj.joint_to_child.Inverse()));
  j.axis = rj.axis;
  j.type = JointTypeOf(rj.type);
  if (rj.parent < 0 && fixed_base) j.type = JointType::kFixed;
  if (rj.lower) j.limits.lower = *rj.lower;
  if (rj.upper) j.limits.upper = *rj.upper;
  j.damping = rj.damping;
  j.friction = rj.friction;
  j.stiffness = rj.stiffness;
  j.rest_position = rj.rest;
  j.armature = rj.armature;
  // At the file's ref (MJCF), else 0; the keyframe's state (hinges, sliders and balls); a scene's
  // positions win.
  if (rj.ref != 0 && HasOneCoordinate(j.type)) j.position = {rj.ref};
  const std::vector<double>& key_q = key.q[k];
  if (!key_q.empty() && (HasOneCoordinate(j.type) || j.type == JointType::kSpherical)) j.position = key_q;
  if (!key.v[k].empty() && HasOneCoordinate(j.type)) j.velocity = key.v[k];
  j.motor = MotorOf(model, options, k, key, notes);
  if (const auto it = options.positions.find(rj.name); it != options.positions.end()) {
    if (!HasOneCoordinate(j.type)) {
      throw std::invalid_argument(model.path + ": positions gives joint '" + rj.name + "' (" +
                                  massprops::RobotJointTypeName(rj.type) +
                                  ") one number; only revolute and prismatic joints take one");
    }
    j.position = {it->second};
  }
  return j;
}

// Phase 6: a root without a joint to the world, welded at the pose (a fixed base).
void WeldRoots(ContactWorld& world, const RobotModel& model, const RobotOptions& options, const Lumping& lumps,
               int first_body) {
  for (std::size_t g = 0; g < lumps.groups.size(); ++g) {
    const int root = lumps.groups[g].root;
    if (lumps.joint_above[static_cast<std::size_t>(root)] >= 0) continue;
    Joint weld;
    weld.name = model.links[static_cast<std::size_t>(root)].name + " (fixed base)";
    weld.type = JointType::kFixed;
    weld.parent = -1;
    weld.child = first_body + static_cast<int>(g);
    weld.parent_frame = FrameOf(options.pose);
    weld.child_frame = FrameOf(lumps.LinkInBody(root));
    world.AddJoint(weld);
  }
}

}  // namespace

RobotInWorld AddRobot(ContactWorld& world, const RobotModel& model, const RobotOptions& options) {
  const std::size_t nl = model.links.size();
  RobotInWorld out;
  out.notes = model.notes;
  if (nl == 0) throw std::invalid_argument(model.path + ": the robot has no links");
  CheckNamedJoints(model, options);
  Lumping lumps = LumpLinks(model);
  for (Group& g : lumps.groups) CombineInertials(model, g);
  const KeyState key = KeyframeState(model, options.keyframe);
  const std::vector<Placement> root_in_world = PlaceRoots(model, options, lumps, key);
  const int first_body = static_cast<int>(world.world().bodies().size());
  AddBodies(world, model, options, lumps, root_in_world, key, out);
  out.body_of_link.resize(nl);
  for (std::size_t l = 0; l < nl; ++l) out.body_of_link[l] = first_body + lumps.group_of[l];
  for (std::size_t l = 0; l < nl; ++l) out.link_in_body.push_back(lumps.LinkInBody(static_cast<int>(l)));
  out.joint_of.assign(model.joints.size(), -1);
  for (std::size_t k = 0; k < model.joints.size(); ++k) {
    if (lumps.Welded(model, model.joints[k].child)) continue;  // lumped
    if (const std::optional<Joint> j = JointOf(model, options, lumps, out, k, key, out.notes)) {
      out.joint_of[k] = world.AddJoint(*j);
    }
  }
  if (options.base == RobotOptions::Base::kFixed) WeldRoots(world, model, options, lumps, first_body);
  // Tendons (their drives from the file's actuators on them), couplings and loops.
  std::vector<JointMotor> tendon_motors(model.tendons.size());
  for (std::size_t a = 0; a < model.actuators.size(); ++a) {
    const int t = model.actuators[a].tendon;
    if (t < 0 || tendon_motors[static_cast<std::size_t>(t)].mode != JointMotor::Mode::kOff) continue;
    if (const auto m = ActuatorMotor(model.actuators[a], key.ctrl[a], model.path, out.notes))
      tendon_motors[static_cast<std::size_t>(t)] = *m;
  }
  // The reference configuration (every joint at 0, free roots where the file puts them, whatever
  // the keyframe): where MJCF's connect and weld find their second frame and tendons their lengths.
  std::vector<Placement> reference;
  if (!model.loops.empty() || !model.tendons.empty() || !model.couplings.empty()) {
    const std::vector<Placement> roots = PlaceRoots(model, options, lumps, KeyframeState(model, ""));
    for (std::size_t g = 0; g < lumps.groups.size(); ++g)
      reference.push_back(roots[g].Then(lumps.groups[g].body_in_root));
  }
  internal::AddRobotConstraints(world, model, options.pose, out, reference, tendon_motors);
  if (model.medium) {  // the file's medium, on its own bodies (MuJoCo's inertia-box model)
    world.AddForce(Fluid({model.medium->density, model.medium->viscosity, model.medium->wind}, out.bodies));
  }
  // The file's excluded pairs (MJCF <contact><exclude>), between the bodies their links became.
  for (const auto& [l1, l2] : model.excluded) {
    const int a = out.body_of_link[static_cast<std::size_t>(l1)], b = out.body_of_link[static_cast<std::size_t>(l2)];
    if (a != b) world.ExcludePair(a, b);
  }
  return out;
}

}  // namespace dynamics
