// The threads a caller allows are the threads the load uses: an OBJ parsed, its vertices welded
// and the mesh solved with num_threads = 1 start no thread (a Dask or multiprocessing worker asks
// for one and must get one); with 2 they do start some. Linux: the process's threads are counted
// in /proc/self/task by a watcher while the work runs.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <sstream>
#include <string>
#include <thread>

#include "massprops/io/load.h"
#include "massprops/io/mesh_io.h"
#include "massprops/solids.h"

namespace massprops {
namespace {

int ThreadsNow() {
  int n = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator("/proc/self/task")) ++n;
  return n;
}

// The most threads the process had while `work` ran, the watcher's own included.
int MostThreadsDuring(const std::function<void()>& work) {
  std::atomic<bool> done{false};
  std::atomic<int> most{0};
  std::thread watcher([&] {
    while (!done.load()) {
      most = std::max(most.load(), ThreadsNow());
      std::this_thread::sleep_for(std::chrono::microseconds(50));
    }
  });
  work();
  done = true;
  watcher.join();
  return most.load();
}

// A torus of 2·10⁵ triangles as OBJ text with 17-digit coordinates (~8 MB: the parser's chunks
// are 4 MB, so it has work for two threads, and so has the weld of its 10⁵ vertices).
std::string TorusObj() {
  const TriangleMesh t = solids::Torus(2.0, 0.5, 316);
  std::string text;
  char line[128];
  for (Eigen::Index v = 0; v < t.V.rows(); ++v) {
    std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", t.V(v, 0), t.V(v, 1), t.V(v, 2));
    text += line;
  }
  for (Eigen::Index f = 0; f < t.F.rows(); ++f) {
    std::snprintf(line, sizeof line, "f %d %d %d\n", t.F(f, 0) + 1, t.F(f, 1) + 1, t.F(f, 2) + 1);
    text += line;
  }
  return text;
}

TEST(ThreadLimit, OneThreadAskedOneThreadUsed) {
  const std::string text = TorusObj();
  ASSERT_GT(text.size(), std::size_t{8} << 20);
  const int before = ThreadsNow();
  LoadOptions one;
  one.num_threads = 1;
  LoadedMesh parsed;
  // The caller's thread and the watcher: nothing else.
  EXPECT_EQ(MostThreadsDuring([&] { parsed = ParseMeshBuffer("torus.obj", "obj", text, 1); }), before + 1);
  EXPECT_EQ(parsed.mesh.num_faces(), 2 * 632 * 316);
  SolidResult solved;
  EXPECT_EQ(MostThreadsDuring([&] { solved = SolveMesh(parsed, "torus", one); }), before + 1);
  EXPECT_NEAR(solved.mp.volume, 2 * M_PI * M_PI * 2.0 * 0.25, 0.01);
  // The control: with two allowed, the same work does start threads, and the watcher sees them
  // (a few tries: on a loaded machine the watcher may not run while a short phase lasts).
  int most = 0;
  for (int attempt = 0; attempt < 5 && most <= before + 1; ++attempt) {
    most = MostThreadsDuring([&] { parsed = ParseMeshBuffer("torus.obj", "obj", text, 2); });
  }
  EXPECT_GT(most, before + 1);
}

}  // namespace
}  // namespace massprops
