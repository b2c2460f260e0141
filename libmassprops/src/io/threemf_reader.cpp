// Our own 3MF reader (3MF Core Specification 1.3): the package's root model part (found through
// _rels/.rels), its unit, its objects — meshes, and components that place other objects with a
// transform — and the build items that place objects in the print. Each build item is a part,
// named after its object. Extensions' elements (materials, beam lattices, slices) are ignored;
// a component or item in another model part (the production extension's p:path) is refused.

#include <pugixml.hpp>

#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "io/io_internal.h"
#include "io/zip.h"

namespace massprops {
namespace {

// A 3MF transform "m00 m01 m02 m10 m11 m12 m20 m21 m22 m30 m31 m32": a point (x y z 1), as a row,
// times the 4×3 matrix — p' = L p + t with L the transpose of the upper 3×3.
struct Transform {
  Matrix3 linear = Matrix3::Identity();
  Vector3 shift = Vector3::Zero();
  Transform Then(const Transform& outer) const { return {outer.linear * linear, outer.linear * shift + outer.shift}; }
};

// Element and attribute names without their namespace prefix ("m:model" is "model").
std::string_view Local(const char* name) {
  const std::string_view n(name);
  const std::size_t colon = n.find(':');
  return colon == std::string_view::npos ? n : n.substr(colon + 1);
}

pugi::xml_node Child(pugi::xml_node parent, std::string_view name) {
  for (pugi::xml_node c : parent.children()) {
    if (c.type() == pugi::node_element && Local(c.name()) == name) return c;
  }
  return {};
}

struct Object {
  std::string name;
  std::string type;
  std::vector<Vector3> vertices;
  std::vector<std::array<std::int32_t, 3>> triangles;
  std::vector<std::pair<std::int64_t, Transform>> components;
};

class Reader {
 public:
  Reader(std::string path, std::string part) : path_(std::move(path)), part_(std::move(part)) {}

  [[noreturn]] void Fail(const std::string& what) const { massprops::Fail(path_, part_ + ": " + what); }

  double Number(pugi::xml_node node, const char* attribute, const std::string& where) const {
    const pugi::xml_attribute a = node.attribute(attribute);
    if (!a) Fail(where + ": the attribute " + attribute + " is missing");
    const char* text = a.value();
    char* end = nullptr;
    const double v = std::strtod(text, &end);
    while (end && (*end == ' ' || *end == '\t' || *end == '\n' || *end == '\r')) ++end;
    if (end == text || *end != '\0') Fail(where + ": " + attribute + "=\"" + text + "\" is not a number");
    if (!std::isfinite(v)) Fail(where + ": " + attribute + "=\"" + text + "\" is not finite");
    return v;
  }

  std::int64_t Index(pugi::xml_node node, const char* attribute, const std::string& where) const {
    const pugi::xml_attribute a = node.attribute(attribute);
    if (!a) Fail(where + ": the attribute " + attribute + " is missing");
    const char* text = a.value();
    char* end = nullptr;
    const long long v = std::strtoll(text, &end, 10);
    if (end == text || *end != '\0' || v < 0) {
      Fail(where + ": " + attribute + "=\"" + text + "\" is not a non-negative integer");
    }
    return v;
  }

  Transform ReadTransform(pugi::xml_node node, const std::string& where) const {
    Transform t;
    const pugi::xml_attribute a = node.attribute("transform");
    if (!a) return t;
    double m[12];
    const char* p = a.value();
    for (double& x : m) {
      char* end = nullptr;
      x = std::strtod(p, &end);
      if (end == p || !std::isfinite(x)) Fail(where + ": transform=\"" + a.value() + "\" is not 12 finite numbers");
      p = end;
    }
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') ++p;
    if (*p != '\0') Fail(where + ": transform=\"" + a.value() + "\" has more than 12 numbers");
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) t.linear(c, r) = m[3 * r + c];
    }
    t.shift = Vector3(m[9], m[10], m[11]);
    return t;
  }

  // A reference to another model part (the production extension) is not read.
  void RefuseOtherPart(pugi::xml_node node, const std::string& where) const {
    for (pugi::xml_attribute a : node.attributes()) {
      if (Local(a.name()) == "path" && std::string_view(a.name()) != "path") {
        Fail(where + ": refers to another model part (" + a.value() +
             ", the production extension, which this reader does not follow)");
      }
    }
  }

  std::map<std::int64_t, Object> ReadObjects(pugi::xml_node resources) const {
    std::map<std::int64_t, Object> objects;
    for (pugi::xml_node node : resources.children()) {
      if (node.type() != pugi::node_element || Local(node.name()) != "object") continue;
      const std::int64_t id = Index(node, "id", "<object>");
      const std::string where = "object " + std::to_string(id);
      Object o;
      o.name = node.attribute("name").value();
      o.type = node.attribute("type") ? node.attribute("type").value() : "model";
      if (const pugi::xml_node mesh = Child(node, "mesh")) {
        for (pugi::xml_node v : Child(mesh, "vertices").children()) {
          if (v.type() != pugi::node_element || Local(v.name()) != "vertex") continue;
          const std::string at = where + ", vertex " + std::to_string(o.vertices.size());
          o.vertices.emplace_back(Number(v, "x", at), Number(v, "y", at), Number(v, "z", at));
        }
        for (pugi::xml_node t : Child(mesh, "triangles").children()) {
          if (t.type() != pugi::node_element || Local(t.name()) != "triangle") continue;
          const std::string at = where + ", triangle " + std::to_string(o.triangles.size());
          std::array<std::int32_t, 3> tri{};
          const char* keys[3] = {"v1", "v2", "v3"};
          for (int k = 0; k < 3; ++k) {
            const std::int64_t i = Index(t, keys[k], at);
            if (i >= static_cast<std::int64_t>(o.vertices.size())) {
              Fail(at + ": " + keys[k] + "=" + std::to_string(i) + " is out of range (the object has " +
                   std::to_string(o.vertices.size()) + " vertices)");
            }
            tri[static_cast<std::size_t>(k)] = static_cast<std::int32_t>(i);
          }
          o.triangles.push_back(tri);
        }
      } else if (const pugi::xml_node components = Child(node, "components")) {
        for (pugi::xml_node c : components.children()) {
          if (c.type() != pugi::node_element || Local(c.name()) != "component") continue;
          const std::string at = where + ", component " + std::to_string(o.components.size());
          RefuseOtherPart(c, at);
          o.components.emplace_back(Index(c, "objectid", at), ReadTransform(c, at));
        }
      } else {
        Fail(where + ": has neither a <mesh> nor <components>");
      }
      if (!objects.emplace(id, std::move(o)).second) Fail(where + ": the id is used by another object");
    }
    return objects;
  }

  // The object's triangles placed by `t` into `out`, components recursively.
  void Place(const std::map<std::int64_t, Object>& objects, std::int64_t id, const Transform& t, int part,
             std::vector<std::int64_t>& path, LoadedMesh& out, std::vector<Vector3>& points) const {
    const auto it = objects.find(id);
    if (it == objects.end()) Fail("no object has the id " + std::to_string(id));
    for (std::int64_t on : path) {
      if (on == id) Fail("object " + std::to_string(id) + " contains itself through its components");
    }
    if (path.size() > 64) Fail("components nested more than 64 deep");
    path.push_back(id);
    const Object& o = it->second;
    const auto base = static_cast<std::int64_t>(points.size());
    if (base + static_cast<std::int64_t>(o.vertices.size()) > (std::int64_t{1} << 31) - 1) {
      Fail("more than 2^31 vertices once every item is placed");
    }
    for (const Vector3& v : o.vertices) points.push_back(t.linear * v + t.shift);
    // A mirroring transform turns the surface inside out: keep its faces outward.
    const bool mirrored = t.linear.determinant() < 0;
    for (const auto& tri : o.triangles) {
      const auto a = static_cast<std::int32_t>(base + tri[0]), b = static_cast<std::int32_t>(base + tri[1]),
                 c = static_cast<std::int32_t>(base + tri[2]);
      out.mesh.AddFace(mirrored ? std::array<std::int32_t, 3>{a, c, b} : std::array<std::int32_t, 3>{a, b, c});
      out.face_part.push_back(part);
    }
    for (const auto& [child, placement] : o.components)
      Place(objects, child, placement.Then(t), part, path, out, points);
    path.pop_back();
  }

 private:
  std::string path_, part_;
};

// The root model part's name: the target of the package's 3D-model relationship, or the
// conventional 3D/3dmodel.model.
std::string RootModelName(const unsigned char* data, std::size_t size, const std::vector<internal::ZipEntry>& entries) {
  for (const internal::ZipEntry& e : entries) {
    if (e.name != "_rels/.rels") continue;
    const auto rels = internal::ZipRead(data, size, e, 1 << 20);
    pugi::xml_document doc;
    if (!rels || !doc.load_buffer(rels->data(), rels->size())) break;
    for (pugi::xml_node r : doc.document_element().children()) {
      const std::string type = r.attribute("Type").value();
      if (type.size() >= 8 && type.compare(type.size() - 8, 8, "/3dmodel") == 0) {
        std::string target = r.attribute("Target").value();
        if (!target.empty() && target[0] == '/') target.erase(0, 1);
        if (!target.empty()) return target;
      }
    }
  }
  return "3D/3dmodel.model";
}

}  // namespace

LoadedMesh Parse3mf(const std::string& path, std::string_view bytes, int /*num_threads: one*/) {
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const std::vector<internal::ZipEntry> entries = internal::ZipDirectory(data, bytes.size());
  if (entries.empty()) Fail(path, "not a 3MF package (no zip directory found: cut short, or not a zip)");
  const std::string root = RootModelName(data, bytes.size(), entries);
  const internal::ZipEntry* model = nullptr;
  for (const internal::ZipEntry& e : entries) {
    if (e.name == root) model = &e;
  }
  if (!model) Fail(path, "the package has no model part " + root);
  // A deflated part is at most ~1000 times its compressed size: a larger claim is a zip bomb.
  if (model->uncompressed > std::max<std::size_t>(1000 * model->compressed, 1 << 20) ||
      model->uncompressed > (std::size_t{1} << 32)) {
    Fail(path, root + ": claims " + std::to_string(model->uncompressed) + " bytes from " +
                   std::to_string(model->compressed) + " compressed, more than deflate gives");
  }
  const auto xml = internal::ZipRead(data, bytes.size(), *model, model->uncompressed);
  if (!xml || xml->size() != model->uncompressed) {
    Fail(path, root + ": cannot be inflated whole (a corrupt or cut-short package)");
  }
  const Reader reader(path, root);
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_buffer(xml->data(), xml->size());
  if (!parsed) {
    reader.Fail("not well-formed XML (at byte " + std::to_string(parsed.offset) + ": " + parsed.description() + ")");
  }
  const pugi::xml_node top = doc.document_element();
  if (Local(top.name()) != "model") reader.Fail("the root element is <" + std::string(top.name()) + ">, not <model>");

  LoadedMesh out;
  out.format = "3mf";
  const std::string unit_word = top.attribute("unit").value();
  const std::string unit_name = unit_word.empty() ? "millimeter" : unit_word;
  const std::optional<LengthUnit> unit = ModelUnitNamed(unit_name);
  if (!unit) reader.Fail("the model declares the unit '" + unit_name + "', which is not a 3MF length unit");
  out.declared_unit = *unit;
  out.declared_unit_name = unit_word.empty() ? unit_name + " (the format's default)" : unit_name;

  const std::map<std::int64_t, Object> objects = reader.ReadObjects(Child(top, "resources"));
  const pugi::xml_node build = Child(top, "build");
  std::vector<Vector3> points;
  std::map<std::string, int> names_used;
  int item_count = 0;
  for (pugi::xml_node item : build.children()) {
    if (item.type() != pugi::node_element || Local(item.name()) != "item") continue;
    const std::string where = "build item " + std::to_string(item_count++);
    reader.RefuseOtherPart(item, where);
    const std::int64_t id = reader.Index(item, "objectid", where);
    const auto it = objects.find(id);
    if (it == objects.end()) reader.Fail(where + ": no object has the id " + std::to_string(id));
    // Support structures are not part of the object's mass.
    if (it->second.type == "support") continue;
    std::string name = it->second.name.empty() ? "object " + std::to_string(id) : it->second.name;
    if (const int seen = names_used[name]++; seen > 0) name += " (" + std::to_string(seen + 1) + ")";
    const int part = static_cast<int>(out.part_names.size());
    out.part_names.push_back(name);
    std::vector<std::int64_t> path_of_ids;
    reader.Place(objects, id, reader.ReadTransform(item, where), part, path_of_ids, out, points);
  }
  if (item_count == 0) reader.Fail("the <build> places no item: nothing to compute");
  if (out.mesh.num_faces() == 0) reader.Fail("the items placed have no triangles");
  out.mesh.V.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) out.mesh.V.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  if (out.part_names.size() == 1) {  // one item: the whole file, no parts to name
    out.part_names.clear();
    out.face_part.clear();
  }
  return out;
}

}  // namespace massprops
