#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <vector>

#include "massprops/mesh_topology.h"

namespace massprops {
namespace {

std::int32_t Find(std::vector<std::int32_t>& parent, std::int32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

}  // namespace

std::string MeshTopology::Problems() const {
  std::ostringstream msg;
  const char* sep = "";
  if (boundary_edges > 0) {
    msg << sep << "open mesh: " << boundary_edges << " boundary edges in " << holes
        << (holes == 1 ? " hole" : " holes");
    sep = "; ";
  }
  if (unbalanced_edges > 0) {
    msg << sep << unbalanced_edges
        << " non-manifold edges (shared by more than two faces) with unmatched orientations";
    sep = "; ";
  }
  if (inconsistent_edges > 0) {
    msg << sep << "inconsistent orientation: " << inconsistent_edges
        << " edges where neighbouring faces disagree";
  }
  return msg.str();
}

MeshTopology AnalyzeTopology(const PolygonMesh& mesh) {
  MeshTopology t;
  t.faces = mesh.num_faces();
  const auto nv = static_cast<std::int32_t>(mesh.V.rows());
  std::vector<char> used(static_cast<std::size_t>(nv), 0);
  std::vector<std::int32_t> parent(static_cast<std::size_t>(nv));
  std::iota(parent.begin(), parent.end(), 0);
  // Each directed edge as (min << 33 | max << 1 | reversed).
  std::vector<std::uint64_t> edges;
  edges.reserve(mesh.indices.size());
  for (std::int64_t f = 0; f < t.faces; ++f) {
    const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
    const int n = mesh.face_size(f);
    bool degenerate = false;
    for (int k = 0; k < n; ++k) {
      const std::uint32_t a = static_cast<std::uint32_t>(idx[k]);
      const std::uint32_t b = static_cast<std::uint32_t>(idx[(k + 1) % n]);
      used[a] = 1;
      if (a == b) {
        degenerate = true;
        continue;
      }
      parent[Find(parent, idx[k])] = Find(parent, idx[(k + 1) % n]);
      const std::uint64_t lo = std::min(a, b), hi = std::max(a, b);
      edges.push_back(lo << 33 | hi << 1 | (a > b ? 1u : 0u));
    }
    t.degenerate_faces += degenerate;
  }
  std::sort(edges.begin(), edges.end());
  std::vector<std::int32_t> hole_parent(static_cast<std::size_t>(nv));
  std::iota(hole_parent.begin(), hole_parent.end(), 0);
  std::vector<char> on_boundary(static_cast<std::size_t>(nv), 0);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    int forward = 0, backward = 0;
    while (j < edges.size() && (edges[j] >> 1) == (edges[i] >> 1)) {
      ((edges[j] & 1) ? backward : forward)++;
      ++j;
    }
    ++t.edges;
    const int uses = forward + backward;
    if (uses == 1) {
      ++t.boundary_edges;
      const auto a = static_cast<std::int32_t>(edges[i] >> 33);
      const auto b = static_cast<std::int32_t>((edges[i] >> 1) & 0xFFFFFFFFu);
      on_boundary[a] = on_boundary[b] = 1;
      hole_parent[Find(hole_parent, a)] = Find(hole_parent, b);
    }
    if (uses > 2) ++t.non_manifold_edges;
    if (uses > 2 && forward != backward) ++t.unbalanced_edges;
    if (uses == 2 && forward != 1) ++t.inconsistent_edges;
    i = j;
  }
  for (std::int32_t v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    ++t.vertices;
    if (Find(parent, v) == v) ++t.components;
  }
  t.unreferenced_vertices = nv - t.vertices;
  for (std::int32_t v = 0; v < nv; ++v) {
    if (on_boundary[v] && Find(hole_parent, v) == v) ++t.holes;
  }
  return t;
}

}  // namespace massprops

namespace massprops {
namespace {

// Signed solid angle of triangle (a, b, c) seen from the origin (Van Oosterom & Strackee 1983).
double SolidAngle(const Vector3& a, const Vector3& b, const Vector3& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double num = a.dot(b.cross(c));
  const double den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
  return 2.0 * std::atan2(num, den);
}

}  // namespace

ShellReport AnalyzeShells(const PolygonMesh& mesh) {
  ShellReport report;
  const std::int64_t nf = mesh.num_faces();
  const auto nv = static_cast<std::int32_t>(mesh.V.rows());
  std::vector<std::int32_t> parent(static_cast<std::size_t>(nv));
  std::iota(parent.begin(), parent.end(), 0);
  for (std::int64_t f = 0; f < nf; ++f) {
    const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
    for (int k = 1; k < mesh.face_size(f); ++k) parent[Find(parent, idx[k])] = Find(parent, idx[0]);
  }
  // Shells in order of their first face.
  std::vector<int> shell_of_root(static_cast<std::size_t>(nv), -1);
  const Vector3 ref = nv > 0 ? Vector3(0.5 * (mesh.V.colwise().minCoeff() + mesh.V.colwise().maxCoeff()).transpose())
                             : Vector3::Zero();
  for (std::int64_t f = 0; f < nf; ++f) {
    const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
    const std::int32_t root = Find(parent, idx[0]);
    int& s = shell_of_root[static_cast<std::size_t>(root)];
    if (s < 0) {
      s = static_cast<int>(report.shells.size());
      report.shells.emplace_back();
    }
    Shell& shell = report.shells[static_cast<std::size_t>(s)];
    shell.faces.push_back(f);
    const Vector3 a = mesh.V.row(idx[0]).transpose() - ref;
    for (int k = 1; k + 1 < mesh.face_size(f); ++k) {
      const Vector3 b = mesh.V.row(idx[k]).transpose() - ref;
      const Vector3 c = mesh.V.row(idx[k + 1]).transpose() - ref;
      shell.signed_volume += a.dot(b.cross(c)) / 6.0;
    }
  }
  // Closedness per shell, and a probe point per shell (centroid of its first face's first
  // triangle: inside the shell's surface, off any other shell unless they touch).
  const std::size_t ns = report.shells.size();
  std::vector<Vector3> probe(ns);
  for (std::size_t s = 0; s < ns; ++s) {
    PolygonMesh sub;
    sub.V = mesh.V;
    for (std::int64_t f : report.shells[s].faces) {
      const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
      sub.AddFace(std::vector<std::int32_t>(idx, idx + mesh.face_size(f)));
    }
    report.shells[s].closed = AnalyzeTopology(sub).BoundsVolume();
    const std::int32_t* idx = mesh.indices.data() + mesh.offsets[report.shells[s].faces[0]];
    probe[s] = (mesh.V.row(idx[0]) + mesh.V.row(idx[1]) + mesh.V.row(idx[2])).transpose() / 3.0;
  }
  // Nesting: winding number of shell t at the probe of shell s; the innermost container wins
  // (the one with the smallest |volume|).
  if (ns > 1) {
    for (std::size_t s = 0; s < ns; ++s) {
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t t = 0; t < ns; ++t) {
        if (t == s || !report.shells[t].closed) continue;
        double omega = 0;
        for (std::int64_t f : report.shells[t].faces) {
          const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
          const Vector3 a = mesh.V.row(idx[0]).transpose() - probe[s];
          for (int k = 1; k + 1 < mesh.face_size(f); ++k) {
            omega += SolidAngle(a, mesh.V.row(idx[k]).transpose() - probe[s],
                                mesh.V.row(idx[k + 1]).transpose() - probe[s]);
          }
        }
        const double winding = omega / (4.0 * M_PI);
        const double size = std::fabs(report.shells[t].signed_volume);
        if (std::fabs(winding) > 0.5 && size < best) {
          best = size;
          report.shells[s].inside_of = static_cast<int>(t);
        }
      }
    }
  }
  // Valid: each shell's orientation alternates with depth (outward at even depth, inward at odd).
  std::ostringstream problem;
  for (std::size_t s = 0; s < ns && problem.tellp() == 0; ++s) {
    int depth = 0;
    for (int t = report.shells[s].inside_of; t >= 0 && depth <= static_cast<int>(ns);
         t = report.shells[static_cast<std::size_t>(t)].inside_of) {
      ++depth;
    }
    const bool outward = report.shells[s].signed_volume > 0;
    if (depth % 2 == 0 && !outward) {
      problem << "shell " << s + 1 << " of " << ns << " faces inward but is not inside another shell";
    } else if (depth % 2 == 1 && outward) {
      problem << "shell " << s + 1 << " of " << ns << " lies inside shell "
              << report.shells[s].inside_of + 1
              << " and both face outward: their volumes overlap (if it is meant as a cavity, its "
                 "faces must point into the cavity; {repair} orients it so)";
    }
  }
  report.problem = problem.str();
  return report;
}

}  // namespace massprops
