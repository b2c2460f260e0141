// Prints what urdfdom (the parser behind ROS's robot_state_publisher and check_urdf) reads from
// each link's <inertial>: "name mass cx cy cz ixx iyy izz ixy ixz iyz", in the link frame with
// the tensor about the center of mass (rotated by the inertial's rpy). A real consumer for the
// tests of `massprops fill`.
#include <cstdio>

#include <urdf_parser/urdf_parser.h>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: urdf_dump FILE.urdf\n");
    return 2;
  }
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDFFile(argv[1]);
  if (!model) {
    std::fprintf(stderr, "urdfdom could not parse %s\n", argv[1]);
    return 1;
  }
  for (const auto& [name, link] : model->links_) {
    if (!link->inertial) continue;
    const urdf::Inertial& in = *link->inertial;
    double x, y, z, w;
    in.origin.rotation.getQuaternion(x, y, z, w);
    if (x != 0 || y != 0 || z != 0) {
      std::fprintf(stderr, "%s: the inertial frame is rotated; this dump expects rpy 0 0 0\n", name.c_str());
      return 1;
    }
    const urdf::Vector3& c = in.origin.position;
    std::printf("%s %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", name.c_str(), in.mass, c.x, c.y,
                c.z, in.ixx, in.iyy, in.izz, in.ixy, in.ixz, in.iyz);
  }
  return 0;
}
