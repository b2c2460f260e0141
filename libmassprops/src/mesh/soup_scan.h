#pragma once
// One batch of a triangle soup's float records read for the streamed pass: the corners as
// doubles about the reference point (for the integration kernel), each corner's position hash
// (for the shell count), each triangle's face key (for repeated faces), the matched-edge hash
// and the bounding box. Written as loops over the batch's triangles, so that the compiler
// vectorizes them (64-bit multiplies: AVX-512, chosen at run time); every result is an integer
// or an exact conversion, so the bits do not depend on the instructions chosen.

#include <cstddef>
#include <cstdint>

#include "core/triangle_kernel.h"

namespace massprops::internal {

/// What a batch adds to its block's sums.
struct ScanSums {
  std::uint64_t edge_hash = 0;  ///< Σ over directed edges p→q of h(p)·g(q) − h(q)·g(p), mod 2⁶⁴
  float lo[3], hi[3];           ///< the bounding box, merged with the batch's corners
  ScanSums();
};

/// Reads `n` ≤ kBatch records (record j at records + j·stride, its 9 floats at `offset`) into
/// `batch` (corners minus `ref`), `corners` (3n position hashes, a b c per triangle) and
/// `face_keys` (n keys that do not depend on the corners' order), and adds to `sums`. Returns the
/// index in the batch of the first triangle with a non-finite coordinate, or −1.
int ScanRecords(const unsigned char* records, int n, std::size_t stride, std::size_t offset, const double* ref,
                Batch& batch, std::uint64_t* corners, std::uint64_t* face_keys, ScanSums& sums);

}  // namespace massprops::internal
