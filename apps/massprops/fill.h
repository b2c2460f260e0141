#pragma once
// `massprops fill ROBOT -o OUT`: a URDF, SDFormat or MJCF file with every link's inertial
// computed from its geometries (massprops/robot.h computes; this parses, reports and writes).

namespace massprops::cli {

int FillMain(int argc, char** argv);

}  // namespace massprops::cli
