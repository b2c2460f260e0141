// The checked path, stage by stage, on a torus of 2·10^6 triangles (MASSPROPS_BENCH_TRIANGLES
// overrides): reading and welding a binary STL, reading an OBJ, the edge analysis, integration, and
// the whole pipeline with --full-check. Read it beside `cat` of the same file (bench/end_to_end.py
// measures that ratio); the stages say where the rest of the time goes.
//
// The OBJ's own stages, the file mapped once outside the clock: BM_ObjFloor (fast_float over every
// number of the file on 2 threads, summed, nothing else: the floor of parsing), BM_ObjParse (our
// parse into vertex and face arrays, and the resolution of the indices), BM_ObjWeld (the
// exact-position weld of the vertex list); BM_ReadObj is all of them with the mapping.

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include <unistd.h>

#include <thread>

#include <fast_float/fast_float.h>

#include "io/io_internal.h"
#include "massprops/io/load.h"
#include "massprops/io/mesh_io.h"
#include "massprops/mass_properties.h"
#include "massprops/mesh_topology.h"
#include "massprops/solids.h"

namespace {

massprops::TriangleMesh Torus() {
  const char* env = std::getenv("MASSPROPS_BENCH_TRIANGLES");
  const long long target = env ? std::atoll(env) : 2000000;
  int n = 3;
  while (4LL * n * n < target) ++n;
  return massprops::solids::Torus(2.0, 0.5, n);
}

std::string TempPath(const char* ext) {
  return (std::filesystem::temp_directory_path() / ("checked_path_bench_" + std::to_string(::getpid()) + "." + ext))
      .string();
}

// A file of this process, removed when it ends (its destructor runs at exit; an atexit handler
// registered while the path's own static was being made ran after that static was destroyed, and
// left every file behind).
struct TempFile {
  std::string path;
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  ~TempFile() {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
  }
};

// The torus as a binary STL and as an OBJ (17 significant digits), written once per process into
// the temporary folder and removed at exit.
const std::string& TorusFile() {
  static const TempFile file{[] {
    const massprops::TriangleMesh m = Torus();
    const std::string p = TempPath("stl");
    std::ofstream out(p, std::ios::binary);
    std::string header(80, ' ');
    out.write(header.data(), 80);
    const auto count = static_cast<std::uint32_t>(m.F.rows());
    out.write(reinterpret_cast<const char*>(&count), 4);
    char rec[50] = {};
    for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
      float c[12] = {};
      for (int k = 0; k < 3; ++k) {
        for (int j = 0; j < 3; ++j) c[3 + 3 * k + j] = static_cast<float>(m.V(m.F(f, k), j));
      }
      std::memcpy(rec, c, 48);
      out.write(rec, 50);
    }
    return p;
  }()};
  return file.path;
}

const std::string& TorusObjFile() {
  static const TempFile file{[] {
    const massprops::TriangleMesh m = Torus();
    const std::string p = TempPath("obj");
    std::FILE* f = std::fopen(p.c_str(), "w");
    for (Eigen::Index v = 0; v < m.V.rows(); ++v)
      std::fprintf(f, "v %.17g %.17g %.17g\n", m.V(v, 0), m.V(v, 1), m.V(v, 2));
    for (Eigen::Index t = 0; t < m.F.rows(); ++t)
      std::fprintf(f, "f %d %d %d\n", m.F(t, 0) + 1, m.F(t, 1) + 1, m.F(t, 2) + 1);
    std::fclose(f);
    return p;
  }()};
  return file.path;
}

void BM_ReadAndWeld(benchmark::State& state) {
  TorusFile();  // written before the clock starts
  for (auto _ : state) benchmark::DoNotOptimize(massprops::ReadMeshFile(TorusFile()));
}

void BM_ReadObj(benchmark::State& state) {
  TorusObjFile();
  for (auto _ : state) benchmark::DoNotOptimize(massprops::ReadMeshFile(TorusObjFile()));
}

// The OBJ file's text, mapped once.
std::string_view ObjText() {
  static const massprops::MappedFile file(TorusObjFile());
  return {reinterpret_cast<const char*>(file.data()), file.size()};
}

// Every number in `text` parsed as a double, summed (the sum keeps the work).
double SumNumbers(std::string_view text) {
  const char* p = text.data();
  const char* const end = p + text.size();
  double sum = 0;
  while (p < end) {
    const char c = *p;
    if ((c >= '0' && c <= '9') || c == '-' || c == '.') {
      double x = 0;
      const auto r = fast_float::from_chars(p, end, x);
      sum += x;
      p = r.ptr == p ? p + 1 : r.ptr;
    } else {
      ++p;
    }
  }
  return sum;
}

void BM_ObjFloor(benchmark::State& state) {
  const std::string_view text = ObjText();
  std::size_t half = text.size() / 2;
  while (half < text.size() && text[half] != '\n') ++half;
  for (auto _ : state) {
    double a = 0, b = 0;
    std::thread other([&] { a = SumNumbers(text.substr(0, half)); });
    b = SumNumbers(text.substr(half));
    other.join();
    benchmark::DoNotOptimize(a + b);
  }
}

void BM_ObjParse(benchmark::State& state) {
  const std::string_view text = ObjText();
  for (auto _ : state) benchmark::DoNotOptimize(massprops::ParseObj("torus.obj", text, 0));
}

void BM_ObjWeld(benchmark::State& state) {
  const massprops::LoadedMesh parsed = massprops::ParseObj("torus.obj", ObjText(), 0);
  for (auto _ : state) {
    state.PauseTiming();
    massprops::PolygonMesh mesh = parsed.mesh;
    state.ResumeTiming();
    benchmark::DoNotOptimize(massprops::MergeCoincidentVertices(mesh));
  }
}

// The edge analysis on state.range(0) threads (0: every core).
void BM_EdgeAnalysis(benchmark::State& state) {
  const massprops::LoadedMesh m = massprops::ReadMeshFile(TorusFile());
  const auto threads = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(massprops::AnalyzeTopology(m.mesh, threads));
}

void BM_Integrate(benchmark::State& state) {
  const massprops::LoadedMesh m = massprops::ReadMeshFile(TorusFile());
  for (auto _ : state) benchmark::DoNotOptimize(massprops::IntegratePolygons(m.mesh));
}

void BM_LoadSolidFullCheck(benchmark::State& state) {
  massprops::LoadOptions o;
  o.full_check = true;
  o.unit_stated = true;
  for (auto _ : state) benchmark::DoNotOptimize(massprops::LoadSolid(TorusFile(), o));
}

}  // namespace

BENCHMARK(BM_ReadAndWeld)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ReadObj)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ObjFloor)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ObjParse)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ObjWeld)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EdgeAnalysis)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Integrate)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LoadSolidFullCheck)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
