// Mirtich's polyhedral mass properties: volume integrals reduced to face integrals by the
// divergence theorem, face integrals to integrals over the face's projection onto the coordinate
// plane where it is largest, and those to sums over the projected edges by Green's theorem.
// B. Mirtich, "Fast and Accurate Computation of Polyhedral Mass Properties", journal of graphics
// tools 1(2):31-50, 1996. Symbols follow the paper: α, β, γ are a right-handed permutation of
// x, y, z with γ the largest component of the face normal n, and w = −n·p for any p on the face.

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/moments.h"
#include "core/triangle_kernel.h"
#include "massprops/mass_properties.h"
#include "massprops/parallel.h"

namespace massprops {

namespace {

using internal::Moments;

constexpr std::int64_t kFaceBlock = 2048;

// Adds one planar polygon's contribution. `p(k)` gives corner k relative to the reference point.
template <typename CornerFn>
void AccumulatePolygon(int n, const CornerFn& p, Moments& m) {
  // Newell's normal: exact area vector of a planar polygon, a robust average plane otherwise.
  double nx = 0, ny = 0, nz = 0, cx = 0, cy = 0, cz = 0;
  for (int k = 0; k < n; ++k) {
    const double* a = p(k);
    const double* b = p(k + 1 == n ? 0 : k + 1);
    nx += (a[1] - b[1]) * (a[2] + b[2]);
    ny += (a[2] - b[2]) * (a[0] + b[0]);
    nz += (a[0] - b[0]) * (a[1] + b[1]);
    cx += a[0];
    cy += a[1];
    cz += a[2];
  }
  const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
  if (len == 0.0) return;  // zero-area face: contributes nothing
  m.area += 0.5 * len;
  const double nrm[3] = {nx / len, ny / len, nz / len};
  const double w = -(nrm[0] * cx + nrm[1] * cy + nrm[2] * cz) / n;

  // γ = axis of the largest normal component; (α, β, γ) cyclic, so the projection keeps the
  // polygon's orientation when n_γ > 0.
  const double ax = std::fabs(nrm[0]), ay = std::fabs(nrm[1]), az = std::fabs(nrm[2]);
  const int C = (ax > ay && ax > az) ? 0 : (ay > az ? 1 : 2);
  const int A = (C + 1) % 3;
  const int B = (A + 1) % 3;

  // Projection integrals over the polygon projected onto the α-β plane.
  double P1 = 0, Pa = 0, Pb = 0, Paa = 0, Pab = 0, Pbb = 0, Paaa = 0, Paab = 0, Pabb = 0, Pbbb = 0;
  for (int k = 0; k < n; ++k) {
    const double* e0 = p(k);
    const double* e1 = p(k + 1 == n ? 0 : k + 1);
    const double a0 = e0[A], b0 = e0[B], a1 = e1[A], b1 = e1[B];
    const double da = a1 - a0, db = b1 - b0;
    const double a0_2 = a0 * a0, a0_3 = a0_2 * a0, a0_4 = a0_3 * a0;
    const double b0_2 = b0 * b0, b0_3 = b0_2 * b0, b0_4 = b0_3 * b0;
    const double a1_2 = a1 * a1, a1_3 = a1_2 * a1;
    const double b1_2 = b1 * b1, b1_3 = b1_2 * b1;

    const double C1 = a1 + a0;
    const double Ca = a1 * C1 + a0_2;
    const double Caa = a1 * Ca + a0_3;
    const double Caaa = a1 * Caa + a0_4;
    const double Cb = b1 * (b1 + b0) + b0_2;
    const double Cbb = b1 * Cb + b0_3;
    const double Cbbb = b1 * Cbb + b0_4;
    const double Cab = 3 * a1_2 + 2 * a1 * a0 + a0_2;
    const double Kab = a1_2 + 2 * a1 * a0 + 3 * a0_2;
    const double Caab = a0 * Cab + 4 * a1_3;
    const double Kaab = a1 * Kab + 4 * a0_3;
    const double Cabb = 4 * b1_3 + 3 * b1_2 * b0 + 2 * b1 * b0_2 + b0_3;
    const double Kabb = b1_3 + 2 * b1_2 * b0 + 3 * b1 * b0_2 + 4 * b0_3;

    P1 += db * C1;
    Pa += db * Ca;
    Paa += db * Caa;
    Paaa += db * Caaa;
    Pb += da * Cb;
    Pbb += da * Cbb;
    Pbbb += da * Cbbb;
    Pab += db * (b1 * Cab + b0 * Kab);
    Paab += db * (b1 * Caab + b0 * Kaab);
    Pabb += da * (a1 * Cabb + a0 * Kabb);
  }
  P1 /= 2.0;
  Pa /= 6.0;
  Paa /= 12.0;
  Paaa /= 20.0;
  Pb /= -6.0;
  Pbb /= -12.0;
  Pbbb /= -20.0;
  Pab /= 24.0;
  Paab /= 60.0;
  Pabb /= -60.0;

  // Face integrals over the polygon in 3-D (divided by |n_γ| through k1 = 1/n_γ).
  const double na = nrm[A], nb = nrm[B];
  const double k1 = 1.0 / nrm[C], k2 = k1 * k1, k3 = k2 * k1, k4 = k3 * k1;
  const double Fa = k1 * Pa;
  const double Fb = k1 * Pb;
  const double Fc = -k2 * (na * Pa + nb * Pb + w * P1);
  const double Faa = k1 * Paa;
  const double Fbb = k1 * Pbb;
  const double Fcc = k3 * (na * na * Paa + 2 * na * nb * Pab + nb * nb * Pbb + w * (2 * (na * Pa + nb * Pb) + w * P1));
  const double Faaa = k1 * Paaa;
  const double Fbbb = k1 * Pbbb;
  const double Fccc =
      -k4 * (na * na * na * Paaa + 3 * na * na * nb * Paab + 3 * na * nb * nb * Pabb + nb * nb * nb * Pbbb +
             3 * w * (na * na * Paa + 2 * na * nb * Pab + nb * nb * Pbb) + w * w * (3 * (na * Pa + nb * Pb) + w * P1));
  const double Faab = k1 * Paab;
  const double Fbbc = -k2 * (na * Pabb + nb * Pbbb + w * Pbb);
  const double Fcca =
      k3 * (na * na * Paaa + 2 * na * nb * Paab + nb * nb * Pabb + w * (2 * (na * Paa + nb * Pab) + w * Pa));

  // Volume integrals: T0 = ∫dV (from the x-face integral), T1 = ∫r, T2 = ∫r², TP = products.
  m.v += nrm[0] * (A == 0 ? Fa : (B == 0 ? Fb : Fc));
  double T1[3], T2[3], TP[3];
  T1[A] = nrm[A] * Faa;
  T1[B] = nrm[B] * Fbb;
  T1[C] = nrm[C] * Fcc;
  T2[A] = nrm[A] * Faaa;
  T2[B] = nrm[B] * Fbbb;
  T2[C] = nrm[C] * Fccc;
  TP[A] = nrm[A] * Faab;  // ∫αβ
  TP[B] = nrm[B] * Fbbc;  // ∫βγ
  TP[C] = nrm[C] * Fcca;  // ∫γα
  m.x += T1[0] / 2.0;
  m.y += T1[1] / 2.0;
  m.z += T1[2] / 2.0;
  m.xx += T2[0] / 3.0;
  m.yy += T2[1] / 3.0;
  m.zz += T2[2] / 3.0;
  // TP[A] is ∫αβ: with (A,B) = (0,1) it is ∫xy, (1,2) ∫yz, (2,0) ∫zx.
  m.xy += TP[0] / 2.0;
  m.yz += TP[1] / 2.0;
  m.zx += TP[2] / 2.0;
}

}  // namespace

namespace internal {

void CheckPolygonMesh(const PolygonMesh& mesh, const char* what) {
  if (mesh.offsets.empty() || mesh.offsets.front() != 0 ||
      mesh.offsets.back() != static_cast<std::int64_t>(mesh.indices.size())) {
    throw std::invalid_argument(std::string(what) + ": face offsets do not match the index list");
  }
  for (std::int64_t f = 0; f < mesh.num_faces(); ++f) {
    if (mesh.face_size(f) < 3) {
      std::ostringstream msg;
      msg << what << ": face " << f << " has " << mesh.face_size(f) << " corners; a face needs at least 3";
      throw std::invalid_argument(msg.str());
    }
  }
  const std::int64_t nv = mesh.V.rows();
  for (const std::int32_t i : mesh.indices) {
    if (i < 0 || i >= nv) {
      std::ostringstream msg;
      msg << what << ": a face refers to vertex " << i << ", but the mesh has " << nv << " vertices";
      throw std::invalid_argument(msg.str());
    }
  }
}

}  // namespace internal

VolumeIntegrals IntegratePolygons(const PolygonMesh& mesh, const IntegrationOptions& options) {
  const Vector3 center = internal::ReferencePoint(mesh.V, options.num_threads, "IntegratePolygons");
  const Vector3 ref = options.reference.value_or(center);
  if (!ref.allFinite()) {
    throw std::invalid_argument("IntegratePolygons: the reference point is not finite");
  }
  internal::CheckPolygonMesh(mesh, "IntegratePolygons");
  const std::int64_t nf = mesh.num_faces();

  const std::int64_t blocks = (nf + kFaceBlock - 1) / kFaceBlock;
  std::vector<Moments> parts(static_cast<std::size_t>(blocks));
  ParallelForBlocks(blocks, ThreadsForItems(options.num_threads, nf), [&](std::int64_t b) {
    Moments m;
    std::vector<double> corners;
    const std::int64_t end = std::min(nf, (b + 1) * kFaceBlock);
    for (std::int64_t f = b * kFaceBlock; f < end; ++f) {
      const int n = mesh.face_size(f);
      corners.resize(3 * static_cast<std::size_t>(n));
      const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
      for (int k = 0; k < n; ++k) {
        for (int j = 0; j < 3; ++j) corners[3 * k + j] = mesh.V(idx[k], j) - ref[j];
      }
      AccumulatePolygon(
          n, [&](int k) { return corners.data() + 3 * k; }, m);
    }
    parts[static_cast<std::size_t>(b)] = m;
  });
  return PairwiseSum(parts).ToIntegrals(ref);
}

}  // namespace massprops
