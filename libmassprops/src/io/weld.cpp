#include "weld.h"

namespace massprops {

// Welds corners given one by one (xyz per corner) into shared vertices by bit-identical position,
// with faces given by their corner counts. Used by the STL readers and the assimp path.
LoadedMesh WeldCorners(const std::string& path, const std::vector<double>& xyz,
                       const std::vector<int>& face_sizes, const char* format) {
  return weld::Weld(path, xyz.size() / 3, [&xyz](std::size_t c) { return weld::PositionKey{xyz[3 * c], xyz[3 * c + 1], xyz[3 * c + 2]}; },
              face_sizes, format);
}

}  // namespace massprops
