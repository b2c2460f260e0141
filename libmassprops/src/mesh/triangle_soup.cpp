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
#include "mesh/soup_scan.h"
#include "mesh/soup_shells.h"

namespace massprops {
namespace {

using internal::Batch;
using internal::LaneSums;
using internal::Moments;

constexpr std::int64_t kBlock = 4096;
constexpr std::int64_t kShellBlocks = 8;

struct BlockResult {
  Moments moments;
  internal::ScanSums scan;
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
        const int bad =
            internal::ScanRecords(data + static_cast<std::size_t>(t0 - begin) * stride, n, stride, offset, ref.data(),
                                  batch, s.corner_hash, s.face_keys.data() + (t0 - group_begin), res.scan);
        if (bad >= 0 && res.first_bad < 0) res.first_bad = t0 + bad;
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
    out.unmatched_edge_hash += p.scan.edge_hash;
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], static_cast<double>(p.scan.lo[k]));
      hi[k] = std::max(hi[k], static_cast<double>(p.scan.hi[k]));
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
