// A CAD file read into the instances of its assembly: STEP and IGES through OCAF/XDE (names,
// placements, AP242 materials, STEP's validation properties), BREP as one shape; the unit the file
// declares. Coordinates come out in OpenCASCADE's session unit, millimetres.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <IGESCAFControl_Reader.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESModel.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <StepBasic_ConversionBasedUnitAndLengthUnit.hxx>
#include <StepBasic_HArray1OfNamedUnit.hxx>
#include <StepBasic_Product.hxx>
#include <StepBasic_ProductDefinition.hxx>
#include <StepBasic_ProductDefinitionFormation.hxx>
#include <StepBasic_SiUnitAndLengthUnit.hxx>
#include <StepData_StepModel.hxx>
#include <StepGeom_GeomRepContextAndGlobUnitAssCtxAndGlobUncertaintyAssCtx.hxx>
#include <StepGeom_GeometricRepresentationContextAndGlobalUnitAssignedContext.hxx>
#include <StepRepr_CharacterizedDefinition.hxx>
#include <StepRepr_PropertyDefinition.hxx>
#include <StepRepr_Representation.hxx>
#include <StepRepr_RepresentedDefinition.hxx>
#include <StepShape_ShapeDefinitionRepresentation.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TDataStd_Name.hxx>
#include <TDataStd_TreeNode.hxx>
#include <TDocStd_Document.hxx>
#include <TopoDS_Iterator.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc.hxx>
#include <XCAFDoc_Area.hxx>
#include <XCAFDoc_Centroid.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_Material.hxx>
#include <XCAFDoc_MaterialTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <XCAFDoc_Volume.hxx>

#include "io/cad/occ.h"

namespace massprops::cad {
namespace {

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

// The validation properties the exporting system attached to a product (XDE's props mode).
FileProperties PropertiesOf(const TDF_Label& label) {
  FileProperties p;
  p.has_volume = XCAFDoc_Volume::Get(label, p.volume) && p.volume > 0;
  p.has_area = XCAFDoc_Area::Get(label, p.area) && p.area > 0;
  p.has_centroid = XCAFDoc_Centroid::Get(label, p.centroid);
  return p;
}

// Depth-first over an XCAF assembly: every simple shape reached is an instance, with the product
// of the placements on the way and the name of the component that placed it.
void Collect(const TDF_Label& label, const gp_Trsf& placement, const std::string& component, std::vector<Instance>& out,
             int depth) {
  if (depth > 64) throw Standard_Failure("the assembly is nested more than 64 levels deep (a cycle?)");
  if (XCAFDoc_ShapeTool::IsAssembly(label)) {
    TDF_LabelSequence components;
    XCAFDoc_ShapeTool::GetComponents(label, components);
    for (Standard_Integer i = 1; i <= components.Length(); ++i) {
      TDF_Label referred;
      if (!XCAFDoc_ShapeTool::GetReferredShape(components(i), referred)) continue;
      const gp_Trsf local = XCAFDoc_ShapeTool::GetLocation(components(i)).Transformation();
      Collect(referred, placement * local, NameOf(components(i)), out, depth + 1);
    }
    return;
  }
  Instance in;
  in.name = NameOf(label);
  // OpenCASCADE names an unnamed component after the label it refers to ("=>[0:1:1:2]"): no name.
  if (component != in.name && component.rfind("=>", 0) != 0) in.instance = component;
  TopoDS_Shape shape = XCAFDoc_ShapeTool::GetShape(label);
  // A free shape may carry its own location: it is part of the placement, not of the prototype.
  const gp_Trsf own = shape.Location().Transformation();
  shape.Location(TopLoc_Location());
  in.shape = shape;
  in.placement = placement * own;
  in.file = PropertiesOf(label);
  if (in.file.has_centroid) in.file.centroid.Transform(own.Inverted());  // the prototype's frame
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

// The length unit of a STEP representation context, as the file names it: a conversion-based
// unit's name ("INCH"), or an SI unit with its prefix ("MILLIMETRE"); "" when it declares none.
std::string LengthUnitWord(const Handle(StepRepr_RepresentationContext) & context) {
  Handle(StepBasic_HArray1OfNamedUnit) units;
  if (const auto a = Handle(StepGeom_GeomRepContextAndGlobUnitAssCtxAndGlobUncertaintyAssCtx)::DownCast(context)) {
    units = a->Units();
  } else if (const auto b =
                 Handle(StepGeom_GeometricRepresentationContextAndGlobalUnitAssignedContext)::DownCast(context)) {
    units = b->Units();
  }
  if (units.IsNull()) return "";
  for (Standard_Integer i = units->Lower(); i <= units->Upper(); ++i) {
    const Handle(StepBasic_NamedUnit)& unit = units->Value(i);
    if (const auto c = Handle(StepBasic_ConversionBasedUnitAndLengthUnit)::DownCast(unit)) {
      return c->Name().IsNull() ? "" : c->Name()->ToCString();
    }
    if (const auto si = Handle(StepBasic_SiUnitAndLengthUnit)::DownCast(unit)) {
      if (si->Name() != StepBasic_sunMetre) continue;
      if (!si->HasPrefix()) return "METRE";
      switch (si->Prefix()) {
        case StepBasic_spMilli: return "MILLIMETRE";
        case StepBasic_spCenti: return "CENTIMETRE";
        case StepBasic_spDeci: return "DECIMETRE";
        case StepBasic_spMicro: return "MICROMETRE";
        case StepBasic_spKilo: return "KILOMETRE";
        default: return "";
      }
    }
  }
  return "";
}

// Each product's declared length unit, by product name: the context of the representation its
// SHAPE_DEFINITION_REPRESENTATION uses (a name given two units maps to "").
std::map<std::string, std::string> ProductUnits(const Handle(StepData_StepModel) & model) {
  std::map<std::string, std::string> units;
  if (model.IsNull()) return units;
  for (Standard_Integer i = 1; i <= model->NbEntities(); ++i) {
    const auto sdr = Handle(StepShape_ShapeDefinitionRepresentation)::DownCast(model->Value(i));
    if (sdr.IsNull() || sdr->UsedRepresentation().IsNull()) continue;
    const Handle(StepRepr_PropertyDefinition) property = sdr->Definition().PropertyDefinition();
    if (property.IsNull()) continue;
    const Handle(StepBasic_ProductDefinition) definition = property->Definition().ProductDefinition();
    if (definition.IsNull() || definition->Formation().IsNull() || definition->Formation()->OfProduct().IsNull()) {
      continue;
    }
    const Handle(TCollection_HAsciiString) name = definition->Formation()->OfProduct()->Name();
    const std::string word = LengthUnitWord(sdr->UsedRepresentation()->ContextOfItems());
    if (name.IsNull() || word.empty()) continue;
    const auto [it, added] = units.emplace(name->ToCString(), word);
    if (!added && it->second != word) it->second.clear();
  }
  return units;
}

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
  for (Standard_Integer i = 1; i <= roots.Length(); ++i) Collect(roots(i), gp_Trsf(), "", d.instances, 0);
}

Document ReadStep(const char* path) {
  Document d;
  d.format = "STEP";
  STEPCAFControl_Reader reader;
  reader.SetNameMode(true);
  reader.SetMatMode(true);
  reader.SetPropsMode(true);
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
      const double mm = MillimetresPerStepUnit(lengths(i).ToCString());
      if (mm != d.mm_per_unit && d.unit_word.find(lengths(i).ToCString()) == std::string::npos) {
        // Parts in several units: OpenCASCADE converts each to millimetres, so the whole is
        // composed in millimetres.
        d.unit_word += std::string(" and ") + lengths(i).ToCString();
        d.mm_per_unit = 0;
      }
    }
  }
  CollectInstances(doc, d);
  const std::map<std::string, std::string> units = ProductUnits(reader.ChangeReader().StepModel());
  for (Instance& in : d.instances) {
    const auto it = units.find(in.name);
    if (it != units.end()) in.unit_word = it->second;
  }
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

}  // namespace

Document ReadDocument(const char* path, int format) {
  return format == kMasspropsCadBrep ? ReadBrep(path) : format == kMasspropsCadIges ? ReadIges(path) : ReadStep(path);
}

}  // namespace massprops::cad
