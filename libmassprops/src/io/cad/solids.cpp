// Every solid of a CAD shape, as an engineer's CAD system would find it: solids inside compounds
// that also hold curves or points, closed shells with no solid around them, loose faces sewn
// first, and solids whose faces point inward turned outward. Each fix changes the "exact" shape,
// so each is said.

#include <cmath>
#include <string>

#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepGProp.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <ShapeFix_Shell.hxx>
#include <ShapeFix_Solid.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>

#include "io/cad/occ.h"

namespace massprops::cad {
namespace {

double SignedVolume(const TopoDS_Shape& solid) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(solid, props, true);
  return props.Mass();
}

std::string Count(int n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); }

class Collector {
 public:
  Collector() {
    builder_.MakeCompound(set_.solids);
    builder_.MakeCompound(set_.surfaces);
  }

  // A solid, turned outward when its faces point inward.
  void AddSolid(TopoDS_Shape solid, int& reversed) {
    const double volume = SignedVolume(solid);
    if (volume < 0) {
      solid.Reverse();
      ++reversed;
    }
    set_.volumes.push_back(std::abs(volume));
    builder_.Add(set_.solids, solid);
    ++set_.count;
  }

  void AddSurface(const TopoDS_Shape& s) {
    builder_.Add(set_.surfaces, s);
    set_.has_surfaces = true;
  }

  SolidSet& set() { return set_; }

 private:
  BRep_Builder builder_;
  SolidSet set_;
};

}  // namespace

double Diagonal(const TopoDS_Shape& shape) {
  Bnd_Box box;
  BRepBndLib::Add(shape, box, false);
  return box.IsVoid() ? 0.0 : std::sqrt(box.SquareExtent());
}

SolidSet FindSolids(const TopoDS_Shape& shape) {
  Collector c;
  int reversed = 0, from_shells = 0;
  for (TopExp_Explorer e(shape, TopAbs_SOLID); e.More(); e.Next()) c.AddSolid(e.Current(), reversed);
  // Shells outside any solid: closed ones bound a solid of their own; open ones, and faces outside
  // any shell, are sewn together first.
  BRepBuilderAPI_Sewing sewing(std::max(1e-6, 1e-5 * Diagonal(shape)));
  int loose = 0;
  for (TopExp_Explorer e(shape, TopAbs_SHELL, TopAbs_SOLID); e.More(); e.Next()) {
    const TopoDS_Shell& shell = TopoDS::Shell(e.Current());
    if (BRep_Tool::IsClosed(shell)) {
      ShapeFix_Solid fix;
      c.AddSolid(fix.SolidFromShell(shell), reversed);
      ++from_shells;
    } else {
      for (TopExp_Explorer f(shell, TopAbs_FACE); f.More(); f.Next()) {
        sewing.Add(f.Current());
        ++loose;
      }
    }
  }
  for (TopExp_Explorer f(shape, TopAbs_FACE, TopAbs_SHELL); f.More(); f.Next()) {
    sewing.Add(f.Current());
    ++loose;
  }
  SolidSet& set = c.set();
  if (from_shells > 0) {
    set.fixes.push_back(Count(from_shells, "closed shell", "closed shells") +
                        " with no solid around them made solids (ShapeFix_Solid)");
  }
  if (loose > 0) {
    sewing.Perform();
    const TopoDS_Shape sewn = sewing.SewedShape();
    int closed = 0;
    for (TopExp_Explorer e(sewn, TopAbs_SHELL); e.More(); e.Next()) {
      // Faces sewn from separate shells keep their own orientations: made consistent first.
      ShapeFix_Shell orient(TopoDS::Shell(e.Current()));
      orient.Perform();
      const TopoDS_Shell shell = orient.Shell();
      if (BRep_Tool::IsClosed(shell)) {
        ShapeFix_Solid fix;
        c.AddSolid(fix.SolidFromShell(shell), reversed);
        ++closed;
      } else {
        c.AddSurface(shell);
      }
    }
    for (TopExp_Explorer f(sewn, TopAbs_FACE, TopAbs_SHELL); f.More(); f.Next()) c.AddSurface(f.Current());
    if (closed > 0) {
      set.fixes.push_back(Count(loose, "unsewn face", "unsewn faces") + " sewn (within " +
                          std::to_string(sewing.Tolerance()) + " mm) into " +
                          Count(closed, "closed shell", "closed shells") + ", made solids");
    }
  }
  if (reversed > 0) {
    set.fixes.push_back(Count(reversed, "solid was", "solids were") +
                        " inside out (faces pointing inward, a negative volume): turned outward");
  }
  return set;
}

}  // namespace massprops::cad
