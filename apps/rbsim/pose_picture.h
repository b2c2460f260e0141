#pragma once
// A picture of a resting pose, so that a person sees which face is which: an SVG with the part at
// rest on the plane (seen from the side, a little above) beside the part in its file's axes with
// the face it rests on drawn in colour. Flat-shaded orthographic views, drawn back to front.

#include <string>
#include <vector>

#include "dynamics/poses.h"
#include "massprops/mesh.h"

namespace rbsim {

/// `mesh`: the part in its file's coordinates (metres); `face`: the corners of the hull face it
/// rests on, in order, same coordinates. @throws std::runtime_error naming the path.
void WritePosePicture(const std::string& path, const massprops::TriangleMesh& mesh, const dynamics::poses::Pose& pose,
                      const std::vector<massprops::Vector3>& face, const std::string& title);

}  // namespace rbsim
