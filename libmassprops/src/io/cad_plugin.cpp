// The CAD plugin: STEP, IGES and BREP files through OpenCASCADE, loaded with dlopen the first time
// such a file comes (as the assimp plugin is), and run in a child process with a time limit by
// cad_loader.cpp. The only translation unit that includes OpenCASCADE.
//
// For each part (a product instance of a STEP or IGES assembly; a BREP file is one part) it sends
// the triangles of a BRepMesh tessellation with the instance's placement applied, and the exact
// B-rep's volume, center of mass and inertia about it (BRepGProp, unit density) with
// OpenCASCADE's error estimate. Coordinates are in OpenCASCADE's session unit, millimetres: the
// readers convert the file's unit to it, and the result says which unit the file declared and how
// many millimetres it holds, so that the loader converts back explicitly.
//
// Result layout (wire.h): format word, the file's unit word ("" when it names none), millimetres
// per file unit (0: unknown), the number of parts, then per part: name, material name, density
// (kg/m^3, 0: none), solid (0/1), volume, center of mass (3), inertia about it (9, row-major),
// error estimate, deflection used, faces left untessellated, triangle count, and 9 coordinates
// per triangle.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <IGESCAFControl_Reader.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESModel.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <Poly_Triangulation.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TDataStd_Name.hxx>
#include <TDataStd_TreeNode.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_Material.hxx>
#include <XCAFDoc_MaterialTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>

#include "cad_plugin.h"
#include "wire.h"

namespace {

// A request the plugin refuses, with the message as the user should read it.
struct Refusal {
  std::string message;
};

// A part as the assembly places it: its prototype shape (without the placement) and where it goes.
struct Instance {
  std::string name;
  std::string material;
  double density = 0;  // kg/m^3
  TopoDS_Shape shape;
  gp_Trsf placement;
};

// What a prototype gives once, however many instances use it: triangles and B-rep integrals in
// the prototype's own frame.
struct Prototype {
  std::vector<double> corners;      // 9 per triangle
  std::uint64_t untessellated = 0;  // faces BRepMesh left without triangles
  bool solid = false;
  double volume = 0, error = 0, deflection = 0;
  gp_Pnt com;
  gp_Mat inertia;
};

std::string NameOf(const TDF_Label& label) {
  Handle(TDataStd_Name) name;
  if (!label.FindAttribute(TDataStd_Name::GetID(), name)) return "";
  return TCollection_AsciiString(name->Get()).ToCString();
}

// Millimetres in one of the file's units, from the word the STEP reader reports (SI units with
// their prefix, or a conversion-based unit's name); 0 when unknown.
double MillimetresPerStepUnit(std::string word) {
  for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  static const std::map<std::string, double> units = {
      {"millimetre", 1}, {"millimeter", 1},  {"mm", 1},          {"metre", 1000},      {"meter", 1000},
      {"m", 1000},       {"centimetre", 10}, {"centimeter", 10}, {"cm", 10},           {"inch", 25.4},
      {"in", 25.4},      {"foot", 304.8},    {"ft", 304.8},      {"micrometre", 1e-3}, {"micrometer", 1e-3},
      {"micron", 1e-3},  {"kilometre", 1e6}, {"kilometer", 1e6}, {"decimetre", 100},   {"decimeter", 100},
      {"mil", 0.0254},   {"mile", 1609344},
  };
  const auto it = units.find(word);
  return it == units.end() ? 0 : it->second;
}

// IGES's global section unit flag (IGES 5.3, section 2.2.4.3).
void IgesUnit(int flag, std::string& word, double& mm) {
  struct Unit {
    int flag;
    const char* word;
    double mm;
  };
  static const Unit units[] = {{1, "inch", 25.4},         {2, "millimetre", 1},    {4, "foot", 304.8},
                               {5, "mile", 1609344},      {6, "metre", 1000},      {7, "kilometre", 1e6},
                               {8, "mil", 0.0254},        {9, "micrometre", 1e-3}, {10, "centimetre", 10},
                               {11, "microinch", 2.54e-5}};
  for (const Unit& u : units) {
    if (u.flag == flag) {
      word = u.word;
      mm = u.mm;
      return;
    }
  }
}

// Depth-first over an XCAF assembly: every simple shape reached is an instance, with the product
// of the placements on the way.
void Collect(const Handle(XCAFDoc_ShapeTool) & shapes, const TDF_Label& label, const gp_Trsf& placement,
             std::vector<Instance>& out, int depth) {
  if (depth > 64) throw Standard_Failure("the assembly is nested more than 64 levels deep (a cycle?)");
  if (XCAFDoc_ShapeTool::IsAssembly(label)) {
    TDF_LabelSequence components;
    XCAFDoc_ShapeTool::GetComponents(label, components);
    for (Standard_Integer i = 1; i <= components.Length(); ++i) {
      TDF_Label referred;
      if (!XCAFDoc_ShapeTool::GetReferredShape(components(i), referred)) continue;
      const gp_Trsf local = XCAFDoc_ShapeTool::GetLocation(components(i)).Transformation();
      Collect(shapes, referred, placement * local, out, depth + 1);
    }
    return;
  }
  Instance in;
  in.name = NameOf(label);
  TopoDS_Shape shape = XCAFDoc_ShapeTool::GetShape(label);
  // A free shape may carry its own location: it is part of the placement, not of the prototype.
  const gp_Trsf own = shape.Location().Transformation();
  shape.Location(TopLoc_Location());
  in.shape = shape;
  in.placement = placement * own;
  // The material (AP242): its density in OpenCASCADE's units, grams per cubic millimetre.
  const double density = XCAFDoc_MaterialTool::GetDensityForShape(label);
  if (density > 0) {
    // g/mm^3 → kg/m^3, to 12 significant digits: a file's 7.85 g/cm^3 comes back as 0.00785 g/mm^3
    // rounded, and is meant as 7850, not 7849.999999999999.
    char text[32];
    std::snprintf(text, sizeof text, "%.12g", density * 1e6);
    in.density = std::strtod(text, nullptr);
    Handle(TDataStd_TreeNode) node;
    if (label.FindAttribute(XCAFDoc::MaterialRefGUID(), node) && node->HasFather()) {
      Handle(XCAFDoc_Material) material;
      if (node->Father()->Label().FindAttribute(XCAFDoc_Material::GetID(), material) && !material->GetName().IsNull()) {
        in.material = material->GetName()->ToCString();
      }
    }
  }
  out.push_back(in);
}

Prototype Tessellate(const TopoDS_Shape& shape, const MasspropsCadOptions& o, double mm_per_unit) {
  Prototype p;
  Bnd_Box box;
  BRepBndLib::Add(shape, box, false);
  double diagonal = 0;
  if (!box.IsVoid()) diagonal = std::sqrt(box.SquareExtent());
  p.deflection =
      o.deflection > 0 ? o.deflection * (mm_per_unit > 0 ? mm_per_unit : 1.0) : o.relative_deflection * diagonal;
  if (!(p.deflection > 0)) p.deflection = 1e-3;
  // Triangles grow as 1/deflection on curved faces: below 1e-6 of the part's size they would not
  // fit in memory (nor finish), so such a request is refused rather than attempted.
  if (p.deflection < 1e-6 * diagonal) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "the deflection %.3g is below 1e-6 of the part's diagonal (%.4g): its "
                  "tessellation would not fit in memory; give a larger deflection",
                  p.deflection / (mm_per_unit > 0 ? mm_per_unit : 1.0),
                  diagonal / (mm_per_unit > 0 ? mm_per_unit : 1.0));
    throw Refusal{text};
  }
  // One thread: the same triangles every time.
  BRepMesh_IncrementalMesh mesher(shape, p.deflection, false, o.angular_deflection, false);
  for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
    const TopoDS_Face& face = TopoDS::Face(e.Current());
    TopLoc_Location location;
    const Handle(Poly_Triangulation) t = BRep_Tool::Triangulation(face, location);
    if (t.IsNull() || t->NbTriangles() == 0) {
      ++p.untessellated;  // a hole in the mesh: the checks refuse it, and the message says why
      continue;
    }
    const gp_Trsf to_shape = location.Transformation();
    const bool reversed = face.Orientation() == TopAbs_REVERSED;
    for (Standard_Integer i = 1; i <= t->NbTriangles(); ++i) {
      Standard_Integer a, b, c;
      t->Triangle(i).Get(a, b, c);
      if (reversed) std::swap(b, c);
      for (Standard_Integer n : {a, b, c}) {
        const gp_Pnt q = t->Node(n).Transformed(to_shape);
        p.corners.insert(p.corners.end(), {q.X(), q.Y(), q.Z()});
      }
    }
  }
  p.solid = TopExp_Explorer(shape, TopAbs_SOLID).More();
  if (p.solid) {
    GProp_GProps props;
    p.error = BRepGProp::VolumeProperties(shape, props, o.brep_tolerance, true);
    p.volume = props.Mass();
    p.com = props.CentreOfMass();
    p.inertia = props.MatrixOfInertia();
  }
  return p;
}

// What a file gave: its parts, and the unit it declares.
struct Document {
  std::string format;      // "STEP", "IGES", "BREP"
  std::string unit_word;   // as the file names it; "" when it names none
  double mm_per_unit = 0;  // 0: unknown (the coordinates stay in millimetres)
  std::vector<Instance> instances;
};

// Reads a STEP or IGES file into an XCAF document (names, placements, materials).
template <typename CafReader>
Handle(TDocStd_Document) Transfer(CafReader& reader, const char* path) {
  if (reader.ReadFile(path) != IFSelect_RetDone) {
    throw Refusal{"OpenCASCADE could not parse it (not a valid file of this format, or cut short)"};
  }
  Handle(TDocStd_Document) doc;
  XCAFApp_Application::GetApplication()->NewDocument("MDTV-XCAF", doc);
  if (!reader.Transfer(doc)) throw Refusal{"OpenCASCADE found no shape it could transfer (no solid, shell or face)"};
  return doc;
}

// Every product instance of the document's assembly trees.
void CollectInstances(const Handle(TDocStd_Document) & doc, Document& d) {
  const Handle(XCAFDoc_ShapeTool) shapes = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  TDF_LabelSequence roots;
  shapes->GetFreeShapes(roots);
  for (Standard_Integer i = 1; i <= roots.Length(); ++i) Collect(shapes, roots(i), gp_Trsf(), d.instances, 0);
}

Document ReadStep(const char* path) {
  Document d;
  d.format = "STEP";
  STEPCAFControl_Reader reader;
  reader.SetNameMode(true);
  reader.SetMatMode(true);
  reader.SetColorMode(false);
  reader.SetGDTMode(false);
  reader.SetLayerMode(false);
  const Handle(TDocStd_Document) doc = Transfer(reader, path);
  TColStd_SequenceOfAsciiString lengths, angles, solid_angles;
  reader.ChangeReader().FileUnits(lengths, angles, solid_angles);
  if (lengths.Length() > 0) {
    d.unit_word = lengths(1).ToCString();
    d.mm_per_unit = MillimetresPerStepUnit(d.unit_word);
    for (Standard_Integer i = 2; i <= lengths.Length(); ++i) {
      if (MillimetresPerStepUnit(lengths(i).ToCString()) != d.mm_per_unit) {
        d.unit_word += std::string(" and ") + lengths(i).ToCString();
        d.mm_per_unit = 0;  // parts in several units: left in millimetres
      }
    }
  }
  CollectInstances(doc, d);
  return d;
}

Document ReadIges(const char* path) {
  Document d;
  d.format = "IGES";
  IGESCAFControl_Reader reader;
  reader.SetNameMode(true);
  reader.SetColorMode(false);
  reader.SetLayerMode(false);
  const Handle(TDocStd_Document) doc = Transfer(reader, path);
  const Handle(IGESData_IGESModel) model = Handle(IGESData_IGESModel)::DownCast(reader.Model());
  if (!model.IsNull()) IgesUnit(model->GlobalSection().UnitFlag(), d.unit_word, d.mm_per_unit);
  CollectInstances(doc, d);
  return d;
}

// A BREP file has no unit and no names: one part, or one per shape of a top-level compound.
Document ReadBrep(const char* path) {
  Document d;
  d.format = "BREP";
  TopoDS_Shape shape;
  BRep_Builder builder;
  if (!BRepTools::Read(shape, path, builder) || shape.IsNull()) {
    throw Refusal{"OpenCASCADE could not read it as a BREP file (not one, or cut short)"};
  }
  std::vector<TopoDS_Shape> shapes;
  if (shape.ShapeType() == TopAbs_COMPOUND) {
    for (TopoDS_Iterator it(shape); it.More(); it.Next()) shapes.push_back(it.Value());
  }
  if (shapes.size() < 2) shapes = {shape};
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    Instance in;
    if (shapes.size() > 1) in.name = "shape " + std::to_string(i + 1);
    in.placement = shapes[i].Location().Transformation();
    in.shape = shapes[i].Located(TopLoc_Location());
    d.instances.push_back(in);
  }
  return d;
}

// One instance's record: the prototype's triangles and integrals, placed.
void WriteInstance(const Instance& in, const Prototype& p, const MasspropsCadOptions& o, massprops::wire::Writer& w) {
  const gp_Trsf& t = in.placement;
  Prototype moved;
  if (std::abs(std::abs(t.ScaleFactor()) - 1.0) > 1e-12 && p.solid) {
    // A placement that scales is applied to the integrals by moving the shape itself.
    GProp_GProps props;
    moved.error = BRepGProp::VolumeProperties(in.shape.Moved(TopLoc_Location(t)), props, o.brep_tolerance, true);
    moved.volume = props.Mass();
    moved.com = props.CentreOfMass();
    moved.inertia = props.MatrixOfInertia();
  } else {
    // Rigid (a mirror included): c' = R c + t, I' = R I Rᵀ.
    moved.volume = p.volume;
    moved.error = p.error;
    moved.com = p.com.Transformed(t);
    const gp_Mat r = t.VectorialPart();
    moved.inertia = r * p.inertia * r.Transposed();
  }
  w.Str(in.name);
  w.Str(in.material);
  w.F64(in.density);
  w.U64(p.solid ? 1 : 0);
  w.F64(moved.volume);
  for (double x : {moved.com.X(), moved.com.Y(), moved.com.Z()}) w.F64(x);
  for (int r = 1; r <= 3; ++r) {
    for (int c = 1; c <= 3; ++c) w.F64(moved.inertia(r, c));
  }
  w.F64(moved.error);
  w.F64(p.deflection);
  w.U64(p.untessellated);
  const std::size_t triangles = p.corners.size() / 9;
  w.U64(triangles);
  // A mirroring placement turns the faces inside out: two corners swap back.
  const bool mirrored = t.IsNegative();
  std::vector<double> placed(p.corners.size());
  for (std::size_t k = 0; k < triangles; ++k) {
    for (int c = 0; c < 3; ++c) {
      const int from = mirrored && c > 0 ? 3 - c : c;
      gp_Pnt q(p.corners[9 * k + 3 * from], p.corners[9 * k + 3 * from + 1], p.corners[9 * k + 3 * from + 2]);
      q.Transform(t);
      placed[9 * k + 3 * c] = q.X();
      placed[9 * k + 3 * c + 1] = q.Y();
      placed[9 * k + 3 * c + 2] = q.Z();
    }
  }
  w.F64s(placed.data(), placed.size());
}

void Hand(massprops::wire::Writer& w, char** out, std::size_t* size) {
  *size = w.bytes().size();
  *out = static_cast<char*>(std::malloc(std::max<std::size_t>(*size, 1)));
  if (*out != nullptr) std::memcpy(*out, w.bytes().data(), *size);
}

void Fail(const std::string& message, char** out, std::size_t* size) {
  massprops::wire::Writer w;
  w.Str(message);
  Hand(w, out, size);
}

int Read(const char* path, const MasspropsCadOptions& o, char** out, std::size_t* size) {
  // OpenCASCADE prints its progress on standard output; the child's output is its pipe only.
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  const Document d = o.format == kMasspropsCadBrep   ? ReadBrep(path)
                     : o.format == kMasspropsCadIges ? ReadIges(path)
                                                     : ReadStep(path);
  if (d.instances.empty()) throw Refusal{"the file holds no shape (no solid, shell or face)"};
  massprops::wire::Writer w;
  w.Str(d.format);
  w.Str(d.unit_word);
  w.F64(d.mm_per_unit);
  w.U64(d.instances.size());
  // Each prototype is tessellated and integrated once, however many instances place it.
  std::map<const TopoDS_TShape*, std::vector<std::pair<TopLoc_Location, Prototype>>> done;
  for (const Instance& in : d.instances) {
    auto& list = done[in.shape.TShape().get()];
    const Prototype* p = nullptr;
    for (const auto& entry : list) {
      if (entry.first.IsEqual(in.shape.Location())) p = &entry.second;
    }
    if (p == nullptr) {
      list.emplace_back(in.shape.Location(), Tessellate(in.shape, o, d.mm_per_unit));
      p = &list.back().second;
    }
    WriteInstance(in, *p, o, w);
  }
  Hand(w, out, size);
  return *out == nullptr ? 1 : 0;
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) int massprops_cad_read(const char* path, const MasspropsCadOptions* options,
                                                              char** out, std::size_t* size) {
  *out = nullptr;
  *size = 0;
  if (options == nullptr || options->abi != MASSPROPS_CAD_ABI) {
    Fail("the CAD plugin does not match this massprops (a mismatched build?)", out, size);
    return 1;
  }
  try {
    return Read(path, *options, out, size);
  } catch (const Refusal& e) {
    Fail(e.message, out, size);
  } catch (const Standard_Failure& e) {
    Fail(std::string("OpenCASCADE failed while reading it: ") +
             (e.GetMessageString() && *e.GetMessageString() ? e.GetMessageString() : e.DynamicType()->Name()),
         out, size);
  } catch (const std::exception& e) {
    Fail(std::string("reading it failed: ") + e.what(), out, size);
  }
  return 1;
}

__attribute__((visibility("default"))) void massprops_cad_free(void* p) { std::free(p); }

}  // extern "C"
