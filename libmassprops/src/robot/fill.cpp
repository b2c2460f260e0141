// massprops::robot: reads a robot description, computes each link from its geometries and
// writes the inertials back (robot.h).

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "massprops/composition.h"
#include "massprops/robot/robot.h"
#include "massprops/text.h"
#include "robot/robot_internal.h"

namespace massprops {

const char* RobotFormatName(RobotFormat format) {
  switch (format) {
    case RobotFormat::kUrdf: return "urdf";
    case RobotFormat::kSdf: return "sdf";
    case RobotFormat::kMjcf: return "mjcf";
  }
  return "?";
}

bool FillResult::AllFilled() const {
  for (const LinkFill& l : links) {
    if (l.status == LinkStatus::kFailed) return false;
  }
  return true;
}

namespace {

using robot::Document;
using robot::FormatOf;
using robot::Geometry;
using robot::Link;
using robot::Parse;

// Mass properties of the meshes, at unit density, each read and checked once.
class MeshCache {
 public:
  explicit MeshCache(const LoadOptions& load) : load_(load) {
    load_.mass = Density{1.0};
    load_.parts = false;
    load_.part_masses.clear();
    load_.hull = false;
    load_.exact = false;
    load_.progress = nullptr;
  }
  const SolidResult& Get(const std::string& path) {
    auto it = cache_.find(path);
    if (it == cache_.end()) it = cache_.emplace(path, LoadSolid(path, load_)).first;
    return it->second;
  }

 private:
  LoadOptions load_;
  std::map<std::string, SolidResult> cache_;
};

// The geometry at unit density, in the link frame; findings go to `notes`.
MassProperties UnitDensity(const Geometry& g, MeshCache& meshes, std::vector<Advice>& notes) {
  MassProperties mp;
  if (const auto* p = std::get_if<Primitive>(&g.shape)) {
    mp = ClosedForm(*p, 1.0);
  } else {
    const auto& mesh = std::get<robot::MeshRef>(g.shape);
    const SolidResult& r = meshes.Get(mesh.path);
    for (const Finding& f : r.findings) {
      // The size the scale gives it is the one that matters: unit guesses about the raw file
      // do not apply.
      if (f.kind != FindingKind::kUnitSuspicion) notes.push_back(f.message.After(g.where + ": "));
    }
    mp = mesh.scale == Vector3::Ones() ? r.mp : Scaled(r.mp, mesh.scale);
  }
  if (!(std::isfinite(mp.volume) && mp.volume > 0 && mp.inertia_com.allFinite() && mp.center_of_mass.allFinite())) {
    throw std::runtime_error(g.where + ": its volume or inertia is not a finite positive number (volume " +
                             ExactDecimal(mp.volume) + " m^3): a scale or size out of range");
  }
  return Transformed(mp, g.rotation, g.translation);
}

// `mp` with its mass scaled to `mass` (same shape, same center of mass).
MassProperties WithMass(MassProperties mp, double mass) {
  const double k = mass / mp.mass;
  mp.mass = mass;
  mp.inertia_com *= k;
  mp.density *= k;
  return mp;
}

LinkFill Compute(const Link& link, const FillOptions& options, MeshCache& meshes) {
  LinkFill out;
  out.name = link.name;
  for (const std::string& n : link.notes) out.notes.emplace_back(n);
  if (!link.error.empty()) {
    out.status = LinkStatus::kFailed;
    out.message = Advice(link.error);
    return out;
  }
  // MJCF geoms of mass or density 0 collide but weigh nothing.
  const bool weighs =
      std::any_of(link.geometries.begin(), link.geometries.end(), [](const Geometry& g) { return !g.massless; });
  if (!weighs) {
    out.status = LinkStatus::kNoGeometry;
    return out;
  }
  const PartMass* entry = MatchPart(options.link_masses, link.name);
  try {
    std::vector<MassProperties> parts;
    for (const Geometry& g : link.geometries) {
      if (g.massless) continue;
      const MassProperties unit = UnitDensity(g, meshes, out.notes);
      if (entry != nullptr && std::holds_alternative<Density>(entry->mass)) {
        parts.push_back(AtDensity(unit, std::get<Density>(entry->mass).value));
      } else if (entry == nullptr && g.own && std::holds_alternative<TotalMass>(*g.own)) {
        parts.push_back(WithMass(AtDensity(unit, 1.0), std::get<TotalMass>(*g.own).value));
      } else if (entry == nullptr && g.own) {
        parts.push_back(AtDensity(unit, std::get<Density>(*g.own).value));
      } else {
        parts.push_back(AtDensity(unit, options.density));
      }
    }
    out.mp = Combine(parts);
    out.geometries = static_cast<int>(parts.size());
    if (entry != nullptr && std::holds_alternative<TotalMass>(entry->mass)) {
      out.mp = WithMass(out.mp, std::get<TotalMass>(entry->mass).value);
    } else if (options.keep_mass && link.stated_mass) {
      if (!(*link.stated_mass > 0)) throw std::runtime_error("its stated mass is not positive");
      out.mp = WithMass(out.mp, *link.stated_mass);
      out.notes.emplace_back("mass kept: " + ExactDecimal(*link.stated_mass) + " kg");
    } else if (options.keep_mass) {
      out.notes.emplace_back("no mass to keep: computed at the density");
    }
  } catch (const LoadError& e) {
    out.status = LinkStatus::kFailed;
    out.message = Advice(e.text());
    return out;
  } catch (const std::exception& e) {
    out.status = LinkStatus::kFailed;
    out.message = Advice(e.what());
    return out;
  }
  if (!(std::isfinite(out.mp.mass) && out.mp.mass > 0 && out.mp.center_of_mass.allFinite() &&
        out.mp.inertia_com.allFinite())) {
    out.status = LinkStatus::kFailed;
    out.message = Advice("its mass properties are not finite (mass " + ExactDecimal(out.mp.mass) +
                         " kg): a scale or size out of range");
    return out;
  }
  out.principal = ComputePrincipalInertia(out.mp.inertia_com);
  out.status = LinkStatus::kFilled;
  return out;
}

}  // namespace

namespace robot {

std::vector<LinkFill> ComputeLinkFills(const std::vector<Link>& links, const FillOptions& options) {
  MeshCache meshes(options.load);
  std::vector<LinkFill> out;
  for (const Link& link : links) out.push_back(Compute(link, options, meshes));
  return out;
}

}  // namespace robot

RobotFormat DetectRobotFormat(const std::string& path) {
  Document doc;
  Parse(doc, path);
  return FormatOf(doc);
}

FillResult FillRobotDescription(const std::string& path, const FillOptions& options) {
  if (!(std::isfinite(options.density) && options.density > 0)) {
    throw std::invalid_argument("the density must be finite and positive");
  }
  Document doc;
  Parse(doc, path);
  FillResult result;
  result.format = FormatOf(doc);
  if (result.format == RobotFormat::kMjcf) {  // (the fill is written into the file as it is)
    for (const char* tag : {"frame", "replicate"}) {
      if (robot::FindElement(doc.xml.document_element(), tag)) {
        throw std::runtime_error(path + ": <" + tag +
                                 "> (MuJoCo 3) places bodies and geoms that massprops fill would have to move to "
                                 "write their inertials: not filled (rbsim and the model reader follow it)");
      }
    }
  }
  std::vector<Link> links = result.format == RobotFormat::kUrdf  ? robot::UrdfLinks(doc, options)
                            : result.format == RobotFormat::kSdf ? robot::SdfLinks(doc, options)
                                                                 : robot::MjcfLinks(doc, options);
  std::vector<std::string> names;
  for (const Link& l : links) names.push_back(l.name);
  if (const PartMass* entry = FirstUnmatched(options.link_masses, names)) {
    throw std::invalid_argument("the density map's entry '" + entry->pattern + "' matches no link of " + path);
  }
  result.links = robot::ComputeLinkFills(links, options);
  for (std::size_t k = 0; k < links.size(); ++k) {
    const LinkFill& fill = result.links[k];
    if (fill.status != LinkStatus::kFilled) continue;
    if (result.format == RobotFormat::kUrdf) robot::WriteUrdfInertial(links[k], fill.mp);
    if (result.format == RobotFormat::kSdf) robot::WriteSdfInertial(links[k], fill.mp);
    if (result.format == RobotFormat::kMjcf) robot::WriteMjcfInertial(links[k], fill.mp, fill.principal);
  }
  result.notes = doc.notes;
  // What precedes and follows the root element (the declaration, comments, line breaks) is
  // copied from the file as it was: pugixml keeps no blanks between top-level nodes.
  const pugi::xml_node root = doc.xml.document_element();
  const std::string& original = doc.text;
  const auto start = static_cast<std::size_t>(root.offset_debug());  // just past the '<'
  const std::size_t close = original.rfind(std::string("</") + root.name());
  std::size_t end = close == std::string::npos ? std::string::npos : original.find('>', close);
  if (end == std::string::npos) end = original.find_last_of('>');  // a root without children: <robot/>
  std::ostringstream text;
  if (start >= 1 && start <= original.size()) text << original.substr(0, start - 1);
  root.print(text, "", pugi::format_raw);
  if (end != std::string::npos) text << original.substr(end + 1);
  result.document = text.str();
  return result;
}

}  // namespace massprops
