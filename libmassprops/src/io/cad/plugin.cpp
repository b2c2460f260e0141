// The CAD plugin: STEP, IGES and BREP files through OpenCASCADE, loaded with dlopen the first time
// such a file comes (as the assimp plugin is), and run in a child process with a time limit by
// cad_loader.cpp. It and its siblings in io/cad/ are the only translation units that include
// OpenCASCADE.
//
// For each part (a product instance of a STEP or IGES assembly; a BREP file is one part, or one
// per shape of a top-level compound) it finds every solid (solids.cpp), integrates them exactly
// (BRepGProp: volume, center of mass, inertia about it, surface area, with OpenCASCADE's error
// estimate) and meshes them for the check (tessellation.cpp), each prototype once however many
// instances place it. Coordinates are in OpenCASCADE's session unit, millimetres; the message says
// which unit the file declared and how many millimetres it holds, so that the loader converts back.
//
// Message 1, the result (wire.h): format word, the file's unit word ("" when it names none),
// millimetres per file unit (0: unknown), the notes about the file (count, strings), the number of
// parts, then per part: product name, instance name, material name, declared unit word, density (kg/m^3, 0: none),
// solids (count), volume, center of mass (3), inertia about it (9, row-major), error estimate,
// surface area, deflection used, faces left untessellated, edges left unwelded, the fixes (count,
// strings), the file's own properties (flags: 1 volume, 2 centroid, 4 area; volume, centroid (3),
// area), vertices (count, 3 coordinates each), triangles (count, 3 indices each). All placed.
//
// Message 2, the interference: pairs whose boxes overlap, pairs measured, then the overlaps
// (count; per overlap the two part indices and the common volume, -1 when the boolean failed).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRep_Builder.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>

#include "io/cad/occ.h"
#include "io/wire.h"
#include "massprops/parallel.h"

namespace massprops::cad {
namespace {

// The exact integrals of a set of solids, unit density, millimetres.
struct Integrals {
  double volume = 0, error = 0, area = 0;
  gp_Pnt com;
  gp_Mat inertia;
};

Integrals Integrate(const TopoDS_Shape& solids, double tolerance) {
  Integrals i;
  GProp_GProps volume, surface;
  i.error = BRepGProp::VolumeProperties(solids, volume, tolerance, true);
  i.volume = volume.Mass();
  i.com = volume.CentreOfMass();
  i.inertia = volume.MatrixOfInertia();
  BRepGProp::SurfaceProperties(solids, surface);
  i.area = surface.Mass();
  return i;
}

// What a prototype gives once, however many instances use it, in its own frame.
struct Prototype {
  SolidSet set;
  Integrals exact;
  CheckMesh mesh;
  double deflection = 0;
};

Prototype MakePrototype(const TopoDS_Shape& shape, const MasspropsCadOptions& o, double mm_per_unit, bool parallel) {
  Prototype p;
  p.set = FindSolids(shape);
  const TopoDS_Shape& geometry = p.set.count > 0 ? static_cast<const TopoDS_Shape&>(p.set.solids) : p.set.surfaces;
  if (p.set.count == 0 && !p.set.has_surfaces) return p;  // curves or points only
  const double diagonal = Diagonal(geometry);
  const double unit = mm_per_unit > 0 ? mm_per_unit : 1.0;
  p.deflection = o.deflection > 0 ? o.deflection * unit : o.relative_deflection * diagonal;
  if (!(p.deflection > 0)) p.deflection = 1e-3;
  // Triangles grow as 1/deflection on curved faces: below 1e-6 of the part's size they would not
  // fit in memory (nor finish), so such a request is refused rather than attempted.
  if (p.deflection < 1e-6 * diagonal) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "the deflection %.3g is below 1e-6 of the part's diagonal (%.4g): its "
                  "tessellation would not fit in memory; give a larger deflection",
                  p.deflection / unit, diagonal / unit);
    throw Refusal{text};
  }
  // The integral reads the surfaces, the mesher writes triangulations: in parallel they run side
  // by side (OpenCASCADE's B-spline evaluation keeps no cache in the shared geometry).
  ParallelForBlocks(p.set.count > 0 ? 2 : 1, parallel ? 2 : 1, [&](std::int64_t task) {
    if (task == 0) {
      p.mesh = Tessellate(geometry, p.deflection, o.angular_deflection, parallel);
    } else {
      p.exact = Integrate(p.set.solids, o.brep_tolerance);
    }
  });
  return p;
}

// An instance's exact integrals: the prototype's moved rigidly, or (a placement that scales)
// integrated again from the moved solids.
Integrals Placed(const Instance& in, const Prototype& p, const MasspropsCadOptions& o) {
  const gp_Trsf& t = in.placement;
  if (p.set.count == 0) return p.exact;
  if (std::abs(std::abs(t.ScaleFactor()) - 1.0) > 1e-12) {
    return Integrate(p.set.solids.Moved(TopLoc_Location(t)), o.brep_tolerance);
  }
  // Rigid (a mirror included): c' = R c + t, I' = R I Rᵀ.
  Integrals moved = p.exact;
  moved.com = p.exact.com.Transformed(t);
  const gp_Mat r = t.VectorialPart();
  moved.inertia = r * p.exact.inertia * r.Transposed();
  return moved;
}

void WritePart(const Instance& in, const Prototype& p, const MasspropsCadOptions& o, wire::Writer& w) {
  const Integrals exact = Placed(in, p, o);
  w.Str(in.name);
  w.Str(in.instance);
  w.Str(in.material);
  w.Str(in.unit_word);
  w.F64(in.density);
  w.U64(static_cast<std::uint64_t>(p.set.count));
  w.F64(exact.volume);
  for (double x : {exact.com.X(), exact.com.Y(), exact.com.Z()}) w.F64(x);
  for (int r = 1; r <= 3; ++r) {
    for (int c = 1; c <= 3; ++c) w.F64(exact.inertia(r, c));
  }
  w.F64(exact.error);
  w.F64(exact.area);
  w.F64(p.deflection);
  w.U64(p.mesh.untessellated);
  w.U64(p.mesh.unmatched_edges);
  w.U64(p.set.fixes.size());
  for (const std::string& fix : p.set.fixes) w.Str(fix);
  const FileProperties& f = in.file;
  w.U64((f.has_volume ? 1u : 0u) | (f.has_centroid ? 2u : 0u) | (f.has_area ? 4u : 0u));
  const gp_Pnt centroid = f.centroid.Transformed(in.placement);
  const double scale = std::abs(in.placement.ScaleFactor());
  w.F64(f.volume * scale * scale * scale);
  for (double x : {centroid.X(), centroid.Y(), centroid.Z()}) w.F64(x);
  w.F64(f.area * scale * scale);
  // The mesh, placed; a mirroring placement turns the faces inside out: two corners swap back.
  const std::size_t vertices = p.mesh.xyz.size() / 3;
  std::vector<double> placed(p.mesh.xyz.size());
  for (std::size_t v = 0; v < vertices; ++v) {
    gp_Pnt q(p.mesh.xyz[3 * v], p.mesh.xyz[3 * v + 1], p.mesh.xyz[3 * v + 2]);
    q.Transform(in.placement);
    placed[3 * v] = q.X(), placed[3 * v + 1] = q.Y(), placed[3 * v + 2] = q.Z();
  }
  w.U64(vertices);
  w.F64s(placed.data(), placed.size());
  std::vector<std::int32_t> tris = p.mesh.tris;
  if (in.placement.IsNegative()) {
    for (std::size_t k = 0; k + 2 < tris.size(); k += 3) std::swap(tris[k + 1], tris[k + 2]);
  }
  w.U64(tris.size() / 3);
  w.I32s(tris.data(), tris.size());
}

class Sender {
 public:
  Sender(MasspropsCadSendFn send, void* context) : send_(send), context_(context) {}
  void operator()(wire::Writer& w) const { send_(context_, w.bytes().data(), w.bytes().size()); }

 private:
  MasspropsCadSendFn send_;
  void* context_;
};

void Read(const char* path, const MasspropsCadOptions& o, const Sender& send) {
  // OpenCASCADE prints its progress on standard output; the child's output is its pipe only.
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  Document d = ReadDocument(path, o.format);
  if (d.instances.empty()) throw Refusal{"the file holds no shape (no solid, shell or face)"};
  // Each prototype is found, integrated and meshed once, however many instances place it; the
  // prototypes are made in parallel (each shape's with all its locations in one task, since they
  // share faces and so triangulations), each on its own, so the bits do not depend on the order.
  const bool parallel = o.threads != 1;
  std::vector<Prototype> made;
  std::vector<std::size_t> prototype_of;        // per instance
  std::vector<std::vector<std::size_t>> tasks;  // per shape: its prototypes, in order of first use
  {
    std::map<const TopoDS_TShape*, std::size_t> task_of;
    std::vector<std::pair<const Instance*, std::size_t>> first_use;  // per prototype
    for (const Instance& in : d.instances) {
      const auto [t, is_new] = task_of.emplace(in.shape.TShape().get(), tasks.size());
      if (is_new) tasks.emplace_back();
      std::size_t found = first_use.size();
      for (std::size_t k : tasks[t->second]) {
        if (first_use[k].first->shape.Location().IsEqual(in.shape.Location())) found = k;
      }
      if (found == first_use.size()) {
        first_use.emplace_back(&in, t->second);
        tasks[t->second].push_back(found);
      }
      prototype_of.push_back(found);
    }
    made.resize(first_use.size());
    // Tasks in order, the lowest failing one's exception rethrown: the same message every run.
    ParallelForBlocks(static_cast<std::int64_t>(tasks.size()), o.threads, [&](std::int64_t t) {
      for (std::size_t k : tasks[static_cast<std::size_t>(t)]) {
        made[k] = MakePrototype(first_use[k].first->shape, o, d.mm_per_unit, parallel);
      }
    });
  }
  std::vector<const Prototype*> prototypes;
  for (std::size_t k : prototype_of) prototypes.push_back(&made[k]);
  // A file of surfaces only, spread over several parts (a surface model whose faces each came as
  // their own representation): the faces of all parts, placed, as one part, so that sewing can
  // find the solid they bound together; kept only when it does.
  Prototype joined;
  if (d.instances.size() > 1 &&
      std::none_of(prototypes.begin(), prototypes.end(), [](const Prototype* p) { return p->set.count > 0; })) {
    TopoDS_Compound all;
    BRep_Builder builder;
    builder.MakeCompound(all);
    for (const Instance& in : d.instances) builder.Add(all, in.shape.Moved(TopLoc_Location(in.placement)));
    joined = MakePrototype(all, o, d.mm_per_unit, parallel);
    if (joined.set.count > 0) {
      Instance one;
      one.name = d.instances.front().name;
      one.shape = all;
      d.instances = {one};
      prototypes = {&joined};
    }
  }
  // Parts with no face at all (curves, points, an empty product) are left out, and said so.
  std::vector<std::string> notes;
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < d.instances.size(); ++i) {
    const Prototype& p = *prototypes[i];
    if (p.set.count > 0 || p.set.has_surfaces) {
      kept.push_back(i);
    } else {
      const std::string& name = d.instances[i].name;
      notes.push_back((name.empty() ? std::string("a shape") : "part '" + name + "'") +
                      " holds no solid or surface (only curves or points, or nothing): left out");
    }
  }
  if (kept.empty()) {
    throw Refusal{"OpenCASCADE found no solid or surface in it (no faces: only curves or points)"};
  }
  wire::Writer result;
  result.Str(d.format);
  result.Str(d.unit_word);
  result.F64(d.mm_per_unit);
  result.U64(notes.size());
  for (const std::string& note : notes) result.Str(note);
  result.U64(kept.size());
  for (std::size_t i : kept) WritePart(d.instances[i], *prototypes[i], o, result);
  send(result);
  // Interference, after the result is safe with the loader.
  std::vector<PlacedSolid> solids;
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const Instance& in = d.instances[kept[k]];
    std::size_t s = 0;
    for (TopExp_Explorer e(prototypes[kept[k]]->set.solids, TopAbs_SOLID); e.More(); e.Next(), ++s) {
      const double scale = std::abs(in.placement.ScaleFactor());
      solids.push_back({k, e.Current().Moved(TopLoc_Location(in.placement)),
                        prototypes[kept[k]]->set.volumes[s] * scale * scale * scale});
    }
  }
  const Interference found = MeasureInterference(solids, o.interference_pairs);
  wire::Writer report;
  report.U64(found.candidates);
  report.U64(found.measured);
  report.U64(found.overlaps.size());
  for (const Overlap& overlap : found.overlaps) {
    report.U64(overlap.a);
    report.U64(overlap.b);
    report.F64(overlap.volume);
  }
  send(report);
}

void Refuse(const std::string& message, const Sender& send) {
  wire::Writer w;
  w.Str(message);
  send(w);
}

}  // namespace
}  // namespace massprops::cad

extern "C" {

__attribute__((visibility("default"))) int massprops_cad_read(const char* path, const MasspropsCadOptions* options,
                                                              MasspropsCadSendFn send, void* context) {
  using massprops::cad::Refuse;
  const massprops::cad::Sender sender(send, context);
  if (options == nullptr || options->abi != MASSPROPS_CAD_ABI) {
    Refuse("the CAD plugin does not match this massprops (a mismatched build?)", sender);
    return 1;
  }
  try {
    massprops::cad::Read(path, *options, sender);
    return 0;
  } catch (const massprops::cad::Refusal& e) {
    Refuse(e.message, sender);
  } catch (const Standard_Failure& e) {
    Refuse(std::string("OpenCASCADE failed while reading it: ") +
               (e.GetMessageString() && *e.GetMessageString() ? e.GetMessageString() : e.DynamicType()->Name()),
           sender);
  } catch (const std::exception& e) {
    Refuse(std::string("reading it failed: ") + e.what(), sender);
  }
  return 1;
}

}  // extern "C"
