// Stand-ins for a build without CGAL (MASSPROPS_WITH_CGAL=OFF): the repair and the
// self-intersection checks say precisely why they cannot run.

#include <stdexcept>

#include "massprops/repair/exact.h"
#include "massprops/repair/repair.h"

namespace massprops {
namespace {
[[noreturn]] void Unavailable(const char* what) {
  throw std::runtime_error(std::string(what) +
                           " needs CGAL, and this build of massprops was configured without it "
                           "(MASSPROPS_WITH_CGAL=OFF)");
}
}  // namespace

RepairedMesh RepairMesh(const PolygonMesh&, const RepairOptions&) { Unavailable("the repair"); }

PolygonMesh UnionOfShells(const PolygonMesh&, std::int64_t&) { Unavailable("the union of overlapping shells"); }

std::int64_t CountSelfIntersections(const PolygonMesh&, const SelfIntersectionOptions&) {
  Unavailable("the self-intersection check");
}

PolygonMesh ConvexHull(const PolygonMesh&) { Unavailable("the convex hull"); }

ExactMassProperties ExactMassPropertiesOf(const PolygonMesh&, double, const MassSpec&, int) {
  Unavailable("exact integration (GMP, MPFR)");
}

}  // namespace massprops
