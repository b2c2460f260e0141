#pragma once
// The triangle kernel shared by the indexed-mesh path and the triangle-soup (binary STL) path.

#include <cmath>

#include "core/moments.h"

namespace massprops::internal {

// Triangles are integrated in batches: corners are gathered (relative to the reference point)
// into structure-of-arrays buffers, then a lane loop accumulates kLanes triangles side by side into
// kLanes separate sums, which the compiler turns into SIMD code. The lanes are added in a fixed
// order at the end, so the bits do not depend on the vector width the compiler picked.
constexpr int kLanes = 4;
constexpr int kBatch = 256;  // multiple of kLanes

struct Batch {
  alignas(64) double ax[kBatch], ay[kBatch], az[kBatch];
  alignas(64) double bx[kBatch], by[kBatch], bz[kBatch];
  alignas(64) double cx[kBatch], cy[kBatch], cz[kBatch];
};

struct LaneSums {
  double q[11][kLanes] = {};  // d, d·s (3), d·(Σvvᵀ + ssᵀ) (6), |n|

  void Into(Moments& m) const {
    double r[11];
    for (int k = 0; k < 11; ++k) r[k] = (q[k][0] + q[k][1]) + (q[k][2] + q[k][3]);
    m.v += r[0];
    m.x += r[1];
    m.y += r[2];
    m.z += r[3];
    m.xx += r[4];
    m.yy += r[5];
    m.zz += r[6];
    m.xy += r[7];
    m.yz += r[8];
    m.zx += r[9];
    m.area += r[10];
  }
};

// Signed tetrahedron of each triangle (a, b, c) with the reference point: with d = a·(b×c) and
// s = a+b+c, adds d, d·s, d·(Σ v vᵀ + s sᵀ) and |(b−a)×(c−a)| (scaled once at the end).
// `count` is a multiple of kLanes (the batch is padded with zero triangles, which add exact zeros).
void AccumulateBatch(const Batch& t, int count, LaneSums& sums);

/// Stores triangle j of a batch: corners a, b, c (3 coordinates each, float or double) relative
/// to the reference point r.
template <typename T>
inline void SetTriangle(Batch& t, int j, const T* a, const T* b, const T* c, const double* r) {
  t.ax[j] = a[0] - r[0];
  t.ay[j] = a[1] - r[1];
  t.az[j] = a[2] - r[2];
  t.bx[j] = b[0] - r[0];
  t.by[j] = b[1] - r[1];
  t.bz[j] = b[2] - r[2];
  t.cx[j] = c[0] - r[0];
  t.cy[j] = c[1] - r[1];
  t.cz[j] = c[2] - r[2];
}

/// Pads a batch of `count` triangles with zero triangles up to a multiple of kLanes; returns it.
inline int PadBatch(Batch& b, int count) {
  const int padded = (count + kLanes - 1) / kLanes * kLanes;
  for (int j = count; j < padded; ++j) {
    b.ax[j] = b.ay[j] = b.az[j] = b.bx[j] = b.by[j] = b.bz[j] = b.cx[j] = b.cy[j] = b.cz[j] = 0.0;
  }
  return padded;
}

/// Divides the raw sums by 6, 24, 120 and 2 (see AccumulateBatch).
Moments ScaleTriangleSums(const Moments& raw);

/// Bounding box of the vertices (validating finiteness; throws naming the first bad vertex).
Vector3 ReferencePoint(const Eigen::Ref<const VertexMatrix>& V, int num_threads, const char* what);

/// Checks a polygon mesh's structure: offsets that match the index list, at least 3 corners per
/// face, indices in range. Throws std::invalid_argument starting with `what`.
void CheckPolygonMesh(const PolygonMesh& mesh, const char* what);

}  // namespace massprops::internal
