// The definitions of massprops/triangle_soup.h: integration of a triangle soup — triangles that
// share no vertex indices, such as the records of a binary STL file as it lies in memory — without
// building an indexed mesh, with a streaming check that the surface is closed.

#include "massprops/triangle_soup.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/triangle_kernel.h"
#include "massprops/parallel.h"
#include "mesh/soup_faces.h"
#include "mesh/soup_shells.h"

namespace massprops {
namespace {

using internal::Batch;
using internal::LaneSums;
using internal::Moments;

constexpr std::int64_t kBlock = 4096;
constexpr std::int64_t kShellBlocks = 8;
constexpr std::size_t kPrefetchBytes = 2048;

struct CornerHash {
  std::uint64_t h, g;
};

// Two hashes of a corner's exact position (-0.0 counts as 0.0): multiply–xorshift mixing, four
// multiplications in all (this runs three times per triangle, so it is kept lean; the tests flip or
// drop every triangle of a regular grid mesh in turn and require the check to notice).
inline CornerHash HashCorner(const float* p) {
  std::uint32_t b[3];
  std::memcpy(b, p, sizeof b);
  for (auto& v : b) v = (v == 0x80000000u) ? 0u : v;
  std::uint64_t h = (b[0] | static_cast<std::uint64_t>(b[1]) << 32) * 0xD6E8FEB86659FD93ull ^
                    (static_cast<std::uint64_t>(b[2]) + 0x9E3779B97F4A7C15ull) * 0xA0761D6478BD642Full;
  h ^= h >> 31;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 29;
  std::uint64_t g = h * 0x94D049BB133111EBull;
  g ^= g >> 32;
  return {h, g};
}

inline bool Finite(float v) {
  std::uint32_t b;
  std::memcpy(&b, &v, sizeof b);
  return (b & 0x7F800000u) != 0x7F800000u;
}

// A key of a triangle's corner positions that does not depend on their order: symmetric
// functions (sum, and sum of products) of the corners' hashes, mixed.
inline std::uint64_t FaceKey(const CornerHash& a, const CornerHash& b, const CornerHash& c) {
  std::uint64_t k = (a.h + b.h + c.h) ^ ((a.g * b.g + b.g * c.g + c.g * a.g) * 0x9E3779B97F4A7C15ull);
  k ^= k >> 32;
  k *= 0xD6E8FEB86659FD93ull;
  return k ^ (k >> 29);
}

struct BlockResult {
  Moments moments;
  std::uint64_t edge_hash = 0;
  float lo[3] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
                 std::numeric_limits<float>::infinity()};
  float hi[3] = {-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                 -std::numeric_limits<float>::infinity()};
  std::int64_t first_bad = -1;
};

// `fetch(begin, n)` returns a pointer to records begin .. begin+n−1 (called once per block).
template <typename Fetch>
SoupIntegrals Integrate(const Fetch& fetch, std::int64_t count, std::size_t stride, std::size_t offset,
                        const Vector3& first_corner, const IntegrationOptions& options) {
  SoupIntegrals out;
  out.triangles = count;
  const Vector3 ref = options.reference.value_or(first_corner);
  if (!ref.allFinite()) {
    throw std::invalid_argument("triangle 0 has a non-finite coordinate");
  }
  const std::int64_t blocks = (count + kBlock - 1) / kBlock;
  std::vector<BlockResult> parts(static_cast<std::size_t>(blocks));
  internal::ShellCounter shells;
  constexpr std::int64_t kGroup = kShellBlocks * kBlock;
  internal::FaceKeyBuckets faces(count, kGroup);

  // Blocks are integrated kShellBlocks at a time by one thread, and their corners joined together
  // (fewer corners left open at the edges of a group than of each block); each block's moments
  // are its own, so the bits do not depend on the grouping.
  const std::int64_t groups = (blocks + kShellBlocks - 1) / kShellBlocks;
  ParallelForBlocks(groups, options.num_threads, [&](std::int64_t group) {
    struct Scratch {
      internal::GroupJoiner joiner;
      std::vector<std::uint64_t> face_keys;
      std::vector<std::uint32_t> face_counts;
      std::uint64_t corner_hash[3 * internal::kBatch];
    };
    Scratch& s = ThreadScratch<Scratch>();
    const std::int64_t group_begin = group * kGroup;
    const auto group_size = static_cast<int>(std::min(count, group_begin + kGroup) - group_begin);
    s.joiner.Begin(group_size);
    s.face_keys.resize(static_cast<std::size_t>(kGroup));
    for (std::int64_t b = group * kShellBlocks; b < std::min(blocks, (group + 1) * kShellBlocks); ++b) {
      BlockResult res;
      Batch batch;
      LaneSums sums;
      const std::int64_t begin = b * kBlock, end = std::min(count, begin + kBlock);
      const unsigned char* data = fetch(begin, end - begin);
      for (std::int64_t t0 = begin; t0 < end; t0 += internal::kBatch) {
        const int n = static_cast<int>(std::min<std::int64_t>(internal::kBatch, end - t0));
        for (int j = 0; j < n; ++j) {
          const unsigned char* rec = data + static_cast<std::size_t>(t0 - begin + j) * stride + offset;
          // Records in memory (a mapped file) may sit in scattered 4 KiB pages that the hardware
          // prefetcher does not cross: ask for bytes ahead (a hint; past the end is no access).
          __builtin_prefetch(rec + kPrefetchBytes);
          float c[9];
          std::memcpy(c, rec, sizeof c);
          bool finite = true;
          for (int k = 0; k < 9; ++k) {
            finite = finite && Finite(c[k]);
            res.lo[k % 3] = std::min(res.lo[k % 3], c[k]);
            res.hi[k % 3] = std::max(res.hi[k % 3], c[k]);
          }
          if (!finite && res.first_bad < 0) res.first_bad = t0 + j;
          // Directed edges a→b, b→c, c→a.
          const CornerHash ha = HashCorner(c), hb = HashCorner(c + 3), hc = HashCorner(c + 6);
          res.edge_hash += ha.h * hb.g - hb.h * ha.g;
          res.edge_hash += hb.h * hc.g - hc.h * hb.g;
          res.edge_hash += hc.h * ha.g - ha.h * hc.g;
          s.face_keys[static_cast<std::size_t>(t0 + j - group_begin)] = FaceKey(ha, hb, hc);
          std::uint64_t* corner = s.corner_hash + 3 * j;
          corner[0] = ha.h;
          corner[1] = hb.h;
          corner[2] = hc.h;
          internal::SetTriangle(batch, j, c, c + 3, c + 6, ref.data());
        }
        s.joiner.AddAll(s.corner_hash, n);
        internal::AccumulateBatch(batch, internal::PadBatch(batch, n), sums);
      }
      sums.Into(res.moments);
      parts[static_cast<std::size_t>(b)] = res;
    }
    faces.Put(group, s.face_keys.data(), group_size, s.face_counts);
    internal::BlockPieces pieces;
    s.joiner.Finish(pieces);
    shells.Add(group, std::move(pieces));
  });

  std::vector<Moments> moments(parts.size());
  Vector3 lo = Vector3::Constant(std::numeric_limits<double>::infinity());
  Vector3 hi = -lo;
  for (std::size_t b = 0; b < parts.size(); ++b) {
    const BlockResult& p = parts[b];
    if (p.first_bad >= 0) {
      std::ostringstream msg;
      msg << "triangle " << p.first_bad << " has a non-finite coordinate";
      throw std::invalid_argument(msg.str());
    }
    moments[b] = p.moments;
    out.unmatched_edge_hash += p.edge_hash;
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], static_cast<double>(p.lo[k]));
      hi[k] = std::max(hi[k], static_cast<double>(p.hi[k]));
    }
  }
  if (count > 0) {
    out.lower = lo;
    out.upper = hi;
  }
  out.integrals = internal::ScaleTriangleSums(PairwiseSum(moments)).ToIntegrals(ref);
  out.repeated_faces = faces.AnyRepeated(options.num_threads);
  out.shells = shells.Shells();
  return out;
}

Vector3 FirstCorner(const unsigned char* record, std::size_t offset) {
  float p[3];
  std::memcpy(p, record + offset, sizeof p);
  return Vector3(p[0], p[1], p[2]);
}

}  // namespace

SoupIntegrals IntegrateFloatTriangleRecords(const unsigned char* data, std::int64_t count, std::size_t stride,
                                            std::size_t offset, const IntegrationOptions& options) {
  const Vector3 first = count > 0 ? FirstCorner(data, offset) : Vector3::Zero();
  return Integrate([&](std::int64_t begin, std::int64_t) { return data + begin * stride; }, count, stride, offset,
                   first, options);
}

SoupIntegrals IntegrateFloatTriangleRecords(const RecordReader& read, std::int64_t count, std::size_t stride,
                                            std::size_t offset, const IntegrationOptions& options) {
  Vector3 first = Vector3::Zero();
  if (count > 0) {
    std::vector<unsigned char> rec(stride);
    read(0, 1, rec.data());
    first = FirstCorner(rec.data(), offset);
  }
  return Integrate(
      [&](std::int64_t begin, std::int64_t n) {
        // One buffer per thread, reused across blocks: it stays in L2 while integrated.
        thread_local std::vector<unsigned char> buffer;
        buffer.resize(static_cast<std::size_t>(kBlock) * stride);
        read(begin, n, buffer.data());
        return static_cast<const unsigned char*>(buffer.data());
      },
      count, stride, offset, first, options);
}

}  // namespace massprops
