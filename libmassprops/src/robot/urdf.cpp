// URDF: <link> elements; their <collision> (or <visual>) elements each hold an <origin xyz rpy>
// and a <geometry> with one <box size>, <cylinder radius length>, <sphere radius>,
// <capsule radius length> or <mesh filename scale>.

#include "massprops/export.h"
#include "robot_internal.h"

namespace massprops::robot {
namespace {

// The pose of an element with an optional <origin xyz="" rpy="">.
void ReadOrigin(pugi::xml_node element, Geometry& g, const std::string& what) {
  const pugi::xml_node origin = element.child("origin");
  if (!origin) return;
  if (const pugi::xml_attribute xyz = origin.attribute("xyz")) {
    const auto t = Numbers(xyz.value(), 3, what + " <origin xyz>");
    g.translation = Vector3(t[0], t[1], t[2]);
  }
  if (const pugi::xml_attribute rpy = origin.attribute("rpy")) {
    const auto a = Numbers(rpy.value(), 3, what + " <origin rpy>");
    g.rotation = FromRollPitchYaw(a[0], a[1], a[2]);
  }
}

Geometry ReadGeometry(pugi::xml_node element, const std::string& what, const Document& doc,
                      const FillOptions& options) {
  Geometry g;
  g.where = what;
  ReadOrigin(element, g, what);
  const pugi::xml_node geometry = element.child("geometry");
  if (!geometry) throw ElementError(what + ": no <geometry>");
  const pugi::xml_node shape = geometry.find_child([](pugi::xml_node n) { return n.type() == pugi::node_element; });
  if (!shape) throw ElementError(what + ": an empty <geometry>");
  const std::string kind = shape.name();
  auto attr = [&](const char* name) {
    const pugi::xml_attribute a = shape.attribute(name);
    if (!a) throw ElementError(what + ": <" + kind + "> has no " + name);
    return std::string(a.value());
  };
  if (kind == "box" || kind == "sphere" || kind == "cylinder" || kind == "capsule") {
    std::vector<double> sizes;  // as URDF names them (massprops::SizeKeys)
    for (const SizeKey& k : SizeKeys(kind, SizeSyntax::kRobot)) {
      const std::string label = "<" + kind + " " + k.key + ">";
      if (k.components == 3) {
        for (double v : Numbers(attr(k.key), 3, what + " " + label)) {
          if (!(v > 0)) throw ElementError(what + ": " + label + " must be positive");
          sizes.push_back(v);
        }
      } else {
        sizes.push_back(Positive(attr(k.key), what + " " + label));
      }
    }
    g.shape = MakePrimitive(kind, sizes);
  } else if (kind == "mesh") {
    MeshRef mesh;
    mesh.path = ResolveUri(attr("filename"), doc, options);
    if (const pugi::xml_attribute scale = shape.attribute("scale")) {
      const auto s = Numbers(scale.value(), 3, what + " <mesh scale>");
      mesh.scale = Vector3(s[0], s[1], s[2]);
    }
    g.shape = mesh;
  } else {
    throw ElementError(what + ": <" + kind + "> is not a geometry this reader knows");
  }
  return g;
}

}  // namespace

std::vector<Link> UrdfLinks(Document& doc, const FillOptions& options) {
  std::vector<Link> links;
  const char* tag = options.from == GeometrySource::kVisual ? "visual" : "collision";
  for (pugi::xml_node element : doc.xml.child("robot").children("link")) {
    Link link;
    link.element = element;
    link.name = element.attribute("name").value();
    if (link.name.empty()) link.name = Describe(element, static_cast<int>(links.size()) + 1);
    if (const pugi::xml_node inertial = element.child("inertial")) {
      if (const pugi::xml_attribute m = inertial.child("mass").attribute("value")) {
        link.stated_mass = m.as_double();
      }
    }
    ReadGeometries(link, tag, [&](pugi::xml_node geometry, const std::string& what) {
      return ReadGeometry(geometry, what, doc, options);
    });
    links.push_back(std::move(link));
  }
  return links;
}

void WriteUrdfInertial(Link& link, const MassProperties& mp) {
  ReplaceOrInsert(link.element, link.element.child("inertial"), UrdfInertial(mp));
}

}  // namespace massprops::robot
