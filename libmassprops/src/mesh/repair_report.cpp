// The words of a repair report; shared by builds with and without CGAL.

#include <sstream>

#include "massprops/repair/repair.h"

namespace massprops {

std::string RepairReport::Summary() const {
  std::ostringstream s;
  s.precision(7);
  if (welded_vertices) s << "merged " << welded_vertices << " near-coincident vertices; ";
  if (internal_walls) s << "removed " << internal_walls << " faces of internal walls (repeated reversed); ";
  if (removed_faces - internal_walls > 0)
    s << "removed " << removed_faces - internal_walls << " degenerate or repeated faces; ";
  if (reoriented) s << "made face orientations consistent; ";
  if (split_vertices) s << "split " << split_vertices << " non-manifold vertices; ";
  if (stitched_edges) s << "stitched " << stitched_edges << " border edges; ";
  if (filled_holes) {
    s << "filled " << filled_holes << (filled_holes == 1 ? " hole (" : " holes (") << planar_holes
      << " planar, the largest of " << largest_hole << " edges); ";
  }
  if (oriented_to_bound_volume) s << "oriented shells outward and cavities inward; ";
  if (united_shells) s << "united " << united_shells + 1 << " overlapping shells into one; ";
  s << "signed volume " << volume_before << " -> " << volume_after;
  return s.str();
}

}  // namespace massprops
