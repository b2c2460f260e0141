// massprops: mass properties of the solids that mesh files bound.
//
//   massprops FILE... [--density D] [--path auto|triangles|polygons] [--format table|json]
//                     [--threads N] [--allow-open]
//
// Errors are one line on stderr naming the file and the fault; the exit status is 1 when any
// file failed, 2 for bad arguments.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "massprops/io.h"
#include "massprops/mass_properties.h"
#include "massprops/mesh_topology.h"
#include "massprops/principal_axes.h"

namespace {

using massprops::Matrix3;
using massprops::Vector3;

struct Report {
  std::string file;
  massprops::LoadedMesh loaded;
  massprops::MeshTopology topology;
  massprops::MassProperties mp;
  massprops::PrincipalInertia principal;
  massprops::ValidityReport validity;
  std::string path_used;
  double seconds = 0;
};

struct Options {
  std::vector<std::string> files;
  double density = 1000.0;
  std::string path = "auto";
  std::string format = "table";
  int threads = 0;
  bool allow_open = false;
};

Report Compute(const std::string& file, const Options& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  Report r;
  r.file = file;
  r.loaded = massprops::ReadMeshFile(file);
  r.topology = massprops::AnalyzeTopology(r.loaded.mesh);
  if (!r.topology.BoundsVolume()) {
    if (!opt.allow_open) {
      throw massprops::MeshFileError(
          file + ": " + r.topology.Problems() +
          ". The mesh does not bound a solid, so its mass properties are not defined; repair it "
          "(close the holes, orient the faces consistently) or pass --allow-open to compute "
          "anyway");
    }
    std::cerr << "warning: " << file << ": " << r.topology.Problems()
              << "; the results below depend on the reference point and are not trustworthy\n";
  }
  massprops::IntegrationOptions io;
  io.num_threads = opt.threads;
  const bool triangles = massprops::IsAllTriangles(r.loaded.mesh);
  if (opt.path == "polygons" || (opt.path == "auto" && !triangles)) {
    r.path_used = "polygons (Mirtich)";
    r.mp = massprops::ComputeMassProperties(r.loaded.mesh, opt.density, io);
  } else {
    r.path_used = triangles ? "triangles (signed tetrahedra)"
                            : "triangles (signed tetrahedra, polygons split into fans)";
    r.mp = massprops::ComputeMassProperties(massprops::Triangulate(r.loaded.mesh), opt.density, io);
  }
  if (r.mp.volume < 0) {
    throw massprops::MeshFileError(
        file + ": the signed volume is negative (" + std::to_string(r.mp.volume) +
        " m^3): the faces point inward. Reverse the face orientation of the mesh");
  }
  r.principal = massprops::ComputePrincipalInertia(r.mp.inertia_com);
  r.validity = massprops::CheckPhysicallyValid(r.principal.moments);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

std::string Num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "% .10e", v);
  return buf;
}

void PrintMatrix(std::ostream& out, const std::string& indent, const Matrix3& m) {
  for (int i = 0; i < 3; ++i) {
    out << indent << "[" << Num(m(i, 0)) << "  " << Num(m(i, 1)) << "  " << Num(m(i, 2)) << " ]\n";
  }
}

void PrintTable(std::ostream& out, const Report& r) {
  const auto& t = r.topology;
  out << "file            " << r.file << "  (" << r.loaded.format << ", " << t.faces << " faces, "
      << t.vertices << " vertices, " << t.components << " component"
      << (t.components == 1 ? "" : "s") << ", "
      << (t.BoundsVolume() ? "closed and consistently oriented" : t.Problems()) << ")\n";
  if (r.loaded.float32_coordinates) {
    out << "precision       the file's coordinates are 32-bit floats (~7 significant digits)\n";
  }
  out << "units           coordinates taken as metres; density " << r.mp.density << " kg/m^3\n";
  out << "integration     " << r.path_used << ", " << r.seconds << " s\n";
  out << "volume          " << Num(r.mp.volume) << " m^3\n";
  out << "surface area    " << Num(r.mp.surface_area) << " m^2\n";
  out << "mass            " << Num(r.mp.mass) << " kg\n";
  const Vector3& c = r.mp.center_of_mass;
  out << "center of mass  [" << Num(c[0]) << "  " << Num(c[1]) << "  " << Num(c[2])
      << " ] m, in the file's axes\n";
  out << "inertia about the center of mass, file's axes (kg m^2):\n";
  PrintMatrix(out, "                ", r.mp.inertia_com);
  out << "                convention: I = integral of rho (|r|^2 E - r r^T) dV; off-diagonal\n"
         "                entries are the NEGATED products of inertia (Ixy = -integral rho x y dV),\n"
         "                as URDF ixy/ixz/iyz and MJCF fullinertia expect them\n";
  const Vector3& m = r.principal.moments;
  out << "principal moments (ascending)  " << Num(m[0]) << "  " << Num(m[1]) << "  " << Num(m[2])
      << " kg m^2\n";
  out << "principal axes (columns, right-handed, in the file's axes):\n";
  PrintMatrix(out, "                ", r.principal.axes);
  out << "physically valid  "
      << (r.validity.valid ? "yes (moments positive, I1 + I2 >= I3)" : "NO: " + r.validity.reason)
      << "\n";
}

nlohmann::ordered_json ToJson(const Report& r) {
  auto mat = [](const Matrix3& m) {
    return nlohmann::ordered_json::array({{m(0, 0), m(0, 1), m(0, 2)},
                                  {m(1, 0), m(1, 1), m(1, 2)},
                                  {m(2, 0), m(2, 1), m(2, 2)}});
  };
  const auto& c = r.mp.center_of_mass;
  const auto& m = r.principal.moments;
  const auto& t = r.topology;
  return {{"file", r.file},
          {"volume", r.mp.volume},
          {"mass", r.mp.mass},
          {"density", r.mp.density},
          {"center_of_mass", {c[0], c[1], c[2]}},
          {"inertia_com", mat(r.mp.inertia_com)},
          {"principal_moments", {m[0], m[1], m[2]}},
          {"principal_axes", mat(r.principal.axes)},
          {"surface_area", r.mp.surface_area},
          {"physically_valid", r.validity.valid},
          {"mesh",
           {{"format", r.loaded.format},
            {"faces", t.faces},
            {"vertices", t.vertices},
            {"components", t.components},
            {"closed", t.boundary_edges == 0},
            {"oriented", t.inconsistent_edges == 0},
            {"boundary_edges", t.boundary_edges},
            {"non_manifold_edges", t.non_manifold_edges},
            {"float32_coordinates", r.loaded.float32_coordinates}}}};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"massprops: exact mass properties of the solids that mesh files bound"};
  Options opt;
  app.add_option("files", opt.files, "Mesh files (.obj, .stl), coordinates in metres")
      ->required();
  app.add_option("--density", opt.density, "Uniform density in kg/m^3")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--path", opt.path, "Integration path: auto (triangles, or Mirtich for n-gons), "
                                     "triangles, polygons")
      ->check(CLI::IsMember({"auto", "triangles", "polygons"}))
      ->capture_default_str();
  app.add_option("--format", opt.format, "Output format")
      ->check(CLI::IsMember({"table", "json"}))
      ->capture_default_str();
  app.add_option("--threads", opt.threads, "Worker threads (0 = all cores); results are the same bits")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--allow-open", opt.allow_open,
               "Compute even when the mesh is open or inconsistently oriented (with a warning)");
  CLI11_PARSE(app, argc, argv);
  if (!std::isfinite(opt.density)) {
    std::cerr << "error: --density must be finite\n";
    return 2;
  }

  int failures = 0;
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  std::ostringstream out;
  for (const auto& file : opt.files) {
    try {
      Report r = Compute(file, opt);
      if (opt.format == "json") {
        all.push_back(ToJson(r));
      } else {
        if (out.tellp() > 0) out << "\n";
        PrintTable(out, r);
      }
    } catch (const std::exception& e) {
      ++failures;
      std::cerr << "error: " << e.what() << "\n";
    }
  }
  if (opt.format == "json") {
    if (!all.empty()) std::cout << (all.size() == 1 ? all[0] : all).dump(2) << "\n";
  } else {
    std::cout << out.str();
  }
  return failures > 0 ? 1 : 0;
}
