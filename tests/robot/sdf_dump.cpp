// Prints what SDFormat (libsdformat, the parser of Gazebo) reads from each link's <inertial>:
// "name mass cx cy cz ixx iyy izz ixy ixz iyz valid", valid being gz-math's own check of the
// inertia (positive moments, triangle inequality). Loading fails on any SDFormat error. A real
// consumer for the tests of `massprops fill`.
#include <cstdio>

#include <sdf/sdf.hh>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: sdf_dump FILE.sdf\n");
    return 2;
  }
  sdf::Root root;
  const sdf::Errors errors = root.Load(argv[1]);
  if (!errors.empty()) {
    for (const sdf::Error& e : errors) std::fprintf(stderr, "sdformat: %s\n", e.Message().c_str());
    return 1;
  }
  const sdf::Model* model = root.Model();
  if (model == nullptr) {
    std::fprintf(stderr, "sdformat: no model in %s\n", argv[1]);
    return 1;
  }
  for (uint64_t i = 0; i < model->LinkCount(); ++i) {
    const sdf::Link* link = model->LinkByIndex(i);
    const ignition::math::Inertiald& in = link->Inertial();
    const ignition::math::MassMatrix3d& m = in.MassMatrix();
    const ignition::math::Pose3d& pose = in.Pose();
    if (pose.Rot() != ignition::math::Quaterniond::Identity) {
      std::fprintf(stderr, "%s: the inertial frame is rotated; this dump expects 0 0 0\n", link->Name().c_str());
      return 1;
    }
    std::printf("%s %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %d\n", link->Name().c_str(), m.Mass(),
                pose.Pos().X(), pose.Pos().Y(), pose.Pos().Z(), m.Ixx(), m.Iyy(), m.Izz(), m.Ixy(), m.Ixz(), m.Iyz(),
                in.MassMatrix().IsValid() ? 1 : 0);
  }
  return 0;
}
