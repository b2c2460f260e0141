// How far MuJoCo 2.2's own mesh inertia is from the exact one: each mesh of data/ (and a
// tessellated sphere) as the one geom of a body at 1000 kg/m^3, compiled by mj_loadXML with its
// defaults (the inertia MuJoCo uses when an MJCF has no <inertial>), against massprops'
// LoadSolid. Why `massprops fill` exists. A comparison tool, not a test: MuJoCo is never a
// dependency of the libraries.
//
//   build/bench/mujoco_inertia [DATA_DIR]

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

#include "massprops/io/load.h"
#include "massprops/primitive.h"

namespace {

std::string WriteModel(const std::string& dir, const std::string& mesh) {
  const std::string path = dir + "/model.xml";
  std::ofstream(path) << "<mujoco><asset><mesh name=\"m\" file=\"" << mesh
                      << "\"/></asset><worldbody><body name=\"b\"><freejoint/>"
                         "<geom type=\"mesh\" mesh=\"m\" density=\"1000\"/></body></worldbody></mujoco>\n";
  return path;
}

std::string WriteSphere(const std::string& dir) {
  const massprops::TriangleMesh t = massprops::Tessellate(massprops::primitive::Sphere{0.5}, 48);
  const std::string path = dir + "/sphere_r0.5.obj";
  std::ofstream out(path);
  out.precision(17);
  for (Eigen::Index v = 0; v < t.V.rows(); ++v)
    out << "v " << t.V(v, 0) << " " << t.V(v, 1) << " " << t.V(v, 2) << "\n";
  for (Eigen::Index f = 0; f < t.F.rows(); ++f) {
    out << "f " << t.F(f, 0) + 1 << " " << t.F(f, 1) + 1 << " " << t.F(f, 2) + 1 << "\n";
  }
  return path;
}

double Percent(double a, double b) { return 100 * (a - b) / b; }

}  // namespace

int main(int argc, char** argv) {
  const std::string data = argc > 1 ? argv[1] : MASSPROPS_DATA_DIR;
  const std::string dir = std::filesystem::temp_directory_path() / ("mujoco_inertia_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::vector<std::string> meshes = {data + "/meshes/spot.obj",
                                     data + "/meshes/Moon.stl",
                                     data + "/meshes/t_handle.obj",
                                     data + "/meshes/cube_cup_quad.obj",
                                     data + "/meshes/HalfDonut_binary.stl",
                                     WriteSphere(dir)};
  std::printf("MuJoCo %s's mesh inertia (no <inertial>, density 1000) against the exact values\n", mj_versionString());
  std::printf("%-24s %12s %10s %10s %10s %10s\n", "mesh", "mass (kg)", "mass", "I1", "I2", "I3");
  for (const std::string& mesh : meshes) {
    massprops::LoadOptions o;
    o.unit_stated = true;
    const massprops::SolidResult exact = massprops::LoadSolid(mesh, o);
    char error[1000] = "";
    mjModel* m = mj_loadXML(WriteModel(dir, mesh).c_str(), nullptr, error, sizeof error);
    const std::string name = std::filesystem::path(mesh).filename().string();
    if (m == nullptr) {
      std::string first_line(error);
      first_line = first_line.substr(0, first_line.find('\n'));
      std::printf("%-24s %12.6g  MuJoCo refuses the file: %s\n", name.c_str(), exact.mp.mass, first_line.c_str());
      continue;
    }
    // MuJoCo's principal moments, ascending like ours.
    std::vector<double> I(m->body_inertia + 3, m->body_inertia + 6);
    std::sort(I.begin(), I.end());
    const massprops::Vector3& e = exact.principal.moments;
    std::printf("%-24s %12.6g %+9.2f%% %+9.2f%% %+9.2f%% %+9.2f%%\n", name.c_str(), exact.mp.mass,
                Percent(m->body_mass[1], exact.mp.mass), Percent(I[0], e[0]), Percent(I[1], e[1]), Percent(I[2], e[2]));
    mj_deleteModel(m);
  }
  std::filesystem::remove_all(dir);
  return 0;
}
