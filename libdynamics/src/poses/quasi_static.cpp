// The quasi-static pose estimate: hull faces, their solid angles from the center of mass, and the
// topple graph (poses.h).

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "../contact/polytope.h"
#include "dynamics/poses.h"

namespace dynamics::poses {
namespace {

using massprops::kPi;

// Solid angle of the triangle (a, b, c) seen from the origin (Van Oosterom and Strackee, IEEE
// Trans. Biomed. Eng. 30(2), 1983), positive for a counter-clockwise triangle seen from outside.
double TriangleSolidAngle(const Vector3& a, const Vector3& b, const Vector3& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double numerator = a.dot(b.cross(c));
  const double denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
  return 2 * std::atan2(numerator, denominator);
}

// Distance from p to the segment [a, b].
double SegmentDistance(const Vector3& p, const Vector3& a, const Vector3& b) {
  const Vector3 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

}  // namespace

Estimate QuasiStatic(const Part& part, double merge_degrees) {
  const massprops::MassProperties& mp = part.mass_properties;
  if (!(mp.mass > 0) || !std::isfinite(mp.mass)) throw std::invalid_argument("poses: the part's mass must be positive");
  if (!(merge_degrees >= 0 && merge_degrees < 45))
    throw std::invalid_argument("poses: merge_degrees must be in [0, 45)");
  const contact::Polytope hull = contact::MakePolytope(part.hull_vertices, part.hull_triangles);
  const Vector3 c = mp.center_of_mass;
  const std::size_t n_faces = hull.faces.size();

  double size = 0;
  for (const Vector3& v : hull.vertices) size = std::max(size, (v - c).norm());
  const double eps = 1e-9 * size;

  Estimate out;
  HullFaces& faces = out.faces;
  faces.normals = hull.normals;
  faces.solid_angles.assign(n_faces, 0.0);
  std::vector<double> height(n_faces);
  std::vector<int> next(n_faces);  // the face it topples onto (itself when stable)
  // The face across face f's edge (a, b): of the faces touching a or b, the other one whose plane
  // holds both (two faces of a convex solid share a whole edge; a tessellated edge's inner corners
  // are no face's corners, so the plane decides, not the outlines).
  auto across = [&](std::size_t f, int a, int b) {
    const Vector3 &pa = hull.vertices[static_cast<std::size_t>(a)], &pb = hull.vertices[static_cast<std::size_t>(b)];
    int best = -1;
    double best_off = std::numeric_limits<double>::infinity();
    for (int v : {a, b}) {
      for (int g : hull.vertex_faces[static_cast<std::size_t>(v)]) {
        if (g == static_cast<int>(f)) continue;
        const auto ug = static_cast<std::size_t>(g);
        const Vector3& q = hull.vertices[static_cast<std::size_t>(hull.faces[ug][0])];
        const double off = std::max(std::abs(hull.normals[ug].dot(pa - q)), std::abs(hull.normals[ug].dot(pb - q)));
        if (off < best_off || (off == best_off && g < best)) best_off = off, best = g;
      }
    }
    return best;
  };

  for (std::size_t f = 0; f < n_faces; ++f) {
    const std::vector<int>& poly = hull.faces[f];
    const Vector3& n = hull.normals[f];
    height[f] = n.dot(hull.vertices[static_cast<std::size_t>(poly[0])] - c);
    if (!(height[f] > eps)) {
      std::ostringstream msg;
      msg << "poses: the center of mass (" << c.transpose() << ") is not inside the convex hull";
      throw std::invalid_argument(msg.str());
    }
    const Vector3 p = c + height[f] * n;  // the center of mass projected onto the face's plane
    bool inside = true;
    double nearest = std::numeric_limits<double>::infinity(), beyond = -1;
    std::pair<int, int> pivot{-1, -1};  // the edge it topples over
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const int ia = poly[k], ib = poly[(k + 1) % poly.size()];
      const Vector3& a = hull.vertices[static_cast<std::size_t>(ia)];
      const Vector3& b = hull.vertices[static_cast<std::size_t>(ib)];
      Vector3 vc[3] = {a - c, b - c, hull.vertices[static_cast<std::size_t>(poly[0])] - c};
      if (k >= 1 && k + 1 < poly.size()) faces.solid_angles[f] += TriangleSolidAngle(vc[2], vc[0], vc[1]);
      // Signed distance of p outside the edge's line, within the face's plane.
      const double out_of_edge = (b - a).cross(n).normalized().dot(p - a);
      if (out_of_edge > eps) inside = false;
      // The part pivots about the edge nearest to p (at a corner: the one p is further beyond).
      const double d = SegmentDistance(p, a, b);
      if (out_of_edge > eps && (d < nearest - eps || (d <= nearest + eps && out_of_edge > beyond))) {
        nearest = d;
        beyond = out_of_edge;
        pivot = {std::min(ia, ib), std::max(ia, ib)};
      }
    }
    next[f] = static_cast<int>(f);
    if (!inside) next[f] = across(f, pivot.first, pivot.second);
  }

  // Follow the topple graph to a stable face. Toppling over an edge lowers the center of mass, so
  // the walk cannot cycle; the guard only protects against rounding at near-neutral faces.
  faces.topples_to.assign(n_faces, -1);
  for (std::size_t f = 0; f < n_faces; ++f) {
    int g = static_cast<int>(f);
    for (std::size_t steps = 0; next[static_cast<std::size_t>(g)] != g && steps < n_faces; ++steps) {
      g = next[static_cast<std::size_t>(g)];
    }
    faces.topples_to[f] = g;
  }

  faces.pose_of.assign(n_faces, -1);
  std::vector<int> stable;
  for (std::size_t f = 0; f < n_faces; ++f)
    if (faces.topples_to[f] == static_cast<int>(f)) stable.push_back(static_cast<int>(f));
  std::vector<double> captured(n_faces, 0.0);
  for (std::size_t f = 0; f < n_faces; ++f)
    captured[static_cast<std::size_t>(faces.topples_to[f])] += faces.solid_angles[f];
  // Most likely first; ties (symmetric parts) by face order, so the list is the same every run.
  std::stable_sort(stable.begin(), stable.end(), [&](int a, int b) {
    return captured[static_cast<std::size_t>(a)] > captured[static_cast<std::size_t>(b)] * (1 + 1e-12);
  });

  const double merge_cos = std::cos(merge_degrees * kPi / 180);
  for (int f : stable) {
    const auto uf = static_cast<std::size_t>(f);
    // A stable face within merge_degrees of a likelier pose's normal is that pose (a facet of a
    // tessellated flat face, a face split by a hull's rounding): its share adds to it.
    auto same = std::find_if(out.poses.begin(), out.poses.end(),
                             [&](const Pose& p) { return p.normal.dot(hull.normals[uf]) >= merge_cos; });
    if (same != out.poses.end()) {
      same->quasi_static += captured[uf] / (4 * kPi);
      same->solid_angle += faces.solid_angles[uf];
      faces.pose_of[uf] = static_cast<int>(same - out.poses.begin());
      continue;
    }
    Pose pose;
    pose.normal = hull.normals[uf];
    pose.rotation = Quaternion::FromTwoVectors(pose.normal, -Vector3::UnitZ()).toRotationMatrix();
    pose.height = height[uf];
    pose.translation = Vector3(0, 0, pose.height) - pose.rotation * c;
    pose.solid_angle = faces.solid_angles[uf];
    pose.quasi_static = captured[uf] / (4 * kPi);
    pose.outline = hull.faces[uf];
    faces.pose_of[uf] = static_cast<int>(out.poses.size());
    out.poses.push_back(std::move(pose));
  }
  // Merging may reorder the poses: most likely first again.
  std::vector<int> order(out.poses.size()), rank(out.poses.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return out.poses[static_cast<std::size_t>(a)].quasi_static >
           out.poses[static_cast<std::size_t>(b)].quasi_static * (1 + 1e-12);
  });
  std::vector<Pose> sorted;
  for (std::size_t k = 0; k < order.size(); ++k) {
    rank[static_cast<std::size_t>(order[k])] = static_cast<int>(k);
    sorted.push_back(std::move(out.poses[static_cast<std::size_t>(order[k])]));
  }
  out.poses = std::move(sorted);
  for (int& p : faces.pose_of)
    if (p >= 0) p = rank[static_cast<std::size_t>(p)];
  // The hull triangles of each pose's face.
  for (std::size_t t = 0; t < part.hull_triangles.size(); ++t) {
    const int pose = faces.pose_of[static_cast<std::size_t>(hull.triangle_faces[t])];
    if (pose >= 0) out.poses[static_cast<std::size_t>(pose)].hull_faces.push_back(static_cast<int>(t));
  }
  return out;
}

}  // namespace dynamics::poses
