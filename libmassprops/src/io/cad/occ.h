#pragma once
// What the CAD plugin's translation units share (OpenCASCADE types included): a file read into
// instances, each instance's solids found, a check mesh made, and solids tested for interference.

#include <cstdint>
#include <string>
#include <vector>

#include <TopoDS_Compound.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Pnt.hxx>
#include <gp_Trsf.hxx>

#include "io/cad/plugin_abi.h"

namespace massprops::cad {

/// A request the plugin refuses, with the message as the user should read it.
struct Refusal {
  std::string message;
};

/// What the exporting system wrote about a product (STEP's geometric validation properties), in
/// millimetres and the product's own frame.
struct FileProperties {
  bool has_volume = false, has_centroid = false, has_area = false;
  double volume = 0, area = 0;
  gp_Pnt centroid;
};

/// A part as the assembly places it: its prototype shape (without the placement) and where it goes.
struct Instance {
  std::string name;      ///< the product's name
  std::string instance;  ///< the assembly component's own label ("" when it has none or is the product)
  std::string material;
  /// The length unit the product's own representation declares, as the file names it ("INCH");
  /// "" when not known. OpenCASCADE has converted its coordinates to millimetres already.
  std::string unit_word;
  double density = 0;  // kg/m^3
  TopoDS_Shape shape;
  gp_Trsf placement;
  FileProperties file;
};

/// What a file gave: its parts, and the unit it declares.
struct Document {
  std::string format;      ///< "STEP", "IGES", "BREP"
  std::string unit_word;   ///< as the file names it; "" when it names none
  double mm_per_unit = 0;  ///< 0: unknown (the coordinates stay in millimetres)
  std::vector<Instance> instances;
};

Document ReadDocument(const char* path, int format);

/// Every solid of a shape: solids as they are (turned outward when inside out), closed shells
/// without a solid made solids, loose faces sewn first. Each such fix is said in `fixes`.
struct SolidSet {
  TopoDS_Compound solids;
  int count = 0;
  std::vector<double> volumes;  ///< each solid's, mm^3 (positive), in the order of `solids`
  /// Faces left outside every solid (open surfaces): the part's geometry when it has no solid.
  TopoDS_Compound surfaces;
  bool has_surfaces = false;
  std::vector<std::string> fixes;
};

SolidSet FindSolids(const TopoDS_Shape& shape);

/// The diagonal of a shape's bounding box, mm (0 for an empty shape).
double Diagonal(const TopoDS_Shape& shape);

/// A tessellation welded through the B-rep's shared edges: nodes on one edge of two faces are one
/// vertex, whatever rounding their faces' locations gave them.
struct CheckMesh {
  std::vector<double> xyz;            ///< 3 per vertex, millimetres, the prototype's frame
  std::vector<std::int32_t> tris;     ///< 3 per triangle, outward
  std::uint64_t untessellated = 0;    ///< faces BRepMesh left without triangles
  std::uint64_t unmatched_edges = 0;  ///< edges whose two sides were meshed differently (not welded)
};

/// Meshes `shape` at `deflection` (mm). In parallel, BRepMesh discretizes each edge and then each
/// face on its own, so the triangles are the same for any thread count.
CheckMesh Tessellate(const TopoDS_Shape& shape, double deflection, double angular_deflection, bool parallel);

/// Two solids that share volume: the instances (or, a == b, two solids inside one instance) and
/// the common volume, mm^3.
struct Overlap {
  std::uint64_t a = 0, b = 0;
  double volume = 0;
};

struct Interference {
  std::uint64_t candidates = 0;  ///< pairs whose boxes overlap
  std::uint64_t measured = 0;    ///< of them, pairs whose common volume was computed
  std::vector<Overlap> overlaps;
};

/// A solid placed for the interference test: which instance it belongs to.
struct PlacedSolid {
  std::uint64_t instance = 0;
  TopoDS_Shape solid;  ///< placed
  double volume = 0;   ///< mm^3
};

/// The exact common volume of the pairs whose boxes overlap, the first `budget` of them in the
/// order of the instances. Touching solids (a bolt in a hole of its radius) share no volume.
Interference MeasureInterference(const std::vector<PlacedSolid>& solids, int budget);

}  // namespace massprops::cad
