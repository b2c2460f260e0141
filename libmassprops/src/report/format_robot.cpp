// A result as a robot description's <inertial> (massprops/report/format.h): URDF, SDFormat or MJCF,
// through export.h.

#include "massprops/export.h"
#include "massprops/report/format.h"

namespace massprops::report {

std::string FormatRobot(const SolidResult& r, Format format) {
  std::string parts;  // an assembly: each part's inertial, then the whole's
  for (const SolidResult& part : r.parts) parts += FormatRobot(part, format);
  std::string about = r.source + (r.part.empty() ? "" : " part " + r.part) + (r.parts.empty() ? "" : " (the whole)") +
                      ": " + ExactDecimal(r.mp.volume) + " m^3 at " + ExactDecimal(r.mp.density) +
                      " kg/m^3; inertia about the center of mass, link axes = the mesh file's axes (unit " +
                      UnitName(r.unit) + ")";
  for (auto at = about.find("--"); at != std::string::npos; at = about.find("--", at)) about.replace(at, 2, "- -");
  const std::string note = parts + "<!-- " + about + " -->\n";
  std::string warnings;  // XML comments may not contain "--": the option names are spelled out
  for (const Finding& f : r.findings) {
    std::string w = Worded(f.message, CliVocabulary());
    for (auto at = w.find("--"); at != std::string::npos; at = w.find("--", at)) w.replace(at, 2, "option ");
    warnings += "<!-- warning: " + w + " -->\n";
  }
  if (format == Format::kUrdf) return note + warnings + UrdfInertial(r.mp);
  if (format == Format::kSdf) return note + warnings + SdfInertial(r.mp);
  return note + warnings + MjcfInertial(r.mp, r.principal);
}

}  // namespace massprops::report
