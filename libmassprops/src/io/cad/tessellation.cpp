// The check mesh: BRepMesh's triangles, welded through the B-rep's topology. Each face's nodes are
// placed by that face's own location, so the nodes of an edge shared by two faces may differ by
// rounding; BRepMesh discretizes each edge once, and Poly_PolygonOnTriangulation says which node
// of each face is the edge's k-th, so those nodes are made one vertex (and a degenerate edge's
// nodes, at a sphere's pole, one vertex with its B-rep vertex).

#include <algorithm>
#include <array>
#include <numeric>
#include <vector>

#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Tool.hxx>
#include <Poly_PolygonOnTriangulation.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>

#include "io/cad/occ.h"

namespace massprops::cad {
namespace {

class UnionFind {
 public:
  int Add() {
    parent_.push_back(static_cast<int>(parent_.size()));
    return parent_.back();
  }
  int Find(int a) {
    while (parent_[a] != a) a = parent_[a] = parent_[parent_[a]];
    return a;
  }
  // The smaller index stays the representative: the first face's node, the same every run.
  void Unite(int a, int b) {
    a = Find(a), b = Find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<int> parent_;
};

}  // namespace

CheckMesh Tessellate(const TopoDS_Shape& shape, double deflection, double angular_deflection, bool parallel) {
  BRepMesh_IncrementalMesh mesher(shape, deflection, false, angular_deflection, parallel);
  CheckMesh m;
  UnionFind nodes;
  std::vector<gp_Pnt> points;
  std::vector<std::array<int, 3>> triangles;
  TopTools_IndexedMapOfShape edges, vertices;
  std::vector<std::vector<int>> edge_nodes;  // per edge: its nodes, in the first face that meshed it
  std::vector<int> vertex_node;
  const auto vertex = [&](const TopoDS_Vertex& v) {
    const int k = vertices.Add(v);  // 1-based; the same index for the same vertex
    if (k > static_cast<int>(vertex_node.size()))
      vertex_node.push_back(nodes.Add()), points.push_back(BRep_Tool::Pnt(v));
    return vertex_node[static_cast<std::size_t>(k - 1)];
  };
  for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
    const TopoDS_Face& face = TopoDS::Face(e.Current());
    TopLoc_Location location;
    const Handle(Poly_Triangulation) t = BRep_Tool::Triangulation(face, location);
    if (t.IsNull() || t->NbTriangles() == 0) {
      ++m.untessellated;  // a hole in the check mesh, counted
      continue;
    }
    const gp_Trsf to_shape = location.Transformation();
    const int base = static_cast<int>(points.size());
    for (Standard_Integer n = 1; n <= t->NbNodes(); ++n) {
      nodes.Add();
      points.push_back(t->Node(n).Transformed(to_shape));
    }
    const auto node = [&](Standard_Integer n) { return base + n - 1; };
    for (TopExp_Explorer x(face, TopAbs_EDGE); x.More(); x.Next()) {
      const TopoDS_Edge& edge = TopoDS::Edge(x.Current());
      // The polygon of this side of the edge (a seam has one per side, both on this face).
      const Handle(Poly_PolygonOnTriangulation)& polygon = BRep_Tool::PolygonOnTriangulation(edge, t, location);
      if (polygon.IsNull() || polygon->NbNodes() < 2) continue;
      std::vector<int> ids;
      for (Standard_Integer j = 1; j <= polygon->NbNodes(); ++j) ids.push_back(node(polygon->Node(j)));
      if (BRep_Tool::Degenerated(edge)) {
        for (int id : ids) nodes.Unite(ids.front(), id);
      }
      TopoDS_Vertex first, last;
      TopExp::Vertices(edge, first, last);  // at the edge's first and last parameter
      if (!first.IsNull()) nodes.Unite(vertex(first), ids.front());
      if (!last.IsNull()) nodes.Unite(vertex(last), ids.back());
      const int k = edges.Add(edge);
      if (k > static_cast<int>(edge_nodes.size())) {
        edge_nodes.push_back(ids);
      } else if (edge_nodes[static_cast<std::size_t>(k - 1)].size() == ids.size()) {
        const std::vector<int>& other = edge_nodes[static_cast<std::size_t>(k - 1)];
        for (std::size_t j = 0; j < ids.size(); ++j) nodes.Unite(other[j], ids[j]);
      } else {
        ++m.unmatched_edges;
      }
    }
    const bool reversed = face.Orientation() == TopAbs_REVERSED;
    for (Standard_Integer i = 1; i <= t->NbTriangles(); ++i) {
      Standard_Integer a, b, c;
      t->Triangle(i).Get(a, b, c);
      if (reversed) std::swap(b, c);
      triangles.push_back({node(a), node(b), node(c)});
    }
  }
  // Each class of nodes one vertex, at its representative's position; triangles that the welding
  // collapsed (at a pole) are dropped: they have no area.
  std::vector<int> index(points.size(), -1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int r = nodes.Find(static_cast<int>(i));
    if (index[static_cast<std::size_t>(r)] < 0) {
      index[static_cast<std::size_t>(r)] = static_cast<int>(m.xyz.size() / 3);
      const gp_Pnt& p = points[static_cast<std::size_t>(r)];
      m.xyz.insert(m.xyz.end(), {p.X(), p.Y(), p.Z()});
    }
  }
  for (const auto& tri : triangles) {
    const int a = index[static_cast<std::size_t>(nodes.Find(tri[0]))];
    const int b = index[static_cast<std::size_t>(nodes.Find(tri[1]))];
    const int c = index[static_cast<std::size_t>(nodes.Find(tri[2]))];
    if (a == b || b == c || a == c) continue;
    m.tris.insert(m.tris.end(), {a, b, c});
  }
  return m;
}

}  // namespace massprops::cad
