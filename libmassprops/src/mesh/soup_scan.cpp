// The definitions of soup_scan.h: one batch of a triangle soup's float records read for the
// streamed pass.

#include "mesh/soup_scan.h"

#include <cstring>
#include <limits>

#include "massprops/simd_clones.h"

namespace massprops::internal {
namespace {

// A corner's two hashes from its coordinates' bits (-0.0 counts as 0.0): multiply–xorshift
// mixing, four multiplications in all. The tests flip or drop every triangle of a regular grid
// mesh in turn and require the checks to notice.
inline void HashCorner(std::uint32_t x, std::uint32_t y, std::uint32_t z, std::uint64_t& h, std::uint64_t& g) {
  x = x == 0x80000000u ? 0u : x;
  y = y == 0x80000000u ? 0u : y;
  z = z == 0x80000000u ? 0u : z;
  h = (x | static_cast<std::uint64_t>(y) << 32) * 0xD6E8FEB86659FD93ull ^
      (static_cast<std::uint64_t>(z) + 0x9E3779B97F4A7C15ull) * 0xA0761D6478BD642Full;
  h ^= h >> 31;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 29;
  g = h * 0x94D049BB133111EBull;
  g ^= g >> 32;
}

// A key of a triangle's corner positions that does not depend on their order: symmetric
// functions (sum, and sum of products) of the corners' hashes, mixed.
inline std::uint64_t FaceKey(std::uint64_t ha, std::uint64_t hb, std::uint64_t hc, std::uint64_t ga, std::uint64_t gb,
                             std::uint64_t gc) {
  std::uint64_t k = (ha + hb + hc) ^ ((ga * gb + gb * gc + gc * ga) * 0x9E3779B97F4A7C15ull);
  k ^= k >> 32;
  k *= 0xD6E8FEB86659FD93ull;
  return k ^ (k >> 29);
}

}  // namespace

ScanSums::ScanSums() {
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::numeric_limits<float>::infinity();
    hi[k] = -std::numeric_limits<float>::infinity();
  }
}

MASSPROPS_CLONES_AVX2_AVX512
int ScanRecords(const unsigned char* records, int n, std::size_t stride, std::size_t offset, const double* ref,
                Batch& batch, std::uint64_t* corners, std::uint64_t* face_keys, ScanSums& sums) {
  // The records' coordinate bits, one array per coordinate (the one scalar loop).
  alignas(64) std::uint32_t bits[9][kBatch];
  for (int j = 0; j < n; ++j) {
    const unsigned char* rec = records + static_cast<std::size_t>(j) * stride + offset;
    // Records in memory (a mapped file) may sit in scattered 4 KiB pages that the hardware
    // prefetcher does not cross: ask for bytes ahead (a hint; past the end is no access).
    __builtin_prefetch(rec + 2048);
    std::uint32_t c[9];
    std::memcpy(c, rec, sizeof c);
    for (int k = 0; k < 9; ++k) bits[k][j] = c[k];
  }
  // Non-finite coordinates (exponent all ones), and the box.
  std::uint32_t bad[kBatch];
  for (int j = 0; j < n; ++j) {
    std::uint32_t any = 0;
    for (int k = 0; k < 9; ++k) any |= static_cast<std::uint32_t>((bits[k][j] & 0x7F800000u) == 0x7F800000u);
    bad[j] = any;
  }
  for (int k = 0; k < 9; ++k) {
    float lo = sums.lo[k % 3], hi = sums.hi[k % 3];
    for (int j = 0; j < n; ++j) {
      float v;
      std::memcpy(&v, &bits[k][j], sizeof v);
      lo = v < lo ? v : lo;  // as std::min / std::max: a NaN is refused above, never kept
      hi = hi < v ? v : hi;
    }
    sums.lo[k % 3] = lo;
    sums.hi[k % 3] = hi;
  }
  // Corners about the reference point, exactly converted to double.
  double* dest[9] = {batch.ax, batch.ay, batch.az, batch.bx, batch.by, batch.bz, batch.cx, batch.cy, batch.cz};
  for (int k = 0; k < 9; ++k) {
    const double r = ref[k % 3];
    for (int j = 0; j < n; ++j) {
      float v;
      std::memcpy(&v, &bits[k][j], sizeof v);
      dest[k][j] = static_cast<double>(v) - r;
    }
  }
  // Hashes: corners, directed edges, faces.
  std::uint64_t edge = 0;
  for (int j = 0; j < n; ++j) {
    std::uint64_t ha, ga, hb, gb, hc, gc;
    HashCorner(bits[0][j], bits[1][j], bits[2][j], ha, ga);
    HashCorner(bits[3][j], bits[4][j], bits[5][j], hb, gb);
    HashCorner(bits[6][j], bits[7][j], bits[8][j], hc, gc);
    edge += (ha * gb - hb * ga) + (hb * gc - hc * gb) + (hc * ga - ha * gc);
    face_keys[j] = FaceKey(ha, hb, hc, ga, gb, gc);
    corners[3 * j] = ha;
    corners[3 * j + 1] = hb;
    corners[3 * j + 2] = hc;
  }
  sums.edge_hash += edge;
  for (int j = 0; j < n; ++j) {
    if (bad[j] != 0) return j;
  }
  return -1;
}

}  // namespace massprops::internal
