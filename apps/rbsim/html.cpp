// run.html: the run as one self-contained page (outputs.h). The page is the viewer script
// (viewer/viewer.js with three.js, bundled once by viewer/build.mjs into the committed
// viewer/viewer.bundle.js and linked into rbsim by viewer_bundle.S) and the run's data as JSON,
// both inline: it opens from file:// with no module imports and no fetches.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "html.h"
#include "outputs.h"

extern "C" const char rbsim_viewer_js[];      // viewer_bundle.S
extern "C" const char rbsim_viewer_js_end[];  // one past its last byte

namespace rbsim {
using Json = nlohmann::json;
namespace {

std::string Base64(const void* data, std::size_t size) {
  static const char* const kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* p = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (std::size_t i = 0; i < size; i += 3) {
    const std::uint32_t n = (static_cast<std::uint32_t>(p[i]) << 16) |
                            (i + 1 < size ? static_cast<std::uint32_t>(p[i + 1]) << 8 : 0u) |
                            (i + 2 < size ? static_cast<std::uint32_t>(p[i + 2]) : 0u);
    out += kDigits[(n >> 18) & 63];
    out += kDigits[(n >> 12) & 63];
    out += i + 1 < size ? kDigits[(n >> 6) & 63] : '=';
    out += i + 2 < size ? kDigits[n & 63] : '=';
  }
  return out;
}

template <typename T>
std::string Base64(const std::vector<T>& v) {
  return Base64(v.data(), v.size() * sizeof(T));
}

Json Colour(const Vector3& c) { return {c.x(), c.y(), c.z()}; }

// The run's data for the viewer (the page's schema; docs/scenes.md, "The page: run.html", describes it).
Json RunData(const Simulation& sim, const Recording& rec) {
  Json j;
  j["version"] = 1;
  j["title"] = std::filesystem::path(sim.scene.file).filename().string();
  const int up = sim.scene.up == 'x' ? 0 : sim.scene.up == 'y' ? 1 : 2;
  j["up"] = {up == 0 ? 1 : 0, up == 1 ? 1 : 0, up == 2 ? 1 : 0};
  j["times"] = rec.times;
  Eigen::AlignedBox3d bounds;
  Json bodies = Json::array();
  for (std::size_t b = 0; b < sim.bodies.size(); ++b) {
    const SimBody& body = sim.bodies[b];
    Json o = ViewerBody(body.name, body.color, body.display, rec.translations[b], rec.rotations[b]);
    if (body.visual.F.rows() > 0) {  // drawn instead of the collider, which a toggle shows
      const Json visual = ViewerStatic(body.name, body.color, body.visual);
      o["visual"] = {{"positions", visual["positions"]}, {"indices", visual["indices"]}};
    }
    double r = Reach(body);
    if (body.visual.V.rows() > 0) r = std::max(r, body.visual.V.rowwise().norm().maxCoeff());
    for (const Eigen::Vector3f& x : rec.translations[b]) {
      bounds.extend(x.cast<double>() + Vector3::Constant(r));
      bounds.extend(x.cast<double>() - Vector3::Constant(r));
    }
    if (!rec.asleep.empty()) {
      std::vector<std::uint8_t> a;
      for (const auto& sample : rec.asleep) a.push_back(sample[b]);
      o["asleep"] = Base64(a);
    }
    bodies.push_back(std::move(o));
  }
  j["bodies"] = std::move(bodies);
  Json statics = Json::array();
  for (const SimStatic& st : sim.statics) statics.push_back(ViewerStatic(st.name, st.color, st.display));
  j["statics"] = std::move(statics);
  // Spatial tendons: lines through their points, sample after sample.
  Json tendons = Json::array();
  for (std::size_t t = 0; t < rec.tendon_paths.size(); ++t) {
    const std::size_t points = sim.world().tendons()[t].path.size();
    if (points < 2) continue;
    tendons.push_back(
        {{"name", sim.world().tendons()[t].name}, {"count", points}, {"points", Base64(rec.tendon_paths[t])}});
  }
  j["tendons"] = std::move(tendons);
  j["bounds"] = ViewerBounds(bounds);
  // Contact forces: arrows as long as a twentieth of the scene for the 90th percentile of the forces.
  if (rec.contacts) {
    Json contacts = Json::array();
    std::vector<double> magnitudes;
    for (const std::vector<float>& c : rec.contact_forces) {
      contacts.push_back(Base64(c));
      for (std::size_t i = 0; i + 5 < c.size(); i += 6) {
        magnitudes.push_back(Eigen::Vector3d(c[i + 3], c[i + 4], c[i + 5]).norm());
      }
    }
    j["contacts"] = std::move(contacts);
    double typical = 0;
    if (!magnitudes.empty()) {
      const auto at = magnitudes.begin() + static_cast<std::ptrdiff_t>(magnitudes.size() * 9 / 10);
      std::nth_element(magnitudes.begin(), at, magnitudes.end());
      typical = *at;
    }
    const double size = std::max(bounds.sizes().maxCoeff(), 1e-3);
    j["force_scale"] = typical > 0 ? 0.05 * size / typical : 0.0;  // m per N
  }
  if (!rec.notes.empty()) j["notes"] = rec.notes;
  j["diagnostics"] = {{"kinetic", rec.kinetic},
                      {"potential", rec.potential},
                      {"energy_drift", rec.energy_drift},
                      {"momentum_drift", rec.momentum_drift}};
  return j;
}

}  // namespace

Json ViewerBody(const std::string& name, const Vector3& color, const massprops::TriangleMesh& mesh,
                const std::vector<Eigen::Vector3f>& translations, const std::vector<Eigen::Vector4f>& rotations) {
  Json o = ViewerStatic(name, color, mesh);
  std::vector<float> t, q;
  for (const Eigen::Vector3f& x : translations) t.insert(t.end(), {x.x(), x.y(), x.z()});
  for (const Eigen::Vector4f& r : rotations) q.insert(q.end(), {r.x(), r.y(), r.z(), r.w()});
  o["translations"] = Base64(t);
  o["rotations"] = Base64(q);
  return o;
}

Json ViewerStatic(const std::string& name, const Vector3& color, const massprops::TriangleMesh& mesh) {
  std::vector<float> positions;
  positions.reserve(static_cast<std::size_t>(mesh.V.size()));
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    for (int k = 0; k < 3; ++k) positions.push_back(static_cast<float>(mesh.V(v, k)));
  }
  std::vector<std::uint32_t> indices;
  indices.reserve(static_cast<std::size_t>(mesh.F.size()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) indices.push_back(static_cast<std::uint32_t>(mesh.F(f, k)));
  }
  return {{"name", name}, {"color", Colour(color)}, {"positions", Base64(positions)}, {"indices", Base64(indices)}};
}

Json ViewerBounds(Eigen::AlignedBox3d bounds) {
  if (bounds.isEmpty()) bounds.extend(Vector3::Zero());
  return {{"min", {bounds.min().x(), bounds.min().y(), bounds.min().z()}},
          {"max", {bounds.max().x(), bounds.max().y(), bounds.max().z()}}};
}

std::string ViewerPage(const std::string& title, const Json& data) {
  const std::string viewer(rbsim_viewer_js, static_cast<std::size_t>(rbsim_viewer_js_end - rbsim_viewer_js));
  std::string escaped;
  for (const char c : title) {
    if (c == '<') {
      escaped += "&lt;";
    } else if (c == '&') {
      escaped += "&amp;";
    } else {
      escaped += c;
    }
  }
  // "</" in the JSON (a name) cannot end its element: written "<\/", the same JSON string.
  std::string json = data.dump(-1, ' ', false, Json::error_handler_t::replace);
  for (std::size_t at = json.find("</"); at != std::string::npos; at = json.find("</", at + 3)) {
    json.replace(at, 2, "<\\/");
  }
  std::string page;
  page += "<!DOCTYPE html>\n<html lang='en'>\n<head>\n<meta charset='utf-8'>\n<title>" + escaped +
          "</title>\n<meta name='viewport' content='width=device-width, initial-scale=1'>\n</head>\n<body>\n";
  page += "<script type='application/json' id='rbsim-run'>" + json + "</script>\n<script>\n";
  page += viewer;  // viewer/build.mjs made it safe inside <script>
  page += "\n</script>\n</body>\n</html>\n";
  return page;
}

void WriteHtml(const std::string& path, const Simulation& sim, const Recording& rec) {
  massprops::report::WriteFileAtomically(
      path, ViewerPage("rbsim: " + std::filesystem::path(sim.scene.file).filename().string(), RunData(sim, rec)));
}

}  // namespace rbsim
