// Interference between the solids of an assembly: boxes first, then the exact common volume
// (BRepAlgoAPI_Common, fuzzy and non-destructive) of the pairs whose boxes overlap, as many pairs
// as the budget allows, in a fixed order, so that the report does not depend on the machine.

#include <algorithm>
#include <cmath>

#include <BRepAlgoAPI_Common.hxx>
#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <Standard_Failure.hxx>

#include "io/cad/occ.h"

namespace massprops::cad {

Interference MeasureInterference(const std::vector<PlacedSolid>& solids, int budget) {
  Interference result;
  std::vector<Bnd_Box> boxes(solids.size());
  for (std::size_t i = 0; i < solids.size(); ++i) BRepBndLib::Add(solids[i].solid, boxes[i], false);
  for (std::size_t i = 0; i < solids.size(); ++i) {
    for (std::size_t j = i + 1; j < solids.size(); ++j) {
      if (boxes[i].IsVoid() || boxes[j].IsVoid() || boxes[i].IsOut(boxes[j])) continue;
      ++result.candidates;
      if (result.measured >= static_cast<std::uint64_t>(std::max(budget, 0))) continue;
      ++result.measured;
      const double smaller = std::min(std::abs(solids[i].volume), std::abs(solids[j].volume));
      const double size = std::sqrt(std::max(boxes[i].SquareExtent(), boxes[j].SquareExtent()));
      double common = 0;
      try {
        BRepAlgoAPI_Common op;
        TopTools_ListOfShape a, b;
        a.Append(solids[i].solid);
        b.Append(solids[j].solid);
        op.SetArguments(a);
        op.SetTools(b);
        // Faces within this distance are one face: a bolt in a hole of its own radius touches it.
        op.SetFuzzyValue(1e-7 * size);
        op.SetNonDestructive(true);
        op.SetRunParallel(false);
        op.Build();
        if (op.HasErrors()) {
          result.overlaps.push_back({solids[i].instance, solids[j].instance, -1});  // not measured
          continue;
        }
        GProp_GProps props;
        BRepGProp::VolumeProperties(op.Shape(), props, true);
        common = std::abs(props.Mass());
      } catch (const Standard_Failure&) {
        result.overlaps.push_back({solids[i].instance, solids[j].instance, -1});
        continue;
      }
      // Touching solids leave a sliver of rounding, not volume.
      if (common > 1e-6 * smaller) result.overlaps.push_back({solids[i].instance, solids[j].instance, common});
    }
  }
  return result;
}

}  // namespace massprops::cad
