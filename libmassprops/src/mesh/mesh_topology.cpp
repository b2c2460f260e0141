// Mesh topology (massprops/mesh_topology.h): boundary, non-manifold and inconsistently oriented
// edges, holes, components, shells and their nesting.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <sstream>
#include <utility>
#include <vector>

#include "massprops/mesh_topology.h"
#include "massprops/parallel.h"

#include <Eigen/Geometry>

namespace massprops {
namespace {

// The union–find's links, read and written as relaxed atomics (plain moves on x86): with vertex
// ranges on several threads, two of them may link or shorten the same trees at once.
std::int32_t Load(const std::int32_t* p) { return __atomic_load_n(p, __ATOMIC_RELAXED); }

// Path halving. A link only ever points to a smaller vertex of the same set, so a halving step
// that races another thread's (or a link) still leaves every vertex in its set.
std::int32_t Find(std::int32_t* parent, std::int32_t i) {
  for (std::int32_t up = Load(parent + i); up != i; up = Load(parent + i)) {
    const std::int32_t grand = Load(parent + up);
    __atomic_store_n(parent + i, grand, __ATOMIC_RELAXED);
    i = grand;
  }
  return i;
}

// Joins the sets of a and b, the larger root under the smaller: the edges come by their smaller
// vertex in increasing order, so a vertex seen first as the larger end hangs straight off a root
// and the trees stay shallow (linking the other way grew chains through the mesh's numbering).
// kShared: other threads join too, so the link is made only if the root is still a root.
template <bool kShared>
void Join(std::int32_t* parent, std::int32_t a, std::int32_t b) {
  for (;;) {
    const std::int32_t ra = Find(parent, a), rb = Find(parent, b);
    if (ra == rb) return;
    std::int32_t child = std::max(ra, rb);
    const std::int32_t root = std::min(ra, rb);
    if (!kShared) {
      parent[child] = root;
      return;
    }
    if (__atomic_compare_exchange_n(parent + child, &child, root, false, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) return;
    a = ra;  // another thread linked one of the roots first: again from the roots
    b = rb;
  }
}

// An array not cleared between calls: its entries are written before they are read. kZeroed:
// zeroed once when it grows, for slot_of, whose entries are read (only compared: any earlier value
// is fine) but must never be indeterminate; the others are not (a 10^6-vertex mesh's edge array
// is 24 MB the kernel zeroes already).
template <typename T, bool kZeroed = false>
class Uninitialized {
 public:
  T* Get(std::size_t n) {
    if (n > capacity_) {
      data_.reset(kZeroed ? new T[n]() : new T[n]);
      capacity_ = n;
    }
    return data_.get();
  }
  std::size_t capacity() const { return capacity_; }

 private:
  std::unique_ptr<T[]> data_;
  std::size_t capacity_ = 0;
};

// AnalyzeTopology's working arrays, kept by each thread from one call to the next: a fresh
// allocation of a few hundred kB per call came back from the kernel as zeroed pages (glibc gives
// the top of the heap back), and those page faults were half of a 10^4-triangle analysis. Arrays
// of a large mesh are let go after the call.
struct TopologyScratch {
  struct Edge {
    std::uint32_t b;
    int forward, backward;
  };
  std::vector<char> used, on_boundary;  // zeroed each call
  std::vector<std::uint32_t> start;     // zeroed each call
  Uninitialized<std::uint32_t> other, cursor;
  Uninitialized<std::uint32_t, true> slot_of;
  Uninitialized<std::int32_t> parent, hole_parent;
  std::vector<Edge> group;

  void Trim() {  // kept for meshes of up to 2^19 vertices (~27 MB a thread at most)
    constexpr std::size_t kKeep = std::size_t{1} << 19;
    if (other.capacity() > 8 * kKeep || start.capacity() > kKeep + 1) *this = TopologyScratch{};
  }
};

// Not inlined: the caller then holds a plain reference, where an inlined thread_local in a shared
// library is looked up again (__tls_get_addr) at every use inside the loops.
[[gnu::noinline]] TopologyScratch& ThreadScratch() {
  static thread_local TopologyScratch scratch;
  return scratch;
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
    msg << sep << unbalanced_edges << " non-manifold edges (shared by more than two faces) with unmatched orientations";
    sep = "; ";
  }
  if (inconsistent_edges > 0) {
    msg << sep << "inconsistent orientation: " << inconsistent_edges << " edges where neighbouring faces disagree";
  }
  return msg.str();
}

namespace {

// The corners of face f as a cyclic sequence starting at its smallest index.
std::vector<std::int32_t> FromSmallest(const PolygonMesh& mesh, std::int64_t f) {
  const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
  const int n = mesh.face_size(f);
  const int start = static_cast<int>(std::min_element(idx, idx + n) - idx);
  std::vector<std::int32_t> out(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) out[static_cast<std::size_t>(k)] = idx[(start + k) % n];
  return out;
}

// Faces with the same corner set as an earlier one: sorted by a hash of the sorted corners, then
// compared exactly; the same cyclic order is a duplicate, the reverse order a reversed duplicate.
void CountDuplicateFaces(const PolygonMesh& mesh, MeshTopology& t) {
  std::vector<std::pair<std::uint64_t, std::int64_t>> keys;
  keys.reserve(static_cast<std::size_t>(t.faces));
  std::vector<std::int32_t> sorted;
  auto sorted_corners = [&](std::int64_t f) {
    const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
    sorted.assign(idx, idx + mesh.face_size(f));
    std::sort(sorted.begin(), sorted.end());
    return sorted;
  };
  for (std::int64_t f = 0; f < t.faces; ++f) {
    std::uint64_t h = 0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(mesh.face_size(f));
    for (std::int32_t c : sorted_corners(f)) {
      h ^= static_cast<std::uint64_t>(c) + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
      h *= 0xBF58476D1CE4E5B9ull;
    }
    keys.emplace_back(h, f);
  }
  std::sort(keys.begin(), keys.end());
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i + 1;
    while (j < keys.size() && keys[j].first == keys[i].first) ++j;
    // A run of equal hashes: faces with the corners of its first face are its copies (a 64-bit
    // hash collision between different corner sets is ignored). Linear in the run's length.
    const std::vector<std::int32_t> first_sorted = sorted_corners(keys[i].second);
    const std::vector<std::int32_t> first = FromSmallest(mesh, keys[i].second);
    std::vector<std::int32_t> first_reversed = first;
    std::reverse(first_reversed.begin() + 1, first_reversed.end());
    for (std::size_t a = i + 1; a < j; ++a) {
      if (sorted_corners(keys[a].second) != first_sorted) continue;
      const std::vector<std::int32_t> fa = FromSmallest(mesh, keys[a].second);
      if (fa == first)
        ++t.duplicate_faces;
      else if (fa == first_reversed)
        ++t.reversed_duplicate_faces;
    }
    i = j;
  }
}

}  // namespace

namespace {

// What one range of vertices finds in the edges whose smaller end it holds.
struct EdgeCounts {
  std::int64_t edges = 0, boundary = 0, non_manifold = 0, unbalanced = 0, inconsistent = 0, degenerate_faces = 0;
  void Add(const EdgeCounts& o) {
    edges += o.edges, boundary += o.boundary, non_manifold += o.non_manifold, unbalanced += o.unbalanced;
    inconsistent += o.inconsistent, degenerate_faces += o.degenerate_faces;
  }
};

// Calls fn(a, b) for each directed edge of face f, in order; kTriangles: every face is a triangle
// (its corners at 3 f, the loop unrolled).
template <bool kTriangles, typename Fn>
void ForEachEdge(const PolygonMesh& mesh, std::int64_t f, Fn&& fn) {
  if constexpr (kTriangles) {
    const std::int32_t* idx = mesh.indices.data() + 3 * f;
    const auto a = static_cast<std::uint32_t>(idx[0]), b = static_cast<std::uint32_t>(idx[1]),
               c = static_cast<std::uint32_t>(idx[2]);
    fn(a, b);
    fn(b, c);
    fn(c, a);
  } else {
    const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
    const int n = mesh.face_size(f);
    for (int k = 0; k < n; ++k)
      fn(static_cast<std::uint32_t>(idx[k]), static_cast<std::uint32_t>(idx[k + 1 < n ? k + 1 : 0]));
  }
}

// Pass 1 over the faces [lo, hi): marks their corners used, counts the directed edges each vertex
// starts as the smaller end (count[v + 1]) and the faces with a repeated corner.
template <bool kTriangles>
void CountEdges(const PolygonMesh& mesh, std::int64_t lo, std::int64_t hi, char* used, std::uint32_t* count,
                EdgeCounts& out) {
  EdgeCounts c;  // counted here: the threads' results share cache lines
  for (std::int64_t f = lo; f < hi; ++f) {
    bool degenerate = false;
    ForEachEdge<kTriangles>(mesh, f, [&](std::uint32_t a, std::uint32_t b) {
      __atomic_store_n(used + a, char{1}, __ATOMIC_RELAXED);  // another slice may mark it too
      if (a == b) {
        degenerate = true;
      } else {
        ++count[std::min(a, b) + 1];
      }
    });
    c.degenerate_faces += degenerate;
  }
  out.Add(c);
}

// Pass 2 over the faces [lo, hi): each directed edge as (larger vertex << 1 | reversed), in the
// group of its smaller vertex, at its cursor.
template <bool kTriangles>
void PlaceEdges(const PolygonMesh& mesh, std::int64_t lo, std::int64_t hi, std::uint32_t* cursor,
                std::uint32_t* other) {
  for (std::int64_t f = lo; f < hi; ++f) {
    ForEachEdge<kTriangles>(mesh, f, [&](std::uint32_t a, std::uint32_t b) {
      if (a != b) other[cursor[std::min(a, b)]++] = std::max(a, b) << 1 | (a > b ? 1u : 0u);
    });
  }
}

// Pass 3 over the vertices [lo, hi): each group's edges counted by their other end, in order of
// first appearance (no sort: the counts do not depend on the order). b has a slot in a's group
// when slot_of[b] names an entry of the group that holds b (slot_of, the range's own, is never
// cleared: an older value fails that test).
template <bool kShared>
void ClassifyEdges(std::uint32_t lo, std::uint32_t hi, const std::uint32_t* start, const std::uint32_t* other,
                   std::uint32_t* slot_of, std::vector<TopologyScratch::Edge>& group, std::int32_t* parent,
                   std::int32_t* hole_parent, char* on_boundary, EdgeCounts& out) {
  EdgeCounts c;  // counted here: the threads' results share cache lines
  for (std::uint32_t a = lo; a < hi; ++a) {
    // The group's entries written field by field into room made beforehand (a pushed-back
    // aggregate went through the stack, and reading it back missed store forwarding: a quarter of
    // the analysis).
    const std::uint32_t degree = start[a + 1] - start[a];
    if (group.size() < degree) group.resize(degree);
    TopologyScratch::Edge* const g = group.data();
    std::uint32_t size = 0;
    for (std::uint32_t k = start[a]; k < start[a + 1]; ++k) {
      const std::uint32_t b = other[k] >> 1;
      std::uint32_t slot = slot_of[b];
      if (slot >= size || g[slot].b != b) {
        slot = size++;
        slot_of[b] = slot;
        g[slot].b = b;
        g[slot].forward = g[slot].backward = 0;
      }
      ((other[k] & 1) ? g[slot].backward : g[slot].forward)++;
    }
    const auto av = static_cast<std::int32_t>(a);
    // One thread: a's root found once for its group, and followed as b's sets join it.
    std::int32_t root = kShared || size == 0 ? av : Find(parent, av);
    for (std::uint32_t i = 0; i < size; ++i) {
      const TopologyScratch::Edge& e = g[i];
      const auto b = static_cast<std::int32_t>(e.b);
      ++c.edges;
      if constexpr (kShared) {
        Join<true>(parent, av, b);
      } else if (const std::int32_t rb = Find(parent, b); rb < root) {  // the larger root under the smaller
        parent[root] = rb;
        root = rb;
      } else if (rb > root) {
        parent[rb] = root;
      }
      const int uses = e.forward + e.backward;
      if (uses == 1) {
        ++c.boundary;
        __atomic_store_n(on_boundary + a, char{1}, __ATOMIC_RELAXED);  // b may be another range's
        __atomic_store_n(on_boundary + b, char{1}, __ATOMIC_RELAXED);
        Join<kShared>(hole_parent, av, b);
      }
      if (uses > 2) ++c.non_manifold;
      if (uses > 2 && e.forward != e.backward) ++c.unbalanced;
      if (uses == 2 && e.forward != 1) ++c.inconsistent;
    }
  }
  out.Add(c);
}

}  // namespace

// Directed edges are grouped by their smaller vertex (a counting sort: vertices are numbered in
// order of first appearance, so the groups fill in near file order), and each group — a vertex's
// few edges to larger neighbours — is counted by the other end in a slot table. Linear, and a
// quarter of the memory of sorting 64-bit edge keys. Meshes of 2^17 faces and more are analysed
// on several threads — faces counted and placed in slices, groups classified in vertex ranges —
// with the counts of one thread: sums, and the union–find's sets, which do not depend on the
// order of the joins.
MeshTopology AnalyzeTopology(const PolygonMesh& mesh, int num_threads) {
  MeshTopology t;
  t.faces = mesh.num_faces();
  const auto nv = static_cast<std::size_t>(mesh.V.rows());
  // At most four parts: each costs two arrays of the vertices' size (its counts and its slot
  // table), and the passes are bound by memory beyond a few threads.
  const int parts = t.faces >= (std::int64_t{1} << 17) ? ResolveThreadCount(num_threads, 4) : 1;
  const auto part = [&](std::int64_t r, std::int64_t n) { return n * r / parts; };
  auto each_part = [&](auto&& fn) { ParallelForBlocks(parts, parts, fn); };
  // The scratch's arrays sized, then used through plain pointers (a store through char* could
  // alias a vector's own pointers, which the loops would then reload at every step).
  TopologyScratch& scratch = ThreadScratch();
  scratch.used.assign(nv, 0);
  scratch.start.assign(nv + 1, 0);
  char* const used = scratch.used.data();
  std::uint32_t* const start = scratch.start.data();  // directed edges by smaller vertex
  // Each slice of faces counts its edges by smaller vertex, then places them at its cursors: the
  // slices' edges follow each other in every group, so each group lists its edges in face order.
  // One slice counts straight into start.
  const bool triangles = IsAllTriangles(mesh);
  std::vector<std::vector<std::uint32_t>> slice(parts > 1 ? static_cast<std::size_t>(parts) : 0);
  std::vector<EdgeCounts> counts(static_cast<std::size_t>(parts));
  each_part([&](std::int64_t r) {
    const auto i = static_cast<std::size_t>(r);
    if (parts > 1) slice[i].assign(nv + 1, 0);
    std::uint32_t* const count = parts > 1 ? slice[i].data() : start;
    (triangles ? CountEdges<true> : CountEdges<false>)(mesh, part(r, t.faces), part(r + 1, t.faces), used, count,
                                                       counts[i]);
  });
  std::uint32_t* cursor = nullptr;  // of one slice
  if (parts == 1) {
    std::uint32_t sum = 0;  // in a register: the loop through memory waited on each store
    for (std::size_t v = 1; v <= nv; ++v) start[v] = sum += start[v];
    cursor = scratch.cursor.Get(nv);
    std::copy(start, start + nv, cursor);
  } else {
    for (std::size_t v = 0; v < nv; ++v) {  // each slice's count into its first place in the group
      std::uint32_t at = start[v];
      for (std::vector<std::uint32_t>& c : slice) at += std::exchange(c[v + 1], at);
      start[v + 1] = at;
    }
  }
  std::uint32_t* const other = scratch.other.Get(start[nv]);
  each_part([&](std::int64_t r) {
    std::uint32_t* const at = parts > 1 ? slice[static_cast<std::size_t>(r)].data() + 1 : cursor;
    (triangles ? PlaceEdges<true> : PlaceEdges<false>)(mesh, part(r, t.faces), part(r + 1, t.faces), at, other);
  });
  std::int32_t* const parent = scratch.parent.Get(nv);
  std::int32_t* const hole_parent = scratch.hole_parent.Get(nv);
  std::iota(parent, parent + nv, 0);
  std::iota(hole_parent, hole_parent + nv, 0);
  scratch.on_boundary.assign(nv, 0);
  char* const on_boundary = scratch.on_boundary.data();
  std::uint32_t* const slot_of = scratch.slot_of.Get(nv);
  // Then each range of vertices classifies its groups' edges (the union–find shared when there
  // are several).
  if (parts == 1) {
    ClassifyEdges<false>(0, static_cast<std::uint32_t>(nv), start, other, slot_of, scratch.group, parent, hole_parent,
                         on_boundary, counts[0]);
  } else {
    each_part([&](std::int64_t r) {
      std::vector<TopologyScratch::Edge> group;
      std::vector<std::uint32_t> own_slots(r == 0 ? 0 : nv);  // a slot table a range
      ClassifyEdges<true>(static_cast<std::uint32_t>(part(r, static_cast<std::int64_t>(nv))),
                          static_cast<std::uint32_t>(part(r + 1, static_cast<std::int64_t>(nv))), start, other,
                          r == 0 ? slot_of : own_slots.data(), group, parent, hole_parent, on_boundary,
                          counts[static_cast<std::size_t>(r)]);
    });
  }
  EdgeCounts all;
  for (const EdgeCounts& c : counts) all.Add(c);
  t.edges = all.edges;
  t.boundary_edges = all.boundary;
  t.non_manifold_edges = all.non_manifold;
  t.unbalanced_edges = all.unbalanced;
  t.inconsistent_edges = all.inconsistent;
  t.degenerate_faces = all.degenerate_faces;
  // A set's root is its smallest vertex, the one that is its own parent.
  for (std::size_t v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    ++t.vertices;
    t.components += parent[v] == static_cast<std::int32_t>(v);
  }
  t.unreferenced_vertices = static_cast<std::int64_t>(nv) - t.vertices;
  for (std::size_t v = 0; v < nv; ++v) t.holes += on_boundary[v] && hole_parent[v] == static_cast<std::int32_t>(v);
  if (t.non_manifold_edges > 0) CountDuplicateFaces(mesh, t);
  scratch.Trim();
  return t;
}

std::int64_t CountUnweldedBoundaryCorners(const PolygonMesh& mesh, double tolerance) {
  if (!(tolerance > 0)) return 0;
  // Boundary edges: undirected edges used once.
  std::vector<std::uint64_t> edges;
  edges.reserve(mesh.indices.size());
  for (std::int64_t f = 0; f < mesh.num_faces(); ++f) {
    const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
    const int n = mesh.face_size(f);
    for (int k = 0; k < n; ++k) {
      const std::uint64_t a = static_cast<std::uint32_t>(idx[k]), b = static_cast<std::uint32_t>(idx[(k + 1) % n]);
      if (a != b) edges.push_back(std::min(a, b) << 32 | std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<std::int32_t> corners;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) {
      corners.push_back(static_cast<std::int32_t>(edges[i] >> 32));
      corners.push_back(static_cast<std::int32_t>(edges[i] & 0xFFFFFFFFu));
    }
    i = j;
  }
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  // A hash grid of cell `tolerance`: neighbours are in the 27 cells around.
  auto cell_of = [&](std::int32_t v) {
    return std::array<std::int64_t, 3>{static_cast<std::int64_t>(std::floor(mesh.V(v, 0) / tolerance)),
                                       static_cast<std::int64_t>(std::floor(mesh.V(v, 1) / tolerance)),
                                       static_cast<std::int64_t>(std::floor(mesh.V(v, 2) / tolerance))};
  };
  std::vector<std::pair<std::array<std::int64_t, 3>, std::int32_t>> grid;
  grid.reserve(corners.size());
  for (std::int32_t v : corners) grid.emplace_back(cell_of(v), v);
  std::sort(grid.begin(), grid.end());
  std::int64_t unwelded = 0;
  for (std::int32_t v : corners) {
    const auto c = cell_of(v);
    bool near = false;
    for (int dx = -1; dx <= 1 && !near; ++dx) {
      for (int dy = -1; dy <= 1 && !near; ++dy) {
        for (int dz = -1; dz <= 1 && !near; ++dz) {
          const std::array<std::int64_t, 3> key{c[0] + dx, c[1] + dy, c[2] + dz};
          for (auto it = std::lower_bound(grid.begin(), grid.end(), std::make_pair(key, std::int32_t{-1}));
               it != grid.end() && it->first == key && !near; ++it) {
            const std::int32_t w = it->second;
            if (w == v) continue;
            const double d = (mesh.V.row(v) - mesh.V.row(w)).norm();
            near = d <= tolerance && d > 0;
          }
        }
      }
    }
    unwelded += near;
  }
  return unwelded;
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

namespace {

// The mesh's connected shells in order of their first face, each with its faces and signed volume
// (about the bounding box's centre).
std::vector<Shell> GroupShells(const PolygonMesh& mesh) {
  std::vector<Shell> shells;
  const std::int64_t nf = mesh.num_faces();
  const auto nv = static_cast<std::int32_t>(mesh.V.rows());
  std::vector<std::int32_t> parent(static_cast<std::size_t>(nv));
  std::iota(parent.begin(), parent.end(), 0);
  for (std::int64_t f = 0; f < nf; ++f) {
    const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
    for (int k = 1; k < mesh.face_size(f); ++k) Join<false>(parent.data(), idx[k], idx[0]);
  }
  std::vector<int> shell_of_root(static_cast<std::size_t>(nv), -1);
  const Vector3 ref =
      nv > 0 ? Vector3(0.5 * (mesh.V.colwise().minCoeff() + mesh.V.colwise().maxCoeff()).transpose()) : Vector3::Zero();
  for (std::int64_t f = 0; f < nf; ++f) {
    const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
    const std::int32_t root = Find(parent.data(), idx[0]);
    int& s = shell_of_root[static_cast<std::size_t>(root)];
    if (s < 0) {
      s = static_cast<int>(shells.size());
      shells.emplace_back();
    }
    Shell& shell = shells[static_cast<std::size_t>(s)];
    shell.faces.push_back(f);
    const Vector3 a = mesh.V.row(idx[0]).transpose() - ref;
    for (int k = 1; k + 1 < mesh.face_size(f); ++k) {
      const Vector3 b = mesh.V.row(idx[k]).transpose() - ref;
      const Vector3 c = mesh.V.row(idx[k + 1]).transpose() - ref;
      shell.signed_volume += a.dot(b.cross(c)) / 6.0;
    }
  }
  return shells;
}

// A point just behind face f (the centroid of its first triangle, moved against the face's
// normal by 1e-7 of the triangle's size): inside the face's shell, and off any other shell's
// surface even where two shells touch along a face (an assembly's parts resting on each
// other), where a point on the face itself would have winding number 0 or 1 by rounding.
Vector3 BehindFace(const PolygonMesh& mesh, std::int64_t f) {
  const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
  const Vector3 a = mesh.V.row(idx[0]).transpose(), b = mesh.V.row(idx[1]).transpose(),
                c = mesh.V.row(idx[2]).transpose();
  const Vector3 centroid = (a + b + c) / 3.0;
  const Vector3 n = (b - a).cross(c - a);
  const double size = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  const double length = n.norm();
  if (!(length > 0) || !std::isfinite(length)) return centroid;
  return Vector3(centroid - (1e-7 * size / length) * n);
}

// Samples of face f for the crossing test: behind its first triangle's centroid, behind the
// midpoints of that triangle's edges (pulled 1e-3 of the way toward the centroid, off the edges
// that neighbouring faces share) and behind the polygon's corner average. A crossing can hide
// from centroids alone: two 64-gon prisms crossed at right angles through their middles have
// every side triangle's centroid a third of the way up, outside the other prism, while the
// middle of each side face lies inside it.
std::vector<Vector3> BehindPoints(const PolygonMesh& mesh, std::int64_t f) {
  const Vector3 behind = BehindFace(mesh, f);
  std::vector<Vector3> points{behind};
  const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
  const Vector3 a = mesh.V.row(idx[0]).transpose(), b = mesh.V.row(idx[1]).transpose(),
                c = mesh.V.row(idx[2]).transpose();
  const Vector3 centroid = (a + b + c) / 3.0;
  const Vector3 shift = behind - centroid;
  for (const Vector3& m : {Vector3((a + b) / 2), Vector3((b + c) / 2), Vector3((c + a) / 2)}) {
    points.push_back(m + 1e-3 * (centroid - m) + shift);
  }
  if (mesh.face_size(f) > 3) {
    Vector3 average = Vector3::Zero();
    for (int k = 0; k < mesh.face_size(f); ++k) average += mesh.V.row(idx[k]).transpose();
    points.push_back(average / mesh.face_size(f) + shift);
  }
  return points;
}

// The shells' bounding boxes: outside one (strictly), a closed shell's winding number is 0
// exactly, so most pairs of an assembly's many parts need no sum over faces at all.
struct ShellWinding {
  const PolygonMesh& mesh;
  const std::vector<Shell>& shells;
  std::vector<Eigen::AlignedBox<double, 3>> box;

  ShellWinding(const PolygonMesh& m, const std::vector<Shell>& s) : mesh(m), shells(s), box(s.size()) {
    for (std::size_t i = 0; i < s.size(); ++i) {
      for (std::int64_t f : s[i].faces) {
        for (std::int64_t k = mesh.offsets[f]; k < mesh.offsets[f + 1]; ++k) {
          box[i].extend(mesh.V.row(mesh.indices[static_cast<std::size_t>(k)]).transpose());
        }
      }
    }
  }
  // The winding number of shell t at x.
  double operator()(std::size_t t, const Vector3& x) const {
    if ((x.array() < box[t].min().array()).any() || (x.array() > box[t].max().array()).any()) return 0.0;
    double omega = 0;
    for (std::int64_t f : shells[t].faces) {
      const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
      const Vector3 a = mesh.V.row(idx[0]).transpose() - x;
      for (int k = 1; k + 1 < mesh.face_size(f); ++k) {
        omega += SolidAngle(a, mesh.V.row(idx[k]).transpose() - x, mesh.V.row(idx[k + 1]).transpose() - x);
      }
    }
    return omega / (4.0 * kPi);
  }
};

// Crossing shells: a shell partly inside and partly outside another (their surfaces cross) is
// found from the winding numbers of samples spread over it — points just behind face centroids,
// so that shells that merely touch (shared corners, edges or faces) are not taken for crossing. Found
// whatever the order of the faces. The faces sampled are spread by the golden ratio's sequence, not
// at a fixed stride: a stride that is a multiple of a regular mesh's row length samples one row
// only (16 evenly spaced faces of a 120 × 240 torus all lie on its outer equator).
std::pair<int, int> FindCrossing(const PolygonMesh& mesh, const std::vector<Shell>& shells,
                                 const ShellWinding& winding) {
  constexpr std::size_t kSamples = 32;
  const std::size_t ns = shells.size();
  for (std::size_t s = 0; s < ns; ++s) {
    const std::vector<std::int64_t>& faces = shells[s].faces;
    const std::size_t count = std::min(kSamples, faces.size());
    for (std::size_t t = 0; t < ns; ++t) {
      if (t == s || !shells[t].closed) continue;
      // Boxes apart: every sample is outside t, none inside.
      if (!winding.box[s].intersects(winding.box[t])) continue;
      bool in = false, out = false;
      for (std::size_t k = 0; k < count && !(in && out); ++k) {
        const double spread = std::fmod(0.6180339887498949 * static_cast<double>(k), 1.0);
        const auto at =
            std::min(faces.size() - 1, static_cast<std::size_t>(spread * static_cast<double>(faces.size())));
        for (const Vector3& x : BehindPoints(mesh, faces[at])) {
          const double w = std::fabs(winding(t, x));
          in = in || w > 0.75;
          out = out || w < 0.25;
        }
      }
      if (in && out) return {static_cast<int>(t), static_cast<int>(s)};
    }
  }
  return {-1, -1};
}

// Valid: no shells cross, and each shell's orientation alternates with depth (outward at even
// depth, inward at odd). The fault, or "".
std::string ShellProblem(const ShellReport& report) {
  const std::size_t ns = report.shells.size();
  std::ostringstream problem;
  if (report.crossing.first >= 0) {
    problem << "shells " << report.crossing.first + 1 << " and " << report.crossing.second + 1 << " of " << ns
            << " intersect: part of shell " << report.crossing.second + 1 << " lies inside shell "
            << report.crossing.first + 1
            << " and part outside, so their volumes overlap and would be counted twice; merge them into one "
               "surface (a boolean union) before computing";
  }
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
      problem << "shell " << s + 1 << " of " << ns << " lies inside shell " << report.shells[s].inside_of + 1
              << " and both face outward: their volumes overlap (if it is meant as a cavity, its "
                 "faces must point into the cavity; {repair} orients it so)";
    }
  }
  return problem.str();
}

}  // namespace

ShellReport AnalyzeShells(const PolygonMesh& mesh) {
  ShellReport report;
  report.shells = GroupShells(mesh);
  // Closedness per shell, and a probe point per shell (just behind its first face).
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
    probe[s] = BehindFace(mesh, report.shells[s].faces[0]);
  }
  const ShellWinding winding(mesh, report.shells);
  // Nesting: winding number of shell t at the probe of shell s; the innermost container wins
  // (the one with the smallest |volume|).
  if (ns > 1) {
    for (std::size_t s = 0; s < ns; ++s) {
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t t = 0; t < ns; ++t) {
        if (t == s || !report.shells[t].closed) continue;
        const double size = std::fabs(report.shells[t].signed_volume);
        if (std::fabs(winding(t, probe[s])) > 0.5 && size < best) {
          best = size;
          report.shells[s].inside_of = static_cast<int>(t);
        }
      }
    }
  }
  report.crossing = FindCrossing(mesh, report.shells, winding);
  report.problem = ShellProblem(report);
  return report;
}

}  // namespace massprops
