// Pictures of resting poses (pose_picture.h).

#include "pose_picture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>

#include "massprops/report/atomic_file.h"

namespace rbsim {
namespace {

using massprops::Matrix3;
using massprops::Vector3;

struct Panel {
  double x0, width, height;  // where it sits in the picture, px
};

// An orthographic view: world → camera (x right, y up, z towards the viewer).
Matrix3 Camera(double azimuth_degrees, double elevation_degrees) {
  const double a = azimuth_degrees * massprops::kPi / 180, e = elevation_degrees * massprops::kPi / 180;
  const Vector3 toward(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));  // to the viewer
  const Vector3 right = Vector3::UnitZ().cross(toward).normalized();
  const Vector3 up = toward.cross(right);
  Matrix3 c;
  c.row(0) = right.transpose();
  c.row(1) = up.transpose();
  c.row(2) = toward.transpose();
  return c;
}

// Draws the triangles of `v` (already placed) seen through `camera` into the panel; triangles
// with `marked[f]` in colour. `ground` adds the plane z = 0 as a line under the part.
void Draw(std::ostringstream& svg, const massprops::TriangleMesh& mesh, const std::vector<Vector3>& v,
          const std::vector<bool>& marked, const Matrix3& camera, const Panel& panel, bool ground,
          const std::vector<Vector3>& face) {
  std::vector<Vector3> p(v.size());
  Eigen::AlignedBox3d box;
  for (std::size_t i = 0; i < v.size(); ++i) {
    p[i] = camera * v[i];
    box.extend(p[i]);
  }
  std::vector<Vector3> floor;  // the plane z = 0 as a square around the part's footprint
  if (ground) {
    double r = 0;
    for (const Vector3& x : v) r = std::max(r, Eigen::Vector2d(x.x(), x.y()).norm());
    r *= 1.15;
    floor = {Vector3(-r, -r, 0), Vector3(r, -r, 0), Vector3(r, r, 0), Vector3(-r, r, 0)};
    for (const Vector3& x : floor) box.extend(camera * x);
  }
  const double margin = 20;
  const double scale = std::min((panel.width - 2 * margin) / std::max(box.sizes().x(), 1e-12),
                                (panel.height - 2 * margin - 30) / std::max(box.sizes().y(), 1e-12));
  auto to_px = [&](const Vector3& q) {
    return Eigen::Vector2d(panel.x0 + panel.width / 2 + scale * (q.x() - box.center().x()),
                           30 + panel.height / 2 - scale * (q.y() - box.center().y()));
  };
  auto polygon = [&](const std::vector<Vector3>& corners, const char* style) {
    svg << "<polygon points='";
    for (const Vector3& x : corners) {
      const auto q = to_px(camera * x);
      svg << q.x() << "," << q.y() << " ";
    }
    svg << "' " << style << "/>\n";
  };
  if (ground) polygon(floor, "fill='#e4e4dc' stroke='#999' stroke-width='1'");  // under everything
  const Vector3 light = Vector3(0.3, 0.5, 1).normalized();                      // camera axes
  std::vector<std::pair<double, Eigen::Index>> order;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Vector3 &a = p[static_cast<std::size_t>(mesh.F(f, 0))], &b = p[static_cast<std::size_t>(mesh.F(f, 1))],
                  &c = p[static_cast<std::size_t>(mesh.F(f, 2))];
    const Vector3 n = (b - a).cross(c - a);
    if (!(n.z() > 0)) continue;  // facing away
    order.emplace_back((a.z() + b.z() + c.z()) / 3, f);
  }
  std::sort(order.begin(), order.end());  // far first
  char buffer[160];
  for (const auto& [depth, f] : order) {
    (void)depth;
    const Vector3 &a = p[static_cast<std::size_t>(mesh.F(f, 0))], &b = p[static_cast<std::size_t>(mesh.F(f, 1))],
                  &c = p[static_cast<std::size_t>(mesh.F(f, 2))];
    const double shade = 0.35 + 0.65 * std::max(0.0, (b - a).cross(c - a).normalized().dot(light));
    const Vector3 base = marked[static_cast<std::size_t>(f)] ? Vector3(0.85, 0.25, 0.2) : Vector3(0.75, 0.78, 0.82);
    const Vector3 rgb = 255 * shade * base;
    const auto pa = to_px(a), pb = to_px(b), pc = to_px(c);
    std::snprintf(buffer, sizeof buffer,
                  "<polygon points='%.1f,%.1f %.1f,%.1f %.1f,%.1f' fill='#%02x%02x%02x' stroke='#%02x%02x%02x' "
                  "stroke-width='0.6' stroke-linejoin='round'/>\n",
                  pa.x(), pa.y(), pb.x(), pb.y(), pc.x(), pc.y(), static_cast<int>(rgb.x()), static_cast<int>(rgb.y()),
                  static_cast<int>(rgb.z()), static_cast<int>(rgb.x()), static_cast<int>(rgb.y()),
                  static_cast<int>(rgb.z()));
    svg << buffer;
  }
  if (!face.empty()) polygon(face, "fill='#d9402f' fill-opacity='0.45' stroke='#b02010' stroke-width='2'");
}

}  // namespace

void WritePosePicture(const std::string& path, const massprops::TriangleMesh& mesh, const dynamics::poses::Pose& pose,
                      const std::vector<Vector3>& face, const std::string& title) {
  // The mesh triangles on the resting plane: every corner within a hair of the hull's face.
  std::vector<Vector3> file(static_cast<std::size_t>(mesh.V.rows()));
  double reach = -std::numeric_limits<double>::infinity(), size = 0;
  for (std::size_t i = 0; i < file.size(); ++i) {
    file[i] = mesh.V.row(static_cast<Eigen::Index>(i)).transpose();
    reach = std::max(reach, pose.normal.dot(file[i]));
  }
  for (const Vector3& x : file) size = std::max(size, x.norm());
  std::vector<bool> marked(static_cast<std::size_t>(mesh.F.rows()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    bool on = true;
    for (int k = 0; k < 3; ++k)
      on = on && pose.normal.dot(file[static_cast<std::size_t>(mesh.F(f, k))]) > reach - 1e-6 * size;
    marked[static_cast<std::size_t>(f)] = on;
  }
  std::vector<Vector3> rest(file.size());
  for (std::size_t i = 0; i < file.size(); ++i) rest[i] = pose.rotation * file[i] + pose.translation;

  const double w = 420, h = 360;
  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << 2 * w << "' height='" << h + 30 << "' viewBox='0 0 "
      << 2 * w << " " << h + 30 << "'>\n<rect width='100%' height='100%' fill='white'/>\n"
      << "<text x='10' y='22' font-family='sans-serif' font-size='16'>" << title << "</text>\n"
      << "<text x='10' y='44' font-family='sans-serif' font-size='12' fill='#444'>at rest on the plane</text>\n"
      << "<text x='" << w + 10
      << "' y='44' font-family='sans-serif' font-size='12' fill='#444'>in the file's axes: the hull face it rests on "
         "in red</text>\n";
  Draw(svg, mesh, rest, marked, Camera(-60, 20), Panel{0, w, h}, true, {});
  // The second view looks at the resting face from outside, tilted a little for depth.
  const Vector3 n = pose.normal;
  const double azimuth = std::atan2(n.y(), n.x()) * 180 / massprops::kPi + 15;
  const double elevation = std::clamp(std::asin(std::clamp(n.z(), -1.0, 1.0)) * 180 / massprops::kPi + 15, -89.0, 89.0);
  Draw(svg, mesh, file, marked, Camera(azimuth, elevation), Panel{w, w, h}, false, face);
  svg << "</svg>\n";
  massprops::report::WriteFileAtomically(path, svg.str());
}

}  // namespace rbsim
