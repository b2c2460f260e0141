// massprops::repair's entry points for the pipeline (geometry_steps.h).

#include "massprops/io/geometry_steps.h"

extern "C" __attribute__((visibility("default"))) const massprops::GeometrySteps* massprops_geometry_steps() {
  static const massprops::GeometrySteps steps = [] {
    massprops::GeometrySteps s;
    s.repair = &massprops::RepairMesh;
    s.union_of_shells = &massprops::UnionOfShells;
    s.count_self_intersections = &massprops::CountSelfIntersections;
    s.convex_hull = &massprops::ConvexHull;
    s.exact = &massprops::ExactMassPropertiesOf;
    return s;
  }();
  return &steps;
}
