// Writes a tessellated torus with about N triangles, for the end-to-end benchmark: a binary STL, or
// an OBJ (shared vertices, coordinates with 17 significant digits) when OUT ends in .obj:
//   make_torus_stl N OUT.stl|OUT.obj
// The torus (R = 2, a = 0.5, metres) has a closed form, so the output can be checked too.

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "massprops/solids.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: make_torus_stl TRIANGLES OUT.stl\n";
    return 2;
  }
  const long long target = std::atoll(argv[1]);
  if (target < 36) {
    std::cerr << "error: TRIANGLES must be at least 36\n";
    return 2;
  }
  int n = 3;
  while (4LL * n * n < target) ++n;
  const massprops::TriangleMesh m = massprops::solids::Torus(2.0, 0.5, n);
  const std::string out_path = argv[2];
  const std::string tmp = out_path + ".tmp";
  const bool obj = out_path.size() > 4 && out_path.compare(out_path.size() - 4, 4, ".obj") == 0;
  if (obj) {
    std::FILE* f = std::fopen(tmp.c_str(), "w");
    if (!f) return 1;
    for (Eigen::Index v = 0; v < m.V.rows(); ++v)
      std::fprintf(f, "v %.17g %.17g %.17g\n", m.V(v, 0), m.V(v, 1), m.V(v, 2));
    for (Eigen::Index t = 0; t < m.F.rows(); ++t)
      std::fprintf(f, "f %d %d %d\n", m.F(t, 0) + 1, m.F(t, 1) + 1, m.F(t, 2) + 1);
    if (std::fclose(f) != 0) {
      std::cerr << "error: " << tmp << ": cannot write\n";
      return 1;
    }
  } else {
    std::ofstream out(tmp, std::ios::binary);
    std::string header(80, ' ');
    header.replace(0, 22, "massprops torus R2 a.5");
    out.write(header.data(), 80);
    const auto count = static_cast<std::uint32_t>(m.F.rows());
    out.write(reinterpret_cast<const char*>(&count), 4);
    std::vector<char> rec(50, 0);
    for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
      float c[12] = {};
      for (int k = 0; k < 3; ++k) {
        for (int j = 0; j < 3; ++j) c[3 + 3 * k + j] = static_cast<float>(m.V(m.F(f, k), j));
      }
      std::copy(reinterpret_cast<const char*>(c), reinterpret_cast<const char*>(c) + 48, rec.begin());
      out.write(rec.data(), 50);
    }
    if (!out) {
      std::cerr << "error: " << tmp << ": cannot write\n";
      return 1;
    }
  }
  if (std::rename(tmp.c_str(), out_path.c_str()) != 0) return 1;
  std::cout << m.F.rows() << "\n";
  return 0;
}
