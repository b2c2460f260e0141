// The floor of reading a binary STL for its mass properties: stream the file block by block on
// two threads (pread into per-thread buffers, as the reader does) and sum the ten moments of the
// signed tetrahedra (volume, first and second moments about the origin) in double, doing nothing
// else — no checks, no reference point, no welding. bench/end_to_end.py times `massprops` against
// it (issue 51: the checks at the cost of the arithmetic).
//   stl_floor FILE.stl [THREADS]   prints the volume (so the sums cannot be optimized away)

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "massprops/parallel.h"

namespace {

constexpr std::size_t kRecord = 50;          // 12 floats and a 2-byte attribute
constexpr std::int64_t kPerBlock = 1 << 15;  // records a block (1.6 MB)

struct Moments {
  std::array<double, 10> m{};  // V, ∫x, ∫y, ∫z, ∫x², ∫y², ∫z², ∫xy, ∫yz, ∫zx (×6 and ×24, ×60/120 kept apart)
  Moments& operator+=(const Moments& o) {
    for (std::size_t k = 0; k < m.size(); ++k) m[k] += o.m[k];
    return *this;
  }
};

void AddTriangle(const float* f, Moments& out) {
  const double ax = f[0], ay = f[1], az = f[2], bx = f[3], by = f[4], bz = f[5], cx = f[6], cy = f[7], cz = f[8];
  const double d = ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);  // 6 V
  const double sx = ax + bx + cx, sy = ay + by + cy, sz = az + bz + cz;
  auto& m = out.m;
  m[0] += d;
  m[1] += d * sx;
  m[2] += d * sy;
  m[3] += d * sz;
  m[4] += d * (ax * ax + bx * bx + cx * cx + sx * sx);
  m[5] += d * (ay * ay + by * by + cy * cy + sy * sy);
  m[6] += d * (az * az + bz * bz + cz * cz + sz * sz);
  m[7] += d * (ax * ay + bx * by + cx * cy + sx * sy);
  m[8] += d * (ay * az + by * bz + cy * cz + sy * sz);
  m[9] += d * (az * ax + bz * bx + cz * cx + sz * sx);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: stl_floor FILE.stl [THREADS]\n");
    return 2;
  }
  const int threads = argc > 2 ? std::atoi(argv[2]) : 2;
  const int fd = ::open(argv[1], O_RDONLY);
  unsigned char head[84];
  if (fd < 0 || ::pread(fd, head, sizeof head, 0) != static_cast<ssize_t>(sizeof head)) {
    std::fprintf(stderr, "error: %s: cannot read its header\n", argv[1]);
    return 1;
  }
  std::uint32_t count;
  std::memcpy(&count, head + 80, 4);
  const std::int64_t blocks = (static_cast<std::int64_t>(count) + kPerBlock - 1) / kPerBlock;
  std::vector<Moments> parts(static_cast<std::size_t>(blocks));
  massprops::ParallelForBlocks(blocks, threads, [&](std::int64_t b) {
    std::vector<unsigned char>& buffer = massprops::ThreadScratch<std::vector<unsigned char>>();
    const std::int64_t first = b * kPerBlock, n = std::min<std::int64_t>(kPerBlock, count - first);
    buffer.resize(static_cast<std::size_t>(n) * kRecord);
    const auto want = static_cast<ssize_t>(buffer.size());
    if (::pread(fd, buffer.data(), buffer.size(), 84 + first * static_cast<std::int64_t>(kRecord)) != want) {
      std::fprintf(stderr, "error: %s: cut short\n", argv[1]);
      std::exit(1);
    }
    Moments m;
    float f[9];
    for (std::int64_t t = 0; t < n; ++t) {
      std::memcpy(f, buffer.data() + t * static_cast<std::int64_t>(kRecord) + 12, sizeof f);
      AddTriangle(f, m);
    }
    parts[static_cast<std::size_t>(b)] = m;
  });
  const Moments total = massprops::PairwiseSum(parts);
  std::printf("%.17g\n", total.m[0] / 6);
  ::close(fd);
  return 0;
}
