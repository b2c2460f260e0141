#pragma once
/// @file
/// Integration of a triangle soup — triangles that share no vertex indices, such as the records of
/// a binary STL file as it lies in memory — without building an indexed mesh, with a streaming
/// check that the surface is closed.

#include <cstddef>
#include <cstdint>
#include <functional>

#include "massprops/mass_properties.h"

namespace massprops {

/// What one pass over a triangle soup gives.
struct SoupIntegrals {
  VolumeIntegrals integrals;  ///< as IntegrateTriangles would give for the welded mesh
  std::int64_t triangles = 0;
  Vector3 lower = Vector3::Zero();  ///< bounding box of the corners
  Vector3 upper = Vector3::Zero();
  /// Σ over the directed edges p→q of all triangles of h(p)·g(q) − h(q)·g(p) (mod 2⁶⁴), where h and
  /// g are 64-bit hashes of a corner's exact position. Every edge matched by its reverse — the
  /// surface is a closed, consistently oriented cycle, which is exactly when its volume integrals
  /// do not depend on the reference point — gives 0. An open or inconsistent surface gives a
  /// non-zero value but for a chance of about 2⁻⁶⁰. Independent of the order of the triangles.
  std::uint64_t unmatched_edge_hash = 0;

  /// Two triangles with the same three corners, in either orientation (a surface there twice,
  /// or double-sided), found from a 64-bit key of each triangle's corner positions: a false alarm
  /// has a chance of about n²·2⁻⁶⁵ (2·10⁻⁸ for 2·10⁶ triangles), and asks only for the full check.
  bool repeated_faces = false;

  /// Connected shells (triangles joined through shared corner positions), counted by a union–find
  /// over each block of triangles and then over the blocks' pieces: two shells — nested, apart or
  /// overlapping — which the edge balance above cannot tell from one. −1 when not counted (more
  /// than 2³² pieces). A 64-bit hash collision of two corners could join two shells (a chance of
  /// about V²·2⁻⁶⁵ for V corners).
  std::int64_t shells = 0;

  bool IsClosedCycle() const { return unmatched_edge_hash == 0; }
};

/// Integrates `count` triangles stored as fixed-size records: record i starts at
/// `data + i·stride` and holds its 9 float32 corner coordinates (a, b, c) at byte `offset`, in
/// the host's byte order (binary STL: stride 50, offset 12). Corners are converted to double
/// exactly. The reference point is options.reference, or else the first corner.
/// @throws std::invalid_argument naming the first triangle with a non-finite coordinate.
SoupIntegrals IntegrateFloatTriangleRecords(const unsigned char* data, std::int64_t count, std::size_t stride,
                                            std::size_t offset, const IntegrationOptions& options = {});

/// Fills `dest` with `count` records starting at record `first` (count · stride bytes), e.g. by
/// pread from a file. Called from worker threads, once per block; may throw.
using RecordReader = std::function<void(std::int64_t first, std::int64_t count, unsigned char* dest)>;

/// As above, with the records fetched block by block through `read` into a small per-thread
/// buffer that stays in cache while it is integrated: a file is streamed once, with little memory.
SoupIntegrals IntegrateFloatTriangleRecords(const RecordReader& read, std::int64_t count, std::size_t stride,
                                            std::size_t offset, const IntegrationOptions& options = {});

}  // namespace massprops
