// OpenCASCADE's own stages on a STEP file, timed in one process with nothing of ours around them:
// the baseline bench/cad_bench.py sets `massprops FILE.step` against. Prints one JSON object:
//
//   {"faces": F, "parts": P, "read_s": ..., "mesh_s": ..., "brep_s": ...}
//
//   cad_stages FILE.step [--mesh REL]
//
// read: STEPCAFControl_Reader into an XCAF document (names, placements, materials), as our plugin
// reads; mesh: BRepMesh at REL of each free shape's diagonal (default 1e-3, the check mesh's; 0
// skips it: the plain program that reads and integrates), angular 0.5; brep:
// BRepGProp::VolumeProperties with a relative error target of 1e-12 (the integration alone).

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp_Explorer.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>

namespace {

double Since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  double relative = 1e-3;
  if (argc == 4 && std::string(argv[2]) == "--mesh") {
    relative = std::atof(argv[3]);
  } else if (argc != 2) {
    std::fprintf(stderr, "usage: cad_stages FILE.step [--mesh RELATIVE_DEFLECTION]\n");
    return 2;
  }
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  auto t0 = std::chrono::steady_clock::now();
  Handle(XCAFApp_Application) app = XCAFApp_Application::GetApplication();
  Handle(TDocStd_Document) doc;
  app->NewDocument("MDTV-XCAF", doc);
  STEPCAFControl_Reader reader;
  reader.SetNameMode(true);
  reader.SetMatMode(true);
  reader.SetColorMode(false);
  reader.SetGDTMode(false);
  reader.SetLayerMode(false);
  if (reader.ReadFile(argv[1]) != IFSelect_RetDone || !reader.Transfer(doc)) {
    std::fprintf(stderr, "cad_stages: cannot read %s\n", argv[1]);
    return 1;
  }
  const double read_s = Since(t0);
  const Handle(XCAFDoc_ShapeTool) shapes = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  TDF_LabelSequence simple;
  shapes->GetShapes(simple);
  int faces = 0, parts = 0;
  t0 = std::chrono::steady_clock::now();
  for (Standard_Integer i = 1; i <= simple.Length(); ++i) {
    if (relative <= 0 || !XCAFDoc_ShapeTool::IsSimpleShape(simple(i))) continue;
    const TopoDS_Shape s = XCAFDoc_ShapeTool::GetShape(simple(i));
    Bnd_Box box;
    BRepBndLib::Add(s, box, false);
    BRepMesh_IncrementalMesh mesher(s, relative * std::sqrt(box.SquareExtent()), false, 0.5, false);
  }
  const double mesh_s = Since(t0);
  t0 = std::chrono::steady_clock::now();
  for (Standard_Integer i = 1; i <= simple.Length(); ++i) {
    if (!XCAFDoc_ShapeTool::IsSimpleShape(simple(i))) continue;
    const TopoDS_Shape s = XCAFDoc_ShapeTool::GetShape(simple(i));
    GProp_GProps props;
    BRepGProp::VolumeProperties(s, props, 1e-12, true);
    ++parts;
    for (TopExp_Explorer e(s, TopAbs_FACE); e.More(); e.Next()) ++faces;
  }
  const double brep_s = Since(t0);
  std::printf("{\"faces\": %d, \"parts\": %d, \"read_s\": %.6f, \"mesh_s\": %.6f, \"brep_s\": %.6f}\n", faces, parts,
              read_s, mesh_s, brep_s);
  return 0;
}
