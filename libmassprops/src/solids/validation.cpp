// The definitions of massprops/validation.h: validation a user can run.

#include "massprops/validation.h"

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>

#include "massprops/composition.h"
#include "massprops/mass_properties.h"
#include "massprops/solids.h"

namespace massprops {
namespace {

struct Case {
  const char* name;
  bool exact;                                   // a polyhedron: the mesh is the solid
  std::function<PolygonMesh(int n)> mesh;       // at resolution n
  std::function<MassProperties()> closed_form;  // density 1000
};

constexpr double kDensity = 1000.0;

const std::vector<Case>& Cases() {
  using namespace solids;
  static const std::vector<Case> cases = {
      {"box", true, [](int) { return Box(Vector3(1, 2, 3)); },
       [] { return BoxProperties(Vector3(1, 2, 3), kDensity); }},
      {"tetrahedron", true, [](int) { return ToPolygonMesh(RegularTetrahedron(1.5)); },
       [] { return RegularTetrahedronProperties(1.5, kDensity); }},
      {"octahedron", true, [](int) { return ToPolygonMesh(Octahedron(0.8)); },
       [] { return OctahedronProperties(0.8, kDensity); }},
      {"prism", true, [](int) { return RegularPrism(7, 0.6, 1.1); },
       [] { return RegularPrismProperties(7, 0.6, 1.1, kDensity); }},
      {"sphere", false, [](int n) { return ToPolygonMesh(Sphere(0.5, n)); },
       [] { return SphereProperties(0.5, kDensity); }},
      {"ellipsoid", false, [](int n) { return ToPolygonMesh(Ellipsoid(Vector3(1, 0.6, 0.3), n)); },
       [] { return EllipsoidProperties(Vector3(1, 0.6, 0.3), kDensity); }},
      {"cylinder", false, [](int n) { return ToPolygonMesh(Cylinder(0.4, 1.2, n)); },
       [] { return CylinderProperties(0.4, 1.2, kDensity); }},
      {"cone", false, [](int n) { return ToPolygonMesh(Cone(0.5, 1.0, n)); },
       [] { return ConeProperties(0.5, 1.0, kDensity); }},
      {"torus", false, [](int n) { return ToPolygonMesh(Torus(1.0, 0.3, n)); },
       [] { return TorusProperties(1.0, 0.3, kDensity); }},
      {"capsule", false, [](int n) { return ToPolygonMesh(Capsule(0.3, 0.8, n)); },
       [] { return CapsuleProperties(0.3, 0.8, kDensity); }},
      {"hollow-sphere", false, [](int n) { return ToPolygonMesh(HollowSphere(0.5, 0.4, n)); },
       [] { return HollowSphereProperties(0.5, 0.4, kDensity); }},
  };
  return cases;
}

const Case& Find(const std::string& name) {
  for (const Case& c : Cases()) {
    if (name == c.name) return c;
  }
  std::string known;
  for (const Case& c : Cases()) known += (known.empty() ? "" : ", ") + std::string(c.name);
  throw std::invalid_argument("unknown solid '" + name + "' (" + known + ")");
}

long long Triangles(const PolygonMesh& m) {
  long long t = 0;
  for (std::int64_t f = 0; f < m.num_faces(); ++f) t += m.face_size(f) - 2;
  return t;
}

}  // namespace

std::vector<std::string> ValidationSolids() {
  std::vector<std::string> names;
  for (const Case& c : Cases()) names.emplace_back(c.name);
  return names;
}

std::vector<ConvergenceRow> ValidateClosedForms(const ValidationOptions& options) {
  const std::vector<std::string> names = options.solids.empty() ? ValidationSolids() : options.solids;
  for (int n : options.resolutions) {
    if (n < 3) throw std::invalid_argument("resolutions must be 3 or more");
  }
  // Far away: turned about a skew axis and moved 10^5 sizes (the sizes here are about 1 m).
  const Matrix3 turn = Eigen::AngleAxisd(0.7, Vector3(1, 2, 3).normalized()).toRotationMatrix();
  const Vector3 away(1e5, -1e5, 1e5);
  std::vector<ConvergenceRow> rows;
  for (const std::string& name : names) {
    const Case& c = Find(name);
    const MassProperties truth_here = c.closed_form();
    const std::vector<int> resolutions = c.exact ? std::vector<int>{0} : options.resolutions;
    for (bool far : {false, true}) {
      const MassProperties truth = far ? Transformed(truth_here, turn, away) : truth_here;
      for (const char* path : {"triangles", "polygons"}) {
        double previous_v = std::numeric_limits<double>::quiet_NaN(), previous_i = previous_v;
        for (int n : resolutions) {
          PolygonMesh mesh = c.mesh(n);
          if (far) mesh.V = ((mesh.V * turn.transpose()).rowwise() + away.transpose()).eval();
          const double size = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
          MassProperties got;
          if (std::string(path) == "triangles") {
            got = ComputeMassProperties(Triangulate(mesh), kDensity);
          } else {
            got = ComputeMassProperties(mesh, kDensity);
          }
          ConvergenceRow r;
          r.solid = name;
          r.resolution = n;
          r.triangles = Triangles(mesh);
          r.path = path;
          r.far = far;
          r.volume_error = std::abs(got.volume - truth.volume) / truth.volume;
          r.com_error = (got.center_of_mass - truth.center_of_mass).norm() / size;
          r.inertia_error = (got.inertia_com - truth.inertia_com).norm() / truth.inertia_com.norm();
          const double nan = std::numeric_limits<double>::quiet_NaN();
          r.volume_order = c.exact ? nan : std::log2(previous_v / r.volume_error);
          r.inertia_order = c.exact ? nan : std::log2(previous_i / r.inertia_error);
          previous_v = r.volume_error;
          previous_i = r.inertia_error;
          rows.push_back(r);
        }
      }
    }
  }
  return rows;
}

}  // namespace massprops
