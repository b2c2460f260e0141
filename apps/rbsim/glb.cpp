// The animated glTF 2.0 binary (.glb) of an rbsim run (Khronos glTF 2.0 specification, sections
// "Binary glTF Layout", "Accessors" and "Animations").
//
// Layout: a root node turns the scene's world so that its up axis becomes glTF's +y; under it one
// node per body, whose mesh is the body's surface in its mesh axes relative to the center of mass
// (flat-shaded: three vertices and the face normal per triangle), and whose translation (center
// of mass) and rotation (mesh axes → world) are animated with one key per sample, LINEAR
// (quaternions slerped). All buffers are little-endian float32, each in its own 4-aligned view.

#include <cmath>
#include <cstdint>
#include <cstring>

#include <nlohmann/json.hpp>

#include "outputs.h"

namespace rbsim {
namespace {

using nlohmann::json;

constexpr int kFloat = 5126;         // GL_FLOAT
constexpr int kArrayBuffer = 34962;  // GL_ARRAY_BUFFER

class GlbBuilder {
 public:
  // Appends floats as a new buffer view + accessor; returns the accessor index.
  int AddAccessor(const std::vector<float>& values, int components, const char* type, bool vertex_attribute,
                  bool with_bounds) {
    const std::size_t offset = bin_.size();
    bin_.resize(offset + values.size() * sizeof(float));
    std::memcpy(bin_.data() + offset, values.data(), values.size() * sizeof(float));
    while (bin_.size() % 4 != 0) bin_.push_back(0);
    json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * sizeof(float)}};
    if (vertex_attribute) view["target"] = kArrayBuffer;
    views_.push_back(view);
    const std::size_t count = values.size() / static_cast<std::size_t>(components);
    json acc = {{"bufferView", views_.size() - 1}, {"componentType", kFloat}, {"count", count}, {"type", type}};
    if (with_bounds) {
      std::vector<float> lo(static_cast<std::size_t>(components), INFINITY),
          hi(static_cast<std::size_t>(components), -INFINITY);
      for (std::size_t i = 0; i < values.size(); ++i) {
        const std::size_t c = i % static_cast<std::size_t>(components);
        lo[c] = std::min(lo[c], values[i]);
        hi[c] = std::max(hi[c], values[i]);
      }
      acc["min"] = lo;
      acc["max"] = hi;
    }
    accessors_.push_back(acc);
    return static_cast<int>(accessors_.size()) - 1;
  }

  std::string Finish(json doc) const {
    doc["buffers"] = json::array({{{"byteLength", bin_.size()}}});
    doc["bufferViews"] = views_;
    doc["accessors"] = accessors_;
    std::string text = doc.dump();
    while (text.size() % 4 != 0) text += ' ';
    std::string out;
    auto u32 = [&out](std::uint32_t v) {
      for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xFFu);
    };
    const std::size_t total = 12 + 8 + text.size() + 8 + bin_.size();
    if (total > 0xFFFFFFF0u) throw std::runtime_error("the animation is larger than a .glb can hold (4 GiB)");
    u32(0x46546C67u);  // "glTF"
    u32(2);
    u32(static_cast<std::uint32_t>(total));
    u32(static_cast<std::uint32_t>(text.size()));
    u32(0x4E4F534Au);  // "JSON"
    out += text;
    u32(static_cast<std::uint32_t>(bin_.size()));
    u32(0x004E4942u);  // "BIN\0"
    out.append(reinterpret_cast<const char*>(bin_.data()), bin_.size());
    return out;
  }

 private:
  std::vector<std::uint8_t> bin_;
  json views_ = json::array();
  json accessors_ = json::array();
};

}  // namespace

void WriteGlb(const std::string& path, const Simulation& sim, const Recording& rec) {
  if (rec.times.empty()) throw std::runtime_error(path + ": nothing was recorded");
  // Animation input must increase strictly, in float32.
  std::vector<float> times(rec.times.begin(), rec.times.end());
  for (std::size_t i = 1; i < times.size(); ++i) {
    if (!(times[i] > times[i - 1])) {
      throw std::runtime_error(path + ": sample times " + std::to_string(rec.times[i - 1]) + " and " +
                               std::to_string(rec.times[i]) +
                               " s are equal in 32-bit floats (glTF's time type); lower output_rate");
    }
  }
  GlbBuilder b;
  json doc;
  doc["asset"] = {{"version", "2.0"}, {"generator", "rbsim (massprops project)"}};
  json nodes = json::array(), meshes = json::array(), materials = json::array();
  json root_children = json::array();
  json samplers = json::array(), channels = json::array();
  const int time_accessor = b.AddAccessor(times, 1, "SCALAR", false, true);

  // A mesh with one material: flat-shaded triangles (see-through when alpha < 1).
  auto add_mesh = [&](const std::string& name, const massprops::TriangleMesh& mesh, const Vector3& color,
                      double alpha = 1.0) {
    const auto& V = mesh.V;
    const auto& F = mesh.F;
    std::vector<float> pos, nrm;
    pos.reserve(static_cast<std::size_t>(F.rows()) * 9);
    nrm.reserve(static_cast<std::size_t>(F.rows()) * 9);
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      const Vector3 a = V.row(F(f, 0)), c1 = V.row(F(f, 1)), c2 = V.row(F(f, 2));
      Vector3 n = (c1 - a).cross(c2 - a);
      const double len = n.norm();
      n = len > 0 && std::isfinite(len) ? Vector3(n / len) : Vector3(0, 0, 1);
      const Eigen::Vector3f nf = n.cast<float>().normalized();
      for (const Vector3* p : {&a, &c1, &c2}) {
        for (int k = 0; k < 3; ++k) {
          pos.push_back(static_cast<float>((*p)[k]));
          nrm.push_back(nf[k]);
        }
      }
    }
    const int pos_acc = b.AddAccessor(pos, 3, "VEC3", true, true);
    const int nrm_acc = b.AddAccessor(nrm, 3, "VEC3", true, false);
    json material = {{"name", name},
                     {"pbrMetallicRoughness",
                      {{"baseColorFactor", {color.x(), color.y(), color.z(), alpha}},
                       {"metallicFactor", 0.0},
                       {"roughnessFactor", 0.6}}}};
    if (alpha < 1) material["alphaMode"] = "BLEND";
    materials.push_back(std::move(material));
    meshes.push_back({{"name", name},
                      {"primitives", json::array({{{"attributes", {{"POSITION", pos_acc}, {"NORMAL", nrm_acc}}},
                                                   {"material", materials.size() - 1},
                                                   {"mode", 4}}})}});
    return meshes.size() - 1;
  };
  // Static bodies and ground planes: fixed nodes, no animation.
  for (const SimStatic& st : sim.statics) {
    if (st.display.F.rows() == 0) continue;
    const std::size_t mesh = add_mesh(st.name, st.display, st.color);
    root_children.push_back(nodes.size() + 1);  // node 0 is the root
    nodes.push_back({{"name", st.name}, {"mesh", mesh}});
  }
  for (std::size_t i = 0; i < sim.bodies.size(); ++i) {
    const SimBody& body = sim.bodies[i];
    // A robot link with visual geometry draws it; its collision geometry is a see-through child
    // node ("... collider") that viewers can hide.
    const bool visual = body.visual.F.rows() > 0;
    const std::size_t mesh = add_mesh(body.name, visual ? body.visual : body.display, body.color);
    std::vector<float> tr, rot;
    for (const auto& t : rec.translations[i]) tr.insert(tr.end(), {t.x(), t.y(), t.z()});
    for (const auto& q : rec.rotations[i]) rot.insert(rot.end(), {q.x(), q.y(), q.z(), q.w()});
    const int tr_acc = b.AddAccessor(tr, 3, "VEC3", false, false);
    const int rot_acc = b.AddAccessor(rot, 4, "VEC4", false, false);
    const std::size_t node = nodes.size() + 1;  // node 0 is the root
    const auto& t0 = rec.translations[i].front();
    const auto& q0 = rec.rotations[i].front();
    nodes.push_back({{"name", body.name},
                     {"mesh", mesh},
                     {"translation", {t0.x(), t0.y(), t0.z()}},
                     {"rotation", {q0.x(), q0.y(), q0.z(), q0.w()}}});
    if (visual && body.display.F.rows() > 0) {
      const std::size_t collider = add_mesh(body.name + " collider", body.display, body.color, 0.35);
      nodes.back()["children"] = {node + 1};
      nodes.push_back({{"name", body.name + " collider"}, {"mesh", collider}});
    }
    root_children.push_back(node);
    samplers.push_back({{"input", time_accessor}, {"output", tr_acc}, {"interpolation", "LINEAR"}});
    channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", node}, {"path", "translation"}}}});
    samplers.push_back({{"input", time_accessor}, {"output", rot_acc}, {"interpolation", "LINEAR"}});
    channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", node}, {"path", "rotation"}}}});
  }
  // World up → glTF +y: z-up turns by −90° about x, x-up by +90° about z.
  const double h = std::sqrt(0.5);
  json root = {{"name", "world"}, {"children", root_children}};
  if (sim.scene.up == 'z') root["rotation"] = {-h, 0.0, 0.0, h};
  if (sim.scene.up == 'x') root["rotation"] = {0.0, 0.0, h, h};
  nodes.insert(nodes.begin(), root);
  doc["nodes"] = nodes;
  doc["meshes"] = meshes;
  doc["materials"] = materials;
  doc["scenes"] = json::array({{{"name", "rbsim"}, {"nodes", {0}}}});
  doc["scene"] = 0;
  doc["animations"] = json::array({{{"name", "simulation"}, {"samplers", samplers}, {"channels", channels}}});
  massprops::report::WriteFileAtomically(path, b.Finish(doc));
}

}  // namespace rbsim
