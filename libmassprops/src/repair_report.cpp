// The words of a repair report; shared by builds with and without CGAL.

#include <sstream>

#include "massprops/repair.h"

namespace massprops {

std::string RepairReport::Summary() const {
  std::ostringstream s;
  s.precision(7);
  if (welded_vertices) s << "merged " << welded_vertices << " near-coincident vertices; ";
  if (removed_faces) s << "removed " << removed_faces << " degenerate or duplicate faces; ";
  if (reoriented) s << "made face orientations consistent; ";
  if (split_vertices) s << "split " << split_vertices << " non-manifold vertices; ";
  if (stitched_edges) s << "stitched " << stitched_edges << " border edges; ";
  if (oriented_to_bound_volume) s << "oriented shells outward and cavities inward; ";
  if (united_shells) s << "united " << united_shells + 1 << " overlapping shells into one; ";
  s << "signed volume " << volume_before << " -> " << volume_after;
  return s.str();
}

}  // namespace massprops
