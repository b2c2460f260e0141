// libFuzzer target for the robot readers (URDF, SDFormat, MJCF): the bytes as a robot file,
// written to a temporary file (the readers take paths and resolve meshes and includes beside
// them), read, added to a world with a ground (from its first keyframe, when it has one) and
// stepped a few times. Any crash, sanitizer report or hang is a bug; a std::exception (the
// readers' and AddRobot's messages, naming the element) is the expected answer to bad input.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include <unistd.h>

#include "bodies/robot.h"
#include "dynamics/contact.h"
#include "massprops/robot/robot_model.h"

// The input's file, removed when the process ends (its destructor runs at exit).
struct InputFile {
  std::string path =
      (std::filesystem::temp_directory_path() / ("robot_fuzz_" + std::to_string(::getpid()) + ".xml")).string();
  ~InputFile() {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
  }
};

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const InputFile file;
  const std::string& path = file.path;
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    const massprops::RobotModel model = massprops::ReadRobotModel(path);
    if (model.links.size() > 64) return 0;  // (a long chain's O(n³) steps: not what this looks for)
    dynamics::World w(dynamics::Integrator::kImplicitMidpoint);
    w.AddForce(dynamics::Gravity(massprops::Vector3(0, 0, -9.81)));
    dynamics::ContactWorld world(std::move(w));
    world.AddGround({});
    dynamics::RobotOptions options;
    if (!model.keyframes.empty()) options.keyframe = model.keyframes.front().name;
    dynamics::AddRobot(world, model, options);
    for (int i = 0; i < 10; ++i) {
      if (!world.Step(1e-3).ok) break;
    }
  } catch (const std::exception&) {
  }
  return 0;
}
