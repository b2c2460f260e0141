// Resting poses from Python (massprops.resting_poses, massprops.drop_batch): the part through the
// pipeline, both estimates, and the report as `rbsim poses --format json` gives it.

#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "bodies/pose_part.h"
#include "dynamics/poses.h"

namespace py = pybind11;
namespace dp = dynamics::poses;

namespace massprops_python {
namespace {

dynamics::Material MaterialOf(const std::vector<double>& m, const char* name) {
  if (m.size() != 3)
    throw py::value_error(std::string(name) + " must be (static_friction, kinetic_friction, restitution)");
  const dynamics::Material material{m[0], m[1], m[2]};
  if (const auto fault = dynamics::CheckMaterial(material)) {
    throw py::value_error(std::string(name) + ": " + fault->field + " " + fault->problem);
  }
  return material;
}

// (the report as JSON, each drop's (pose, seconds to rest): a pose index, -1 not settled, -2 at rest
// on another face).
py::tuple RestingPoses(const std::string& path, std::int64_t first, std::int64_t count,
                       std::optional<std::vector<std::pair<int, double>>> outcomes, double height, std::uint64_t seed,
                       const std::vector<double>& ground, const std::vector<double>& material,
                       const std::string& collision, double dt, double max_time, int threads, double merge_degrees,
                       const py::kwargs& kw) {
  const massprops::LoadOptions load = LoadOptionsFrom(kw);
  if (collision != "hull" && collision != "mesh") throw py::value_error("collision must be 'hull' or 'mesh'");
  if (first < 0 || count < 0) throw py::value_error("first and count must be >= 0");
  dynamics::PosesReport report;
  report.part = path;
  report.collision = collision == "mesh" ? dynamics::PoseCollision::kMesh : dynamics::PoseCollision::kHull;
  report.drops = count;
  dp::DropOptions& o = report.options;
  o.height = height;
  o.seed = seed;
  o.ground = MaterialOf(ground, "ground");
  o.dt = dt;
  o.max_time = max_time;
  o.threads = threads;
  const dynamics::Material part_material = MaterialOf(material, "material");
  std::vector<dp::DropOutcome> drops;
  RunWithoutGil([&] {
    std::vector<std::string> findings;  // not returned: the report is the command's JSON, which has none
    report.pose_part = dynamics::LoadPosePart(path, load, report.collision, part_material, PythonWords(), findings);
    report.estimate = dp::QuasiStatic(report.pose_part, merge_degrees);
    if (outcomes) {
      if (static_cast<std::int64_t>(outcomes->size()) != count) {
        throw std::invalid_argument("outcomes: " + std::to_string(outcomes->size()) + " given for " +
                                    std::to_string(count) + " drops");
      }
      for (const auto& [pose, time] : *outcomes) {
        dp::DropOutcome d;
        d.pose = pose;
        d.time = time;
        drops.push_back(d);
      }
    } else {
      drops = dp::Drop(report.pose_part, report.estimate, o, first, count);
    }
    report.tally = dp::Count(drops, report.estimate.poses.size());
  });
  std::vector<std::pair<int, double>> poses;
  for (const dp::DropOutcome& d : drops) poses.emplace_back(d.pose, d.time);
  return py::make_tuple(dynamics::PosesJson(report), poses);
}

}  // namespace

void BindPoses(py::module_& m) {
  m.def("resting_poses", &RestingPoses, py::arg("path"), py::arg("first"), py::arg("count"),
        py::arg("outcomes") = py::none(), py::arg("height") = 0.1, py::arg("seed") = 1,
        py::arg("ground") = std::vector<double>{0.6, 0.5, 0.0},
        py::arg("material") = std::vector<double>{0.6, 0.5, 0.0}, py::arg("collision") = "hull", py::arg("dt") = 1e-3,
        py::arg("max_time") = 20.0, py::arg("threads") = 0, py::arg("merge_degrees") = 1.0,
        "Both pose estimates of a part file: (report JSON, outcome of each of the drops first .. first+count-1); "
        "with `outcomes`, the report of those outcomes (drops run elsewhere) instead of new drops");
}

}  // namespace massprops_python
