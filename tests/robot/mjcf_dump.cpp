// Prints what MuJoCo compiles from an MJCF file for each body: "name mass cx cy cz ixx iyy izz
// ixy ixz iyz" with the tensor rebuilt from body_inertia and body_iquat, in the body frame about
// the center of mass. mj_loadXML fails on anything MuJoCo refuses (an inertia that breaks the
// triangle inequality, a missing mesh, ...). A real consumer for the tests of `massprops fill`.
#include <cstdio>

#include <mujoco/mujoco.h>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: mjcf_dump FILE.xml\n");
    return 2;
  }
  char error[1000] = "";
  mjModel* m = mj_loadXML(argv[1], nullptr, error, sizeof error);
  if (m == nullptr) {
    std::fprintf(stderr, "mujoco: %s\n", error);
    return 1;
  }
  for (int b = 1; b < m->nbody; ++b) {
    mjtNum r[9];
    mju_quat2Mat(r, m->body_iquat + 4 * b);
    const mjtNum* d = m->body_inertia + 3 * b;
    mjtNum I[9];  // R diag(d) R^T
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        I[3 * i + j] =
            r[3 * i] * d[0] * r[3 * j] + r[3 * i + 1] * d[1] * r[3 * j + 1] + r[3 * i + 2] * d[2] * r[3 * j + 2];
      }
    }
    const mjtNum* c = m->body_ipos + 3 * b;
    std::printf("%s %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", mj_id2name(m, mjOBJ_BODY, b),
                m->body_mass[b], c[0], c[1], c[2], I[0], I[4], I[8], I[1], I[2], I[5]);
  }
  mj_deleteModel(m);
  return 0;
}
