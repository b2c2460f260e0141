// Writes the CAD files the tests and benchmarks read, with OpenCASCADE itself: closed-form solids
// as STEP, IGES and BREP, a part in inches, named assemblies with placements and AP242 materials,
// an open shell, a file with no solid, and the STL of a part's own tessellation.
//
//   make_cad DIR              the test set (see Fixtures below)
//   make_cad --bench DIR      a part of about 10^3 faces, a 1 MB B-spline solid, an assembly of 100 parts
//
// Dimensions are in millimetres (OpenCASCADE's unit) unless a file says otherwise.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepLib.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <Geom_BSplineSurface.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPCAFControl_Writer.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <StlAPI_Writer.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Shell.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_Centroid.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_MaterialTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <XCAFDoc_Volume.hxx>
#include <gp_Ax2.hxx>
#include <gp_Trsf.hxx>

namespace {

bool Check(bool ok, const std::string& what) {
  if (!ok) std::fprintf(stderr, "make_cad: could not write %s\n", what.c_str());
  return ok;
}

bool WriteStep(const TopoDS_Shape& shape, const std::string& path, const char* unit = "MM") {
  STEPControl_Controller::Init();  // before the unit: set earlier, it is ignored
  Interface_Static::SetCVal("write.step.unit", unit);
  STEPControl_Writer writer;
  if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone) return Check(false, path);
  const bool ok = writer.Write(path.c_str()) == IFSelect_RetDone;
  Interface_Static::SetCVal("write.step.unit", "MM");
  return Check(ok, path);
}

bool WriteIges(const TopoDS_Shape& shape, const std::string& path) {
  IGESControl_Controller::Init();
  IGESControl_Writer writer("MM", 1);  // B-rep mode: solids as solids
  writer.AddShape(shape);
  writer.ComputeModel();
  return Check(writer.Write(path.c_str()), path);
}

bool WriteBrep(const TopoDS_Shape& shape, const std::string& path) {
  return Check(BRepTools::Write(shape, path.c_str()), path);
}

struct Placed {
  std::string product;
  TopoDS_Shape shape;
  gp_Trsf placement;
  std::string material;
  double density_g_cm3 = 0;
};

// A named assembly: one product per distinct name (instances of a name share its shape).
bool WriteAssembly(const std::vector<Placed>& parts, const std::string& name, const std::string& path) {
  Handle(XCAFApp_Application) app = XCAFApp_Application::GetApplication();
  Handle(TDocStd_Document) doc;
  app->NewDocument("MDTV-XCAF", doc);
  const Handle(XCAFDoc_ShapeTool) shapes = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  const Handle(XCAFDoc_MaterialTool) materials = XCAFDoc_DocumentTool::MaterialTool(doc->Main());
  const TDF_Label assembly = shapes->NewShape();
  TDataStd_Name::Set(assembly, name.c_str());
  std::vector<std::pair<std::string, TDF_Label>> products;
  for (const Placed& p : parts) {
    TDF_Label product;
    for (const auto& [n, label] : products) {
      if (n == p.product) product = label;
    }
    if (product.IsNull()) {
      product = shapes->AddShape(p.shape, false);
      TDataStd_Name::Set(product, p.product.c_str());
      if (!p.material.empty()) {
        materials->SetMaterial(product, new TCollection_HAsciiString(p.material.c_str()),
                               new TCollection_HAsciiString(""), p.density_g_cm3,
                               new TCollection_HAsciiString("density"),
                               new TCollection_HAsciiString("POSITIVE_RATIO_MEASURE"));
      }
      products.emplace_back(p.product, product);
    }
    shapes->AddComponent(assembly, product, TopLoc_Location(p.placement));
  }
  shapes->UpdateAssemblies();
  STEPControl_Controller::Init();
  Interface_Static::SetCVal("write.step.unit", "MM");
  STEPCAFControl_Writer writer;
  writer.SetMaterialMode(true);
  writer.SetNameMode(true);
  if (!writer.Transfer(doc, STEPControl_AsIs)) return Check(false, path);
  return Check(writer.Write(path.c_str()) == IFSelect_RetDone, path);
}

// One product with the validation properties an exporter computed for it (STEP's
// geometric validation properties: volume, centroid), as SolidWorks and Creo write them.
bool WriteWithProperties(const TopoDS_Shape& shape, double volume, const gp_Pnt& centroid, const std::string& path) {
  Handle(TDocStd_Document) doc;
  XCAFApp_Application::GetApplication()->NewDocument("MDTV-XCAF", doc);
  const Handle(XCAFDoc_ShapeTool) shapes = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  const TDF_Label label = shapes->AddShape(shape, false);
  TDataStd_Name::Set(label, "validated");
  XCAFDoc_Volume::Set(label, volume);
  XCAFDoc_Centroid::Set(label, centroid);
  STEPControl_Controller::Init();
  Interface_Static::SetCVal("write.step.unit", "MM");
  STEPCAFControl_Writer writer;
  writer.SetPropsMode(true);
  writer.SetNameMode(true);
  if (!writer.Transfer(doc, STEPControl_AsIs)) return Check(false, path);
  return Check(writer.Write(path.c_str()) == IFSelect_RetDone, path);
}

gp_Trsf Placement(double x, double y, double z, double degrees_about_z = 0) {
  gp_Trsf rotation, translation;
  rotation.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), degrees_about_z * M_PI / 180);
  translation.SetTranslation(gp_Vec(x, y, z));
  return translation * rotation;
}

// The STL of the shape's own tessellation (binary), at this chordal deflection, one thread.
bool WriteStlOfTessellation(const TopoDS_Shape& shape, double deflection, const std::string& path) {
  BRepMesh_IncrementalMesh mesher(shape, deflection, false, 0.5, false);
  StlAPI_Writer writer;
  writer.ASCIIMode() = false;
  return Check(writer.Write(shape, path.c_str()), path);
}

// Five faces of a box, sewn: a shell with a hole, no solid.
TopoDS_Shape OpenBox() {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(10, 20, 30).Shape();
  BRepBuilderAPI_Sewing sewing;
  int n = 0;
  for (TopExp_Explorer e(box, TopAbs_FACE); e.More(); e.Next()) {
    if (n++ < 5) sewing.Add(e.Current());
  }
  sewing.Perform();
  return sewing.SewedShape();
}

// A box's six faces, each its own face (no shell): what an exporter that writes surfaces leaves.
TopoDS_Shape LooseFaces() {
  TopoDS_Compound faces;
  BRep_Builder builder;
  builder.MakeCompound(faces);
  for (TopExp_Explorer e(BRepPrimAPI_MakeBox(10, 20, 30).Shape(), TopAbs_FACE); e.More(); e.Next())
    builder.Add(faces, e.Current());
  return faces;
}

// The shapes other systems' files hold, and assemblies as they exchange them. Closed forms in
// cad_test.cpp's CadField tests.
bool FieldFixtures(const std::string& dir) {
  bool ok = true;
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(10, 20, 30).Shape();
  TopoDS_Shell shell;
  for (TopExp_Explorer e(box, TopAbs_SHELL); e.More(); e.Next()) shell = TopoDS::Shell(e.Current());
  ok &= WriteStep(shell, dir + "/closed_shell.step");         // a closed shell with no solid around it
  ok &= WriteStep(LooseFaces(), dir + "/loose_faces.step");   // six unsewn faces
  ok &= WriteStep(box.Reversed(), dir + "/inside_out.step");  // a solid whose faces point inward
  // A solid beside a curve set (NX's habit): one compound of a box and two edges.
  {
    TopoDS_Compound c;
    BRep_Builder b;
    b.MakeCompound(c);
    b.Add(c, box);
    b.Add(c, BRepBuilderAPI_MakeEdge(gp_Pnt(0, 0, 40), gp_Pnt(10, 0, 40)).Shape());
    b.Add(c, BRepBuilderAPI_MakeEdge(gp_Pnt(0, 0, 50), gp_Pnt(0, 20, 50)).Shape());
    ok &= WriteStep(c, dir + "/solid_and_curves.step");
  }
  // A bolt in a hole of its own radius: a 40 × 40 × 10 plate with a hole of radius 5, and a
  // cylinder of radius 5, 30 long, through it. Touching, not interfering.
  const TopoDS_Shape plate =
      BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(gp_Pnt(-20, -20, 0), 40, 40, 10).Shape(),
                      BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp_Dir(0, 0, 1)), 5, 12).Shape())
          .Shape();
  ok &= WriteAssembly(
      {{"plate", plate, Placement(0, 0, 0)}, {"bolt", BRepPrimAPI_MakeCylinder(5, 30).Shape(), Placement(0, 0, -10)}},
      "bolted", dir + "/bolt_in_hole.step");
  // Two 10 × 10 × 10 blocks, the second moved by (6, 3, 0): they share 4 × 7 × 10 = 280 mm^3.
  ok &= WriteAssembly({{"block", BRepPrimAPI_MakeBox(10, 10, 10).Shape(), Placement(0, 0, 0)},
                       {"block", BRepPrimAPI_MakeBox(10, 10, 10).Shape(), Placement(6, 3, 0)}},
                      "overlapping", dir + "/overlapping_blocks.step");
  // An assembly with an empty product and a product of curves only beside a box.
  TopoDS_Compound empty;
  BRep_Builder().MakeCompound(empty);
  ok &= WriteAssembly(
      {{"box", box, Placement(0, 0, 0)},
       {"nothing", empty, Placement(50, 0, 0)},
       {"sketch", BRepBuilderAPI_MakeEdge(gp_Pnt(0, 0, 0), gp_Pnt(10, 0, 0)).Shape(), Placement(0, 50, 0)}},
      "with_empty", dir + "/empty_and_curve_products.step");
  // Validation properties as the exporter wrote them: right (the box's own), and wrong (a volume
  // 2 % larger and a centroid moved by 1 mm).
  ok &= WriteWithProperties(box, 6000, gp_Pnt(5, 10, 15), dir + "/props_agree.step");
  ok &= WriteWithProperties(box, 6120, gp_Pnt(6, 10, 15), dir + "/props_disagree.step");
  return ok;
}

bool Fixtures(const std::string& dir) {
  bool ok = true;
  // Closed forms (README's table): box 10 × 20 × 30, cylinder r 5 h 10, sphere r 10, cone r 4 h 12,
  // torus R 20 r 5, a 40 × 40 × 10 plate with a hole of radius 8 through its middle.
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(10, 20, 30).Shape();
  const TopoDS_Shape cylinder = BRepPrimAPI_MakeCylinder(5, 10).Shape();
  const TopoDS_Shape sphere = BRepPrimAPI_MakeSphere(10).Shape();
  const TopoDS_Shape cone = BRepPrimAPI_MakeCone(4, 0, 12).Shape();
  const TopoDS_Shape torus = BRepPrimAPI_MakeTorus(20, 5).Shape();
  const TopoDS_Shape plate = BRepPrimAPI_MakeBox(gp_Pnt(-20, -20, 0), 40, 40, 10).Shape();
  const TopoDS_Shape hole = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp_Dir(0, 0, 1)), 8, 12).Shape();
  const TopoDS_Shape drilled = BRepAlgoAPI_Cut(plate, hole).Shape();
  ok &= WriteStep(box, dir + "/box.step");
  ok &= WriteStep(cylinder, dir + "/cylinder.step");
  ok &= WriteStep(sphere, dir + "/sphere.step");
  ok &= WriteStep(cone, dir + "/cone.step");
  ok &= WriteStep(torus, dir + "/torus.step");
  ok &= WriteStep(drilled, dir + "/drilled.step");
  ok &= WriteIges(drilled, dir + "/drilled.iges");
  ok &= WriteBrep(drilled, dir + "/drilled.brep");
  ok &= WriteIges(box, dir + "/box.igs");
  ok &= WriteBrep(torus, dir + "/torus.brep");
  // 1 × 2 × 3 inches, made in millimetres, written in inches.
  ok &= WriteStep(BRepPrimAPI_MakeBox(25.4, 50.8, 76.2).Shape(), dir + "/box_inches.step", "INCH");
  // Three products: a steel base plate, an aluminium post standing on it, and a pin used twice
  // (once turned 90 degrees about z); the pin has no material.
  ok &= WriteAssembly({{"base", BRepPrimAPI_MakeBox(100, 60, 10).Shape(), Placement(0, 0, 0), "steel", 7.85},
                       {"post", BRepPrimAPI_MakeCylinder(10, 50).Shape(), Placement(30, 30, 10), "aluminium", 2.7},
                       {"pin", BRepPrimAPI_MakeBox(4, 20, 4).Shape(), Placement(70, 20, 10)},
                       {"pin", BRepPrimAPI_MakeBox(4, 20, 4).Shape(), Placement(90, 40, 10, 90)}},
                      "fixture", dir + "/assembly.step");
  // One material throughout.
  ok &= WriteAssembly({{"block", box, Placement(0, 0, 0), "steel", 7.85}}, "one", dir + "/steel_box.step");
  ok &= WriteStep(OpenBox(), dir + "/open_box.step");
  ok &= FieldFixtures(dir);
  ok &= WriteStep(BRepBuilderAPI_MakeEdge(gp_Pnt(0, 0, 0), gp_Pnt(10, 0, 0)).Shape(), dir + "/edge_only.step");
  // The same tessellation as STEP would make at deflection 0.05 mm, as a binary STL.
  ok &= WriteStlOfTessellation(BRepPrimAPI_MakeCylinder(5, 10).Shape(), 0.05, dir + "/cylinder_0.05.stl");
  return ok;
}

// A single solid whose side is one B-spline surface of 144 x 100 poles (about 1 MB of STEP, as a
// CAD system writes a knurled or lobed part): bicubic, periodic around, clamped along its height,
// five lobes that twist as they rise; its first and last rows of poles are planar, so the two
// ends are planar B-spline curves, capped by plane faces.
TopoDS_Shape LobedSpline() {
  const int around = 144, rows = 100, degree = 3;
  TColgp_Array2OfPnt poles(1, around, 1, rows);
  for (int i = 1; i <= around; ++i) {
    const double t = 2 * M_PI * (i - 1) / around;
    for (int j = 1; j <= rows; ++j) {
      const double z = 0.5 * (j - 1), twist = 0.05 * (j - 1);
      const double r = 10 + 1.5 * std::sin(5 * t + twist) + 0.2 * std::sin(23 * t);
      poles.SetValue(i, j, gp_Pnt(r * std::cos(t), r * std::sin(t), z));
    }
  }
  TColStd_Array1OfReal u_knots(1, around + 1), v_knots(1, rows - degree + 1);
  TColStd_Array1OfInteger u_mults(1, around + 1), v_mults(1, rows - degree + 1);
  for (int k = 1; k <= around + 1; ++k) u_knots.SetValue(k, k - 1), u_mults.SetValue(k, 1);
  for (int k = 1; k <= rows - degree + 1; ++k) v_knots.SetValue(k, k - 1), v_mults.SetValue(k, 1);
  v_mults.SetValue(1, degree + 1), v_mults.SetValue(rows - degree + 1, degree + 1);
  Handle(Geom_BSplineSurface) side =
      new Geom_BSplineSurface(poles, u_knots, v_knots, u_mults, v_mults, degree, degree, Standard_True, Standard_False);
  Standard_Real u0, u1, v0, v1;
  side->Bounds(u0, u1, v0, v1);
  BRepBuilderAPI_Sewing sewing(1e-6);
  sewing.Add(BRepBuilderAPI_MakeFace(side, 1e-7).Face());
  for (double v : {v0, v1}) {
    const TopoDS_Wire rim = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(side->VIso(v)).Edge()).Wire();
    sewing.Add(BRepBuilderAPI_MakeFace(rim, Standard_True).Face());
  }
  sewing.Perform();
  TopoDS_Solid solid = BRepBuilderAPI_MakeSolid(TopoDS::Shell(sewing.SewedShape())).Solid();
  BRepLib::OrientClosedSolid(solid);
  return solid;
}

bool Bench(const std::string& dir) {
  bool ok = true;
  // A part of about 10^3 faces: a plate with a 17 × 17 grid of holes, square ones (4 faces each)
  // and round ones (1 face), cut at once.
  TopoDS_Compound tools;
  BRep_Builder builder;
  builder.MakeCompound(tools);
  for (int i = 0; i < 17; ++i) {
    for (int j = 0; j < 17; ++j) {
      const double x = 10 + 8 * i, y = 10 + 8 * j;
      const TopoDS_Shape hole =
          (i + j) % 4 == 0 ? BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, y, -1), gp_Dir(0, 0, 1)), 2.5, 12).Shape()
                           : BRepPrimAPI_MakeBox(gp_Pnt(x - 2, y - 2, -1), 4, 4, 12).Shape();
      builder.Add(tools, hole);
    }
  }
  const TopoDS_Shape part = BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 156, 156, 10).Shape(), tools).Shape();
  ok &= WriteStep(part, dir + "/plate_1k_faces.step");
  ok &= WriteStep(LobedSpline(), dir + "/spline_1mb.step");
  std::vector<Placed> parts;
  for (int i = 0; i < 100; ++i) {
    const std::string name = "part" + std::to_string(i % 10);
    const TopoDS_Shape shape =
        i % 2 == 0 ? BRepPrimAPI_MakeCylinder(3 + i % 10, 20).Shape() : BRepPrimAPI_MakeBox(5 + i % 10, 8, 6).Shape();
    parts.push_back({name + (i % 2 == 0 ? "c" : "b"), shape, Placement(30.0 * (i % 10), 30.0 * (i / 10), 0, 7.0 * i)});
  }
  ok &= WriteAssembly(parts, "hundred", dir + "/assembly_100.step");
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  const bool bench = argc == 3 && std::string(argv[1]) == "--bench";
  if (argc != 2 && !bench) {
    std::fprintf(stderr, "usage: make_cad DIR | make_cad --bench DIR\n");
    return 2;
  }
  const std::string dir = argv[argc - 1];
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const int code = (bench ? Bench(dir) : Fixtures(dir)) ? 0 : 1;
  // OpenCASCADE keeps its session (readers' statics, the XDE application) until the process ends
  // and never frees it: leave without the exit-time teardown, where LeakSanitizer would count it.
  std::fflush(nullptr);
  std::_Exit(code);
}
