// The report of `massprops fill` (massprops/report/format.h): each link's status, what was computed
// and from what.

#include <nlohmann/json.hpp>

#include "massprops/report/format.h"

namespace massprops::report {
namespace {

using Json = nlohmann::ordered_json;

const char* StatusName(LinkStatus s) {
  return s == LinkStatus::kFilled ? "filled" : s == LinkStatus::kFailed ? "failed" : "no geometry";
}

}  // namespace

std::string FormatFillJson(const std::string& file, const std::string& output, const FillResult& r,
                           const Vocabulary& words) {
  auto vec = [](const Vector3& v) { return Json::array({v[0], v[1], v[2]}); };
  Json links = Json::array();
  for (const LinkFill& l : r.links) {
    Json j = {{"name", l.name}, {"status", StatusName(l.status)}};
    if (l.status == LinkStatus::kFilled) {
      const Matrix3& I = l.mp.inertia_com;
      j["geometries"] = l.geometries;
      j["mass"] = l.mp.mass;
      j["center_of_mass"] = vec(l.mp.center_of_mass);
      j["inertia_com"] = Json::array({vec(I.row(0)), vec(I.row(1)), vec(I.row(2))});
      j["principal_moments"] = vec(l.principal.moments);
    }
    if (l.status == LinkStatus::kFailed) j["message"] = Worded(l.message, words);
    Json notes = Json::array();
    for (const Advice& n : l.notes) notes.push_back(Worded(n, words));
    j["notes"] = notes;
    links.push_back(j);
  }
  const Json report = {
      {"file", file}, {"output", output}, {"format", RobotFormatName(r.format)}, {"links", links}, {"notes", r.notes}};
  return report.dump(2) + "\n";
}

}  // namespace massprops::report
