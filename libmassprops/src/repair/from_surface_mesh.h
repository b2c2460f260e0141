#pragma once
// A CGAL Surface_mesh as our PolygonMesh (internal: for the CGAL translation units only).

#include <CGAL/Surface_mesh.h>

#include <cstdint>
#include <vector>

#include "massprops/mesh.h"

namespace massprops::cgal_internal {

// Vertices renumbered densely in the mesh's order, faces with their corners in order.
template <typename Point>
PolygonMesh FromSurfaceMesh(CGAL::Surface_mesh<Point>& mesh) {
  mesh.collect_garbage();
  PolygonMesh out;
  out.V.resize(static_cast<Eigen::Index>(mesh.number_of_vertices()), 3);
  std::vector<std::int32_t> index(mesh.num_vertices(), -1);
  std::int32_t next = 0;
  for (auto v : mesh.vertices()) {
    const Point& p = mesh.point(v);
    index[v.idx()] = next;
    out.V.row(next++) << p.x(), p.y(), p.z();
  }
  for (auto f : mesh.faces()) {
    std::vector<std::int32_t> face;
    for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) face.push_back(index[v.idx()]);
    out.AddFace(face);
  }
  return out;
}

}  // namespace massprops::cgal_internal
