#include <algorithm>
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
    msg << sep << "open mesh: " << boundary_edges << " boundary edges";
    sep = "; ";
  }
  if (non_manifold_edges > 0) {
    msg << sep << non_manifold_edges << " non-manifold edges (shared by more than two faces)";
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
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    int forward = 0, backward = 0;
    while (j < edges.size() && (edges[j] >> 1) == (edges[i] >> 1)) {
      ((edges[j] & 1) ? backward : forward)++;
      ++j;
    }
    ++t.edges;
    const int uses = forward + backward;
    if (uses == 1) ++t.boundary_edges;
    if (uses > 2) ++t.non_manifold_edges;
    if (uses == 2 && forward != 1) ++t.inconsistent_edges;
    i = j;
  }
  for (std::int32_t v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    ++t.vertices;
    if (Find(parent, v) == v) ++t.components;
  }
  t.unreferenced_vertices = nv - t.vertices;
  return t;
}

}  // namespace massprops
