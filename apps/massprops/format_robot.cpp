#include "format.h"
#include "massprops/export.h"

namespace massprops::cli {

std::string FormatRobot(const SolidResult& r, Format format) {
  const std::string note = "<!-- " + r.source + ": " + ExactDecimal(r.mp.volume) + " m^3 at " +
                           ExactDecimal(r.mp.density) +
                           " kg/m^3; inertia about the center of mass, link axes = the mesh file's axes (unit " +
                           UnitName(r.unit) + ") -->\n";
  if (format == Format::kUrdf) return note + UrdfInertial(r.mp);
  if (format == Format::kSdf) return note + SdfInertial(r.mp);
  return note + MjcfInertial(r.mp, r.principal);
}

}  // namespace massprops::cli
