// The definitions of massprops/primitive.h: the closed-form solids, as one list.

#include "massprops/primitive.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "massprops/solids.h"
#include "massprops/text.h"

namespace massprops {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

void RequirePositive(Scalar v, const char* what) {
  if (!(std::isfinite(v) && v > 0)) {
    throw std::invalid_argument(std::string(what) + " must be finite and positive (got " + FormatDouble(v, "%.6g") +
                                ")");
  }
}

std::string G(double v) { return FormatDouble(v, "%.6g"); }

}  // namespace

const char* PrimitiveName(const Primitive& p) { return kPrimitiveNames[p.index()]; }

namespace {

struct SizeRow {
  const char* name;
  std::vector<SizeKey> shape_syntax, scene, robot;
};

const std::vector<SizeRow>& SizeTable() {
  static const std::vector<SizeRow> rows = {
      {"box",
       {{"x", 1, "edge length along x"}, {"y", 1, "edge length along y"}, {"z", 1, "edge length along z"}},
       {{"size", 3, "edge lengths [x, y, z]"}},
       {{"size", 3, "edge lengths"}}},
      {"sphere", {{"r", 1, "radius"}}, {{"radius", 1, "radius"}}, {{"radius", 1, "radius"}}},
      {"ellipsoid",
       {{"a", 1, "semi-axis along x"}, {"b", 1, "semi-axis along y"}, {"c", 1, "semi-axis along z"}},
       {{"semi_axes", 3, "[a, b, c]"}},
       {{"radii", 3, "semi-axes"}}},
      {"cylinder",
       {{"r", 1, "radius"}, {"h", 1, "height"}},
       {{"radius", 1, "radius"}, {"height", 1, "height"}},
       {{"radius", 1, "radius"}, {"length", 1, "height"}}},
      {"cone", {{"r", 1, "radius"}, {"h", 1, "height"}}, {{"radius", 1, "radius"}, {"height", 1, "height"}}, {}},
      {"torus",
       {{"R", 1, "major radius"}, {"r", 1, "minor radius"}},
       {{"major_radius", 1, "major radius"}, {"minor_radius", 1, "minor radius"}},
       {}},
      {"capsule",
       {{"r", 1, "radius"}, {"h", 1, "length of the cylinder part"}},
       {{"radius", 1, "radius"}, {"length", 1, "length of the cylinder part"}},
       {{"radius", 1, "radius"}, {"length", 1, "length of the cylinder part"}}},
  };
  return rows;
}

}  // namespace

const std::vector<SizeKey>& SizeKeys(std::string_view name, SizeSyntax syntax) {
  static const std::vector<SizeKey> none;
  for (const SizeRow& row : SizeTable()) {
    if (name != row.name) continue;
    switch (syntax) {
      case SizeSyntax::kShapeSyntax: return row.shape_syntax;
      case SizeSyntax::kScene: return row.scene;
      case SizeSyntax::kRobot: return row.robot;
    }
  }
  return none;
}

Primitive MakePrimitive(std::string_view name, const std::vector<double>& s) {
  namespace pr = primitive;
  const auto need = [&](std::size_t n) {
    if (s.size() != n) {
      throw std::invalid_argument(std::string(name) + ": " + std::to_string(n) + " sizes expected, got " +
                                  std::to_string(s.size()));
    }
  };
  if (name == "box") {
    need(3);
    return pr::Box{Vector3(s[0], s[1], s[2])};
  }
  if (name == "sphere") {
    need(1);
    return pr::Sphere{s[0]};
  }
  if (name == "ellipsoid") {
    need(3);
    return pr::Ellipsoid{Vector3(s[0], s[1], s[2])};
  }
  if (name == "cylinder") {
    need(2);
    return pr::Cylinder{s[0], s[1]};
  }
  if (name == "cone") {
    need(2);
    return pr::Cone{s[0], s[1]};
  }
  if (name == "torus") {
    need(2);
    return pr::Torus{s[0], s[1]};
  }
  if (name == "capsule") {
    need(2);
    return pr::Capsule{s[0], s[1]};
  }
  throw std::invalid_argument("'" + std::string(name) + "' is not a primitive");
}

void Validate(const Primitive& p) {
  namespace pr = primitive;
  std::visit(Overloaded{
                 [](const pr::Box& s) {
                   for (int i = 0; i < 3; ++i) RequirePositive(s.size[i], "box: edge");
                 },
                 [](const pr::Sphere& s) { RequirePositive(s.radius, "sphere: radius"); },
                 [](const pr::Ellipsoid& s) {
                   for (int i = 0; i < 3; ++i) RequirePositive(s.semi_axes[i], "ellipsoid: semi-axis");
                 },
                 [](const pr::Cylinder& s) {
                   RequirePositive(s.radius, "cylinder: radius");
                   RequirePositive(s.height, "cylinder: height");
                 },
                 [](const pr::Cone& s) {
                   RequirePositive(s.radius, "cone: radius");
                   RequirePositive(s.height, "cone: height");
                 },
                 [](const pr::Torus& s) {
                   RequirePositive(s.major_radius, "torus: major radius");
                   RequirePositive(s.minor_radius, "torus: minor radius");
                   if (!(s.minor_radius < s.major_radius)) {
                     throw std::invalid_argument(
                         "torus: the minor radius must be smaller than the major radius "
                         "(a self-intersecting torus is not a solid)");
                   }
                 },
                 [](const pr::Capsule& s) {
                   RequirePositive(s.radius, "capsule: radius");
                   RequirePositive(s.length, "capsule: length");
                 },
             },
             p);
}

MassProperties ClosedForm(const Primitive& p, Scalar density) {
  Validate(p);
  namespace pr = primitive;
  namespace so = solids;
  const MassProperties mp =
      std::visit(Overloaded{
                     [&](const pr::Box& s) { return so::BoxProperties(s.size, density); },
                     [&](const pr::Sphere& s) { return so::SphereProperties(s.radius, density); },
                     [&](const pr::Ellipsoid& s) { return so::EllipsoidProperties(s.semi_axes, density); },
                     [&](const pr::Cylinder& s) { return so::CylinderProperties(s.radius, s.height, density); },
                     [&](const pr::Cone& s) { return so::ConeProperties(s.radius, s.height, density); },
                     [&](const pr::Torus& s) { return so::TorusProperties(s.major_radius, s.minor_radius, density); },
                     [&](const pr::Capsule& s) { return so::CapsuleProperties(s.radius, s.length, density); },
                 },
                 p);
  if (!std::isnormal(mp.volume) || !std::isnormal(mp.inertia_com.trace()) || !mp.inertia_com.allFinite()) {
    throw std::invalid_argument(std::string(PrimitiveName(p)) +
                                ": its volume or inertia under- or overflows double precision at these sizes");
  }
  return mp;
}

TriangleMesh Tessellate(const Primitive& p, int n) {
  namespace pr = primitive;
  namespace so = solids;
  return std::visit(Overloaded{
                        [&](const pr::Box& s) { return Triangulate(so::Box(s.size)); },
                        [&](const pr::Sphere& s) { return so::Sphere(s.radius, n); },
                        [&](const pr::Ellipsoid& s) { return so::Ellipsoid(s.semi_axes, n); },
                        [&](const pr::Cylinder& s) { return so::Cylinder(s.radius, s.height, n); },
                        [&](const pr::Cone& s) { return so::Cone(s.radius, s.height, n); },
                        [&](const pr::Torus& s) { return so::Torus(s.major_radius, s.minor_radius, n); },
                        [&](const pr::Capsule& s) { return so::Capsule(s.radius, s.length, n); },
                    },
                    p);
}

ImplicitPtr ToImplicit(const Primitive& p) {
  namespace pr = primitive;
  namespace im = implicit;
  return std::visit(Overloaded{
                        [](const pr::Box& s) { return im::Box(s.size); },
                        [](const pr::Sphere& s) { return im::Sphere(s.radius); },
                        [](const pr::Ellipsoid& s) { return im::Ellipsoid(s.semi_axes); },
                        [](const pr::Cylinder& s) { return im::Cylinder(s.radius, s.height); },
                        [](const pr::Cone& s) { return im::Cone(s.radius, s.height); },
                        [](const pr::Torus& s) { return im::Torus(s.major_radius, s.minor_radius); },
                        [](const pr::Capsule& s) { return im::Capsule(s.radius, s.length); },
                    },
                    p);
}

std::string Describe(const Primitive& p) {
  namespace pr = primitive;
  return std::visit(
      Overloaded{
          [](const pr::Box& s) {
            return "box " + G(s.size.x()) + " x " + G(s.size.y()) + " x " + G(s.size.z()) + " m";
          },
          [](const pr::Sphere& s) { return "sphere r=" + G(s.radius) + " m"; },
          [](const pr::Ellipsoid& s) {
            return "ellipsoid " + G(s.semi_axes.x()) + ", " + G(s.semi_axes.y()) + ", " + G(s.semi_axes.z()) + " m";
          },
          [](const pr::Cylinder& s) { return "cylinder r=" + G(s.radius) + " h=" + G(s.height) + " m"; },
          [](const pr::Cone& s) { return "cone r=" + G(s.radius) + " h=" + G(s.height) + " m (apex at z=+3h/4)"; },
          [](const pr::Torus& s) { return "torus R=" + G(s.major_radius) + " r=" + G(s.minor_radius) + " m"; },
          [](const pr::Capsule& s) { return "capsule r=" + G(s.radius) + " length=" + G(s.length) + " m"; },
      },
      p);
}

}  // namespace massprops
