// Signed-distance grid files (format in implicit.h and the README).

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "massprops/io/mesh_io.h"

namespace massprops {

ImplicitPtr ReadSdfGridFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw std::runtime_error(
        path + (std::filesystem::exists(path, ec) ? ": not a regular file" : ": cannot open the grid file"));
  }
  const auto bytes = std::filesystem::file_size(path, ec);
  std::ifstream in(path);
  if (!in || ec) throw std::runtime_error(path + ": cannot open the grid file");
  std::string magic;
  int version = 0;
  in >> magic >> version;
  if (magic != "sdfgrid" || version != 1)
    throw std::runtime_error(path + ": not an sdfgrid 1 file (first line must be 'sdfgrid 1')");
  Eigen::Vector3i n;
  Vector3 origin, h;
  if (!(in >> n.x() >> n.y() >> n.z())) throw std::runtime_error(path + ": expected the sample counts NX NY NZ");
  if ((n.array() < 2).any() || (n.cast<double>().prod() > 1e9))
    throw std::runtime_error(path + ": sample counts must be 2 or more (and at most 10^9 in all)");
  if (!(in >> origin.x() >> origin.y() >> origin.z()))
    throw std::runtime_error(path + ": expected the origin X0 Y0 Z0");
  if (!(in >> h.x() >> h.y() >> h.z())) throw std::runtime_error(path + ": expected the spacing HX HY HZ");
  const auto count =
      static_cast<std::size_t>(n.x()) * static_cast<std::size_t>(n.y()) * static_cast<std::size_t>(n.z());
  // Every value takes at least two bytes of text: a header that promises more than the file can
  // hold is refused before anything is allocated for it.
  if (count > bytes / 2) {
    throw std::runtime_error(path + ": the header promises " + std::to_string(count) + " values, more than the file (" +
                             std::to_string(bytes) + " bytes) can hold");
  }
  std::vector<Scalar> v(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (!(in >> v[i]))
      throw std::runtime_error(path + ": expected " + std::to_string(count) + " values, found " + std::to_string(i));
  }
  try {
    return implicit::SdfGrid(n, origin, h, std::move(v), "grid(file=\"" + path + "\")");
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace massprops
