// The definitions of mesh_field.h: the signed distance field of a closed triangle mesh, for contact
// (internal).

#include "mesh_field.h"

#include "massprops/box_tree.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>

#include "massprops/implicit.h"
#include "massprops/mesh.h"
#include "massprops/mesh_topology.h"
#include "massprops/parallel.h"

namespace dynamics::contact {
namespace {

constexpr int kLeaf = 4;
constexpr int kMinCells = 64;      // along the longest side, at least
constexpr double kMaxNodes = 8e6;  // 64 MB of values at most: the cell grows beyond
constexpr int kPad = 3;            // cells of grid beyond the mesh's box

// The point of triangle abc closest to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vector3 ClosestOnTriangle(const Vector3& p, const Vector3& a, const Vector3& b, const Vector3& c) {
  const Vector3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vector3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vector3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// A bounding-box hierarchy of triangles: closest distances and ray hits.
class TriangleTree {
 public:
  TriangleTree(const std::vector<Vector3>& v, const std::vector<std::array<int, 3>>& t) : v_(v), t_(t) {
    std::vector<Vector3> centroid(t.size());
    for (std::size_t i = 0; i < t.size(); ++i) centroid[i] = (v[t[i][0]] + v[t[i][1]] + v[t[i][2]]) / 3.0;
    tree_ = massprops::BuildBoxTree<3>(
        static_cast<int>(t.size()), kLeaf,
        [&](int f) {
          Eigen::AlignedBox<double, 3> b;
          for (int k = 0; k < 3; ++k) b.extend(v[t[static_cast<std::size_t>(f)][k]]);
          return b;
        },
        [&](int f) -> const Vector3& { return centroid[static_cast<std::size_t>(f)]; });
  }

  double Distance(const Vector3& p) const {
    double best2 = std::numeric_limits<double>::infinity();
    int stack[96];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = tree_.nodes[static_cast<std::size_t>(stack[--top])];
      if (n.box.squaredExteriorDistance(p) >= best2) continue;
      if (n.leaf()) {
        for (int i = n.first; i < n.first + n.count; ++i) {
          const auto& tri = t_[static_cast<std::size_t>(tree_.order[static_cast<std::size_t>(i)])];
          best2 = std::min(best2, (ClosestOnTriangle(p, v_[tri[0]], v_[tri[1]], v_[tri[2]]) - p).squaredNorm());
        }
        continue;
      }
      const Node& l = tree_.nodes[static_cast<std::size_t>(n.left)];
      const Node& r = tree_.nodes[static_cast<std::size_t>(n.right)];
      const bool left_first = l.box.squaredExteriorDistance(p) < r.box.squaredExteriorDistance(p);
      if (top + 2 > 96) throw std::logic_error("mesh field: hierarchy too deep");
      stack[top++] = left_first ? n.right : n.left;  // the nearer child is visited first
      stack[top++] = left_first ? n.left : n.right;
    }
    return std::sqrt(best2);
  }

  // The nearest hit along p + s d, s > skip (Möller–Trumbore), ignoring triangle `self`.
  double Ray(const Vector3& p, const Vector3& d, int self) const {
    double best = std::numeric_limits<double>::infinity();
    int stack[96];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = tree_.nodes[static_cast<std::size_t>(stack[--top])];
      if (!HitsBox(n.box, p, d, best)) continue;
      if (n.leaf()) {
        for (int i = n.first; i < n.first + n.count; ++i) {
          const int f = tree_.order[static_cast<std::size_t>(i)];
          if (f == self) continue;
          const auto& tri = t_[static_cast<std::size_t>(f)];
          const Vector3 e1 = v_[tri[1]] - v_[tri[0]], e2 = v_[tri[2]] - v_[tri[0]];
          const Vector3 q = d.cross(e2);
          const double det = e1.dot(q);
          if (std::abs(det) < 1e-300) continue;
          const Vector3 s = p - v_[tri[0]];
          const double u = s.dot(q) / det;
          if (u < 0 || u > 1) continue;
          const Vector3 r = s.cross(e1);
          const double w = d.dot(r) / det;
          if (w < 0 || u + w > 1) continue;
          const double dist = e2.dot(r) / det;
          if (dist > 0 && dist < best) best = dist;
        }
        continue;
      }
      if (top + 2 > 96) throw std::logic_error("mesh field: hierarchy too deep");
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
    return best;
  }

 private:
  using Node = massprops::BoxTree<3>::Node;

  static bool HitsBox(const Eigen::AlignedBox<double, 3>& box, const Vector3& p, const Vector3& d, double limit) {
    double lo = 0, hi = limit;
    for (int k = 0; k < 3; ++k) {
      if (std::abs(d[k]) < 1e-300) {
        if (p[k] < box.min()[k] || p[k] > box.max()[k]) return false;
        continue;
      }
      double a = (box.min()[k] - p[k]) / d[k], b = (box.max()[k] - p[k]) / d[k];
      if (a > b) std::swap(a, b);
      lo = std::max(lo, a);
      hi = std::min(hi, b);
      if (lo > hi) return false;
    }
    return true;
  }

  const std::vector<Vector3>& v_;
  const std::vector<std::array<int, 3>>& t_;
  massprops::BoxTree<3> tree_;
};

// The mesh as massprops' triangle mesh, checked: enough triangles, a valid cell, finite vertices,
// indices in range, closed and consistently oriented.
massprops::TriangleMesh Validated(const shape::Mesh& mesh) {
  if (mesh.triangles.size() < 4)
    throw std::invalid_argument("a mesh collider needs a closed mesh (4 triangles at least)");
  if (!(mesh.cell >= 0) || !std::isfinite(mesh.cell)) {
    throw std::invalid_argument("a mesh collider's cell must be finite and >= 0 (0: automatic)");
  }
  massprops::TriangleMesh tm;
  tm.V.resize(static_cast<Eigen::Index>(mesh.vertices.size()), 3);
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (!mesh.vertices[i].allFinite()) throw std::invalid_argument("a mesh collider has a non-finite vertex");
    tm.V.row(static_cast<Eigen::Index>(i)) = mesh.vertices[i].transpose();
  }
  const auto nv = static_cast<int>(mesh.vertices.size());
  tm.F.resize(static_cast<Eigen::Index>(mesh.triangles.size()), 3);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.triangles[f][static_cast<std::size_t>(k)];
      if (v < 0 || v >= nv) {
        throw std::invalid_argument("a mesh collider's triangle refers to vertex " + std::to_string(v) + " of " +
                                    std::to_string(nv));
      }
      tm.F(static_cast<Eigen::Index>(f), k) = v;
    }
  }
  const massprops::MeshTopology topology = massprops::AnalyzeTopology(massprops::ToPolygonMesh(tm));
  if (!topology.BoundsVolume()) {
    throw std::invalid_argument("a mesh collider must be closed and consistently oriented (" + topology.Problems() +
                                "); repair the mesh (massprops --repair) or collide its hull");
  }
  return tm;
}

// The thinnest wall: from each triangle's centroid, the distance inward (against its normal) to
// the next surface, area-weighted; the 2nd percentile (single slivers at concave edges give
// spuriously small values).
double ThinnestWall(const TriangleTree& tree, const shape::Mesh& mesh) {
  std::vector<std::pair<double, double>> walls;  // (thickness, area)
  double total = 0;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    const Vector3 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    const Vector3 n = (b - a).cross(c - a);
    const double area = 0.5 * n.norm();
    if (!(area > 0)) continue;
    const double d = tree.Ray((a + b + c) / 3.0, -n.normalized(), static_cast<int>(f));
    if (!std::isfinite(d)) continue;
    walls.emplace_back(d, area);
    total += area;
  }
  if (walls.empty()) return std::numeric_limits<double>::infinity();
  std::sort(walls.begin(), walls.end());
  double acc = 0;
  for (const auto& [d, area] : walls) {
    acc += area;
    if (acc >= 0.02 * total) return d;
  }
  return walls.back().first;
}

// Orders `order` (indices of samples) into clusters of at most 32 by recursive median splits
// along the longest side of their box.
void Cluster(const std::vector<Vector3>& samples, std::vector<int>& order, int first, int count,
             std::vector<MeshField::Cluster>& out) {
  auto at = [&](int i) -> const Vector3& {
    return samples[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])];
  };
  Eigen::AlignedBox<double, 3> box;
  for (int i = first; i < first + count; ++i) box.extend(at(i));
  if (count > 32) {
    int axis;
    box.sizes().maxCoeff(&axis);
    const int mid = first + count / 2;
    std::nth_element(order.begin() + first, order.begin() + mid, order.begin() + first + count, [&](int x, int y) {
      return samples[static_cast<std::size_t>(x)][axis] < samples[static_cast<std::size_t>(y)][axis];
    });
    Cluster(samples, order, first, mid - first, out);
    Cluster(samples, order, mid, first + count - mid, out);
    return;
  }
  MeshField::Cluster c;
  c.centre = box.center();
  for (int i = first; i < first + count; ++i) c.radius = std::max(c.radius, (at(i) - c.centre).norm());
  c.first = first;
  c.count = count;
  out.push_back(c);
}

// The samples (every vertex, and points about a cell apart along longer edges) with their faces
// (mesh_field.h: inactive features), clustered.
void AddSamples(const shape::Mesh& mesh, double cell, MeshField& field) {
  const std::size_t nv = mesh.vertices.size();
  std::vector<Vector3> face_normal;
  for (const auto& t : mesh.triangles) {
    const Vector3 a = mesh.vertices[static_cast<std::size_t>(t[0])], b = mesh.vertices[static_cast<std::size_t>(t[1])],
                  c = mesh.vertices[static_cast<std::size_t>(t[2])];
    const Vector3 n = (b - a).cross(c - a);
    face_normal.push_back(n.norm() > 0 ? Vector3(n.normalized()) : Vector3::Zero());
  }
  // Each edge's faces (a closed mesh: two).
  std::map<std::pair<int, int>, std::vector<int>> edges;
  std::vector<std::vector<int>> vertex_faces(nv);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      edges[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}].push_back(static_cast<int>(f));
      vertex_faces[static_cast<std::size_t>(t[k])].push_back(static_cast<int>(f));
    }
  }
  const double flat = std::cos(kFlatEdge);
  // Whether an edge is active: convex, with a real angle.
  auto active = [&](const std::pair<int, int>& e, const std::vector<int>& faces) {
    if (faces.size() != 2) return true;
    const Vector3& n1 = face_normal[static_cast<std::size_t>(faces[0])];
    const Vector3& n2 = face_normal[static_cast<std::size_t>(faces[1])];
    if (n1.dot(n2) >= flat) return false;
    // Convex when the second face's far corner lies below the first face's plane.
    int far = e.first;
    for (const int v : mesh.triangles[static_cast<std::size_t>(faces[1])]) {
      if (v != e.first && v != e.second) far = v;
    }
    return n1.dot(mesh.vertices[static_cast<std::size_t>(far)] - mesh.vertices[static_cast<std::size_t>(e.first)]) < 0;
  };
  // The distinct normals of a set of faces.
  auto add_normals = [&](const std::vector<int>& faces) {
    MeshField::SampleFaces out{static_cast<std::uint32_t>(field.normals.size()), 0};
    for (const int f : faces) {
      const Vector3& n = face_normal[static_cast<std::size_t>(f)];
      bool seen = n.squaredNorm() == 0;
      for (std::uint32_t k = out.first; k < out.first + out.count && !seen; ++k) seen = field.normals[k].dot(n) >= flat;
      if (!seen) {
        field.normals.push_back(n);
        ++out.count;
      }
    }
    return out;
  };
  std::vector<Vector3> samples = mesh.vertices;
  std::vector<MeshField::SampleFaces> faces_of(nv);
  std::vector<char> vertex_active(nv, 0);
  for (const auto& [e, faces] : edges) {
    const bool is_active = active(e, faces);
    if (is_active)
      vertex_active[static_cast<std::size_t>(e.first)] = vertex_active[static_cast<std::size_t>(e.second)] = 1;
    const MeshField::SampleFaces edge_faces = is_active ? MeshField::SampleFaces{} : add_normals(faces);
    const Vector3 a = mesh.vertices[static_cast<std::size_t>(e.first)],
                  b = mesh.vertices[static_cast<std::size_t>(e.second)];
    const int k = static_cast<int>(std::ceil((b - a).norm() / cell));
    for (int i = 1; i < k; ++i) {
      samples.push_back(a + (b - a) * (static_cast<double>(i) / k));
      faces_of.push_back(edge_faces);
    }
  }
  for (std::size_t v = 0; v < nv; ++v) {
    if (!vertex_active[v] && !vertex_faces[v].empty()) faces_of[v] = add_normals(vertex_faces[v]);
  }
  std::vector<int> order(samples.size());
  std::iota(order.begin(), order.end(), 0);
  Cluster(samples, order, 0, static_cast<int>(order.size()), field.clusters);
  for (const int i : order) {
    field.samples.push_back(samples[static_cast<std::size_t>(i)]);
    field.sample_faces.push_back(faces_of[static_cast<std::size_t>(i)]);
  }
}

}  // namespace

double MeshField::Distance(const Vector3& x, Vector3* gradient) const {
  // Clamp into the grid (beyond it, see the end).
  const Vector3 top = origin + cell * Vector3(nodes[0] - 1, nodes[1] - 1, nodes[2] - 1);
  const Vector3 inside = x.cwiseMax(origin).cwiseMin(top);
  const double outside2 = (x - inside).squaredNorm();  // (no square root for the usual point inside)
  const double outside = outside2 > 0 ? std::sqrt(outside2) : 0.0;
  const Vector3 g = (inside - origin) / cell;
  int i[3];
  double f[3];
  for (int k = 0; k < 3; ++k) {
    // g ≥ 0 (inside is clamped to the grid): truncation is the floor, without a call into libm.
    i[k] = std::clamp(static_cast<int>(g[k]), 0, nodes[static_cast<std::size_t>(k)] - 2);
    f[k] = g[k] - i[k];
  }
  auto at = [&](int a, int b, int c) {
    return values[(static_cast<std::size_t>(i[2] + c) * static_cast<std::size_t>(nodes[1]) +
                   static_cast<std::size_t>(i[1] + b)) *
                      static_cast<std::size_t>(nodes[0]) +
                  static_cast<std::size_t>(i[0] + a)];
  };
  const double c000 = at(0, 0, 0), c100 = at(1, 0, 0), c010 = at(0, 1, 0), c110 = at(1, 1, 0), c001 = at(0, 0, 1),
               c101 = at(1, 0, 1), c011 = at(0, 1, 1), c111 = at(1, 1, 1);
  const double c00 = c000 + (c100 - c000) * f[0], c10 = c010 + (c110 - c010) * f[0], c01 = c001 + (c101 - c001) * f[0],
               c11 = c011 + (c111 - c011) * f[0];
  const double c0 = c00 + (c10 - c00) * f[1], c1 = c01 + (c11 - c01) * f[1];
  const double value = c0 + (c1 - c0) * f[2];
  if (gradient != nullptr) {
    if (outside > 0) {
      *gradient = (x - inside) / outside;
    } else {
      const double dx = ((c100 - c000) * (1 - f[1]) + (c110 - c010) * f[1]) * (1 - f[2]) +
                        ((c101 - c001) * (1 - f[1]) + (c111 - c011) * f[1]) * f[2];
      const double dy = ((c010 - c000) * (1 - f[0]) + (c110 - c100) * f[0]) * (1 - f[2]) +
                        ((c011 - c001) * (1 - f[0]) + (c111 - c101) * f[0]) * f[2];
      *gradient = Vector3(dx, dy, c1 - c0) / cell;
    }
  }
  if (outside == 0) return value;
  // Beyond the grid, a bound from below: the distance to the mesh's box (which holds the mesh),
  // or the value at the nearest grid point less the way there, whichever is larger.
  return std::max(mesh_box.exteriorDistance(x), value - outside);
}

bool MeshField::SurelyAbove(const Vector3& x, double threshold, double* bound) const {
  if (block_min.empty()) return false;
  // The cell Distance uses for a point inside the grid, or (rounding at a cell's face) its
  // neighbour across that face, whose block holds the face's nodes, which then carry all but ~10⁻¹⁶
  // of the value; beyond the grid φ is not bounded by the nodes.
  const Vector3 g = (x - origin) * inverse_cell;
  std::size_t b[3];
  for (int k = 0; k < 3; ++k) {
    const int n = nodes[static_cast<std::size_t>(k)];
    if (!(g[k] >= 0 && g[k] <= n - 1)) return false;
    const int i = std::min(static_cast<int>(g[k]), n - 2);
    b[k] = static_cast<std::size_t>(i / kBlock);
  }
  const double least =
      block_min[(b[2] * static_cast<std::size_t>(blocks[1]) + b[1]) * static_cast<std::size_t>(blocks[0]) + b[0]];
  // The interpolation's rounding may leave it a few ulps under its corners: a margin far above that.
  if (!(least - 1e-12 * (1 + std::abs(least) + std::abs(threshold)) > threshold)) return false;
  if (bound != nullptr) *bound = least - 1e-12 * (1 + std::abs(least));
  return true;
}

std::size_t MeshField::MemoryBytes() const {
  return (values.size() + block_min.size()) * sizeof(double) +
         samples.size() * (sizeof(Vector3) + sizeof(SampleFaces)) + normals.size() * sizeof(Vector3);
}

std::shared_ptr<const MeshField> BuildMeshField(const shape::Mesh& mesh, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  const massprops::TriangleMesh tm = Validated(mesh);
  auto field = std::make_shared<MeshField>();
  Eigen::AlignedBox<double, 3> box;
  for (const Vector3& v : mesh.vertices) {
    box.extend(v);
    field->radius = std::max(field->radius, v.norm());
  }
  const double longest = box.sizes().maxCoeff();
  if (!(longest > 0)) throw std::invalid_argument("a mesh collider has no extent");
  field->vertex_order.resize(mesh.vertices.size());
  std::iota(field->vertex_order.begin(), field->vertex_order.end(), 0);
  Cluster(mesh.vertices, field->vertex_order, 0, static_cast<int>(mesh.vertices.size()), field->vertex_runs);
  const TriangleTree tree(mesh.vertices, mesh.triangles);
  field->thinnest = ThinnestWall(tree, mesh);
  double cell = mesh.cell > 0 ? mesh.cell : std::min(longest / kMinCells, field->thinnest / 3);
  cell = std::max(cell, longest / 1024);
  auto count_nodes = [&](double h) { return ((box.sizes() / h).array().ceil() + 1 + 2 * kPad).prod(); };
  while (count_nodes(cell) > kMaxNodes) cell *= 1.1;
  field->cell = cell;
  field->inverse_cell = 1 / cell;
  for (int k = 0; k < 3; ++k)
    field->nodes[static_cast<std::size_t>(k)] = static_cast<int>(std::ceil(box.sizes()[k] / cell)) + 1 + 2 * kPad;
  field->origin = box.min() - Vector3::Constant(kPad * cell);
  field->mesh_box = box;
  // The sign: the winding number of the closed mesh (exact: it counts ray crossings).
  const massprops::ImplicitPtr winding = massprops::implicit::WindingNumberSolid(tm);
  const int nx = field->nodes[0], ny = field->nodes[1],
            nz = field->nodes[2];  // (not a structured binding: lambdas below use them)
  field->values.resize(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz));
  // Slices of constant z side by side: each node is computed on its own, so the values are the
  // same whatever the thread count.
  massprops::ParallelForBlocks(nz, threads, [&](std::int64_t slice) {
    const auto z = static_cast<int>(slice);
    for (int y = 0; y < ny; ++y) {
      for (int x = 0; x < nx; ++x) {
        const Vector3 p = field->origin + cell * Vector3(x, y, z);
        const double d = tree.Distance(p);
        const bool in = winding->Value(p) < 0;
        field->values[(static_cast<std::size_t>(z) * static_cast<std::size_t>(ny) + static_cast<std::size_t>(y)) *
                          static_cast<std::size_t>(nx) +
                      static_cast<std::size_t>(x)] = in ? -d : d;
      }
    }
  });
  // Each block's least node: block b holds cells [b K, b K + K) and so nodes [b K, b K + K] (K =
  // kBlock; the last block's stop at the grid's last node).
  constexpr int K = MeshField::kBlock;
  for (int k = 0; k < 3; ++k)
    field->blocks[static_cast<std::size_t>(k)] = (field->nodes[static_cast<std::size_t>(k)] - 1 + K - 1) / K;
  const int bx = field->blocks[0], by = field->blocks[1], bz = field->blocks[2];
  auto node = [&](int x, int y, int z) {
    return field->values[(static_cast<std::size_t>(z) * static_cast<std::size_t>(ny) + static_cast<std::size_t>(y)) *
                             static_cast<std::size_t>(nx) +
                         static_cast<std::size_t>(x)];
  };
  field->block_min.reserve(static_cast<std::size_t>(bx) * static_cast<std::size_t>(by) * static_cast<std::size_t>(bz));
  for (int z0 = 0; z0 < bz * K; z0 += K) {
    for (int y0 = 0; y0 < by * K; y0 += K) {
      for (int x0 = 0; x0 < bx * K; x0 += K) {
        double least = std::numeric_limits<double>::infinity();
        for (int z = z0; z <= std::min(z0 + K, nz - 1); ++z) {
          for (int y = y0; y <= std::min(y0 + K, ny - 1); ++y) {
            for (int x = x0; x <= std::min(x0 + K, nx - 1); ++x) least = std::min(least, node(x, y, z));
          }
        }
        field->block_min.push_back(least);
      }
    }
  }
  AddSamples(mesh, cell, *field);
  field->build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return field;
}

}  // namespace dynamics::contact

namespace dynamics {

shape::Mesh MakeMesh(std::vector<Vector3> vertices, std::vector<std::array<int, 3>> triangles, double cell,
                     int threads) {
  shape::Mesh mesh{std::move(vertices), std::move(triangles), cell, nullptr};
  mesh.field = contact::BuildMeshField(mesh, threads);
  return mesh;
}

MeshFieldInfo DescribeMeshField(const shape::Mesh& mesh) {
  if (mesh.field == nullptr) throw std::invalid_argument("the mesh collider's field is not built (MakeMesh)");
  const contact::MeshField& f = *mesh.field;
  return {f.nodes, f.cell, f.thinnest, f.samples.size(), f.MemoryBytes(), f.build_seconds};
}

}  // namespace dynamics
