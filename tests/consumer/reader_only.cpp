// A program that only reads files: it links massprops::io and nothing of CGAL, GMP or MPFR (the
// test around it checks the program's and libmassprops_io's dynamic dependencies). The default
// pipeline runs without them; an option that needs a CGAL step (here --repair) reaches
// massprops::repair beside libmassprops_io, loaded only then.
//   reader_only MESH_DIR   (exit 0 when every number matches its closed form)

#include <cmath>
#include <cstdio>
#include <string>

#include "massprops/io/load.h"

namespace {

int failures = 0;

void Check(const char* what, double got, double want, double rel) {
  const bool ok = std::abs(got - want) <= rel * std::abs(want);
  std::printf("%s %s: %.17g (want %.17g)\n", ok ? "ok  " : "FAIL", what, got, want);
  failures += ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: reader_only MESH_DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  // The T-handle: crossbar 0.08 × 0.02 × 0.02 m over a shaft 0.02 × 0.06 × 0.02 m.
  massprops::LoadOptions options;
  options.unit = massprops::LengthUnit::kMetre;
  options.mass = massprops::Density{1000.0};
  const double volume = 0.08 * 0.02 * 0.02 + 0.02 * 0.06 * 0.02;
  const massprops::SolidResult plain = massprops::LoadSolid(dir + "/t_handle.obj", options);
  Check("t_handle volume", plain.mp.volume, volume, 1e-14);
  Check("t_handle mass", plain.mp.mass, 1000.0 * volume, 1e-14);
  options.repair = true;  // CGAL's step, through the seam
  const massprops::SolidResult repaired = massprops::LoadSolid(dir + "/t_handle.obj", options);
  Check("t_handle volume, repaired", repaired.mp.volume, volume, 1e-14);
  if (!repaired.repair) {
    std::printf("FAIL the repair did not run\n");
    ++failures;
  }
  return failures == 0 ? 0 : 1;
}
