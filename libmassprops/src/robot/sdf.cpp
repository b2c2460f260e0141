// SDFormat: <link> elements (in <model>s, nested or in a <world>); their <collision> (or
// <visual>) elements each hold a <pose> (x y z roll pitch yaw; radians unless degrees="true";
// or x y z qx qy qz qw with rotation_format="quat_xyzw") relative to the link, and a <geometry>
// with one <box><size>, <sphere><radius>, <cylinder><radius><length>, <capsule><radius><length>,
// <ellipsoid><radii> or <mesh><uri><scale>.

#include <cmath>
#include <string>

#include "massprops/export.h"
#include "robot_internal.h"

namespace massprops::robot {
namespace {

std::string Text(pugi::xml_node parent, const char* child, const std::string& what) {
  const pugi::xml_node n = parent.child(child);
  if (!n) throw ElementError(what + ": no <" + child + ">");
  return n.text().get();
}

void ReadPose(pugi::xml_node element, const std::string& link, Geometry& g, const std::string& what) {
  const pugi::xml_node pose = element.child("pose");
  if (!pose) return;
  const std::string relative_to = pose.attribute("relative_to").value();
  if (!relative_to.empty() && relative_to != link) {
    throw ElementError(what + ": <pose relative_to=\"" + relative_to +
                       "\"> names another frame than its link (only poses relative to the link are followed)");
  }
  const std::string format = pose.attribute("rotation_format").value();
  if (format == "quat_xyzw") {
    const auto v = Numbers(pose.text().get(), 7, what + " <pose>");
    g.translation = Vector3(v[0], v[1], v[2]);
    g.rotation = FromQuaternion(v[6], v[3], v[4], v[5], what + " <pose>");
    return;
  }
  if (!format.empty() && format != "euler_rpy") {
    throw ElementError(what + ": <pose rotation_format=\"" + format + "\"> is not euler_rpy or quat_xyzw");
  }
  const auto v = Numbers(pose.text().get(), 6, what + " <pose>");
  const double unit = pose.attribute("degrees").as_bool() ? M_PI / 180 : 1.0;
  g.translation = Vector3(v[0], v[1], v[2]);
  g.rotation = FromRollPitchYaw(v[3] * unit, v[4] * unit, v[5] * unit);
}

Geometry ReadGeometry(pugi::xml_node element, const std::string& link, const std::string& what, const Document& doc,
                      const FillOptions& options) {
  Geometry g;
  g.where = what;
  ReadPose(element, link, g, what);
  const pugi::xml_node geometry = element.child("geometry");
  if (!geometry) throw ElementError(what + ": no <geometry>");
  const pugi::xml_node shape = geometry.find_child([](pugi::xml_node n) { return n.type() == pugi::node_element; });
  if (!shape) throw ElementError(what + ": an empty <geometry>");
  const std::string kind = shape.name();
  const std::string in = what + " <" + kind + ">";
  if (kind == "box" || kind == "sphere" || kind == "cylinder" || kind == "capsule" || kind == "ellipsoid") {
    std::vector<double> sizes;  // as SDFormat names them (massprops::SizeKeys)
    for (const SizeKey& k : SizeKeys(kind, SizeSyntax::kRobot)) {
      const std::string label = in + " <" + k.key + ">";
      if (k.components == 3) {
        for (double v : Numbers(Text(shape, k.key, in), 3, label)) {
          if (!(v > 0)) throw ElementError(label + " must be positive");
          sizes.push_back(v);
        }
      } else {
        sizes.push_back(Positive(Text(shape, k.key, in), label));
      }
    }
    g.shape = MakePrimitive(kind, sizes);
  } else if (kind == "mesh") {
    if (shape.child("submesh")) throw ElementError(in + ": <submesh> (one piece of a mesh file) is not followed");
    MeshRef mesh;
    mesh.path = ResolveUri(Text(shape, "uri", in), doc, options);
    if (const pugi::xml_node scale = shape.child("scale")) {
      const auto s = Numbers(scale.text().get(), 3, in + " <scale>");
      mesh.scale = Vector3(s[0], s[1], s[2]);
    }
    g.shape = mesh;
  } else {
    throw ElementError(what + ": <" + kind + "> is not a geometry this reader knows");
  }
  return g;
}

}  // namespace

std::vector<Link> SdfLinks(Document& doc, const FillOptions& options) {
  std::vector<Link> links;
  const char* tag = options.from == GeometrySource::kVisual ? "visual" : "collision";
  for (const pugi::xml_node element : FindElements(doc.xml.child("sdf"), "link")) {
    Link link;
    link.element = element;
    link.name = element.attribute("name").value();
    if (link.name.empty()) link.name = Describe(element, static_cast<int>(links.size()) + 1);
    if (const pugi::xml_node mass = element.child("inertial").child("mass")) link.stated_mass = mass.text().as_double();
    ReadGeometries(link, tag, [&](pugi::xml_node geometry, const std::string& what) {
      return ReadGeometry(geometry, link.name, what, doc, options);
    });
    links.push_back(std::move(link));
  }
  return links;
}

void WriteSdfInertial(Link& link, const MassProperties& mp) {
  ReplaceOrInsert(link.element, link.element.child("inertial"), SdfInertial(mp));
}

}  // namespace massprops::robot
