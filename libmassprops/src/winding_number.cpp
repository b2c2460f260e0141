// The generalized winding number of a triangle mesh (Jacobson, Kavan & Sorkine-Hornung 2013),
// evaluated hierarchically: exact solid angles (Van Oosterom & Strackee 1983) for triangles near
// the query point, the dipole (first-order) term of each far cluster of a bounding volume
// hierarchy (Barill, Dickson, Schmidt, Levin & Jacobson 2018).
//
// A closed, consistently oriented mesh has an integer winding number, which the signed count of
// the faces a ray from the point crosses gives exactly — and in O(log n), where the hierarchy
// must evaluate every nearby triangle exactly: slivers (the side faces of a prism over a polygon
// of 10^6 corners) keep every cluster near the points beside them (0.5 ms per point). Points where
// the count is not certified (on or within rounding of an edge or face) take the hierarchy.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <string>

#include "massprops/implicit.h"
#include "massprops/mesh_topology.h"

#include "certain_predicates.h"

namespace massprops::implicit {
namespace {

constexpr int kLeafSize = 8;
constexpr double kFourPi = 4.0 * M_PI;

struct Node {
  AlignedBox3 box;
  Vector3 center = Vector3::Zero();       // area-weighted centroid of its triangles
  Vector3 vector_area = Vector3::Zero();  // Σ ½ (b−a)×(c−a)
  double radius = 0;                      // of the ball about center that holds its triangles
  int first = 0, count = 0;               // its triangles: order[first, first+count)
  int own = 0;                            // the first `own` of them are held here, not below
  int left = -1, right = -1;
};

// The signed number of faces a ray from x crosses, along the coordinate axis across which the
// faces' bounding boxes cover the least area (the cost of a query): faces seen counterclockwise
// from ahead count +1 (the ray leaves through them), the others −1, and faces parallel to the ray
// (no area across it) none. Faces are found through a bounding-box hierarchy of their projections
// on the plane across the ray. Coordinates are permuted, not rotated: the counts are exact.
class CrossingCounter {
 public:
  CrossingCounter(const VertexMatrix& V, const FaceMatrix& F) : F_(F) {
    Vector3 area = Vector3::Zero();  // Σ of the faces' box areas across each axis
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      Vector3 lo = V.row(F(f, 0)).transpose(), hi = lo;
      for (int k = 1; k < 3; ++k) {
        lo = lo.cwiseMin(V.row(F(f, k)).transpose());
        hi = hi.cwiseMax(V.row(F(f, k)).transpose());
      }
      const Vector3 size = hi - lo;
      area += Vector3(size[1] * size[2], size[2] * size[0], size[0] * size[1]);
    }
    int along;
    area.minCoeff(&along);
    axes_ = {(along + 1) % 3, (along + 2) % 3, along};  // (u, v, w): across the ray, and along it
    P_.resize(V.rows(), 3);
    for (Eigen::Index i = 0; i < V.rows(); ++i) P_.row(i) << V(i, axes_[0]), V(i, axes_[1]), V(i, axes_[2]);
    const auto nf = static_cast<int>(F.rows());
    order_.resize(static_cast<std::size_t>(nf));
    std::iota(order_.begin(), order_.end(), 0);
    nodes_.reserve(static_cast<std::size_t>(2 * nf / kLeafSize + 8));
    Build(0, nf);
  }

  // The crossing count, or false when a test along the way is not certified.
  bool Count(const Vector3& x, double& count) const {
    const double qp[3] = {x[axes_[0]], x[axes_[1]], x[axes_[2]]};
    const double* q = qp;
    int total = 0;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Box2& n = nodes_[static_cast<std::size_t>(stack[--top])];
      if (q[0] < n.lo[0] || q[0] > n.hi[0] || q[1] < n.lo[1] || q[1] > n.hi[1]) continue;
      if (n.left >= 0) {
        if (top + 2 > 128) return false;
        stack[top++] = n.left;
        stack[top++] = n.right;
      }
      for (int i = n.first; i < n.first + n.own; ++i) {
        const int f = order_[static_cast<std::size_t>(i)];
        const double* a = &P_(F_(f, 0), 0);
        const double* b = &P_(F_(f, 1), 0);
        const double* c = &P_(F_(f, 2), 0);
        const int s1 = internal::CertainOrient2d(a[0], a[1], b[0], b[1], q[0], q[1]);
        const int s2 = internal::CertainOrient2d(b[0], b[1], c[0], c[1], q[0], q[1]);
        const int s3 = internal::CertainOrient2d(c[0], c[1], a[0], a[1], q[0], q[1]);
        if ((s1 > 0 || s2 > 0 || s3 > 0) && (s1 < 0 || s2 < 0 || s3 < 0)) continue;  // outside
        if (s1 == 0 || s2 == 0 || s3 == 0) return false;                             // on an edge, within rounding
        const int ahead = internal::CertainOrient3d(a, b, c, qp) * s1;               // > 0: the face is ahead
        if (ahead == 0) return false;                                                // on the face, within rounding
        if (ahead > 0) total += s1;
      }
    }
    count = total;
    return true;
  }

 private:
  struct Box2 {
    double lo[2], hi[2];
    int first = 0, own = 0;  // a leaf's faces: order[first, first+own)
    int left = -1, right = -1;
  };

  int Build(int first, int count) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Box2 node;
    node.first = first;
    node.own = count;
    node.lo[0] = node.lo[1] = std::numeric_limits<double>::infinity();
    node.hi[0] = node.hi[1] = -std::numeric_limits<double>::infinity();
    double clo[2] = {node.lo[0], node.lo[1]}, chi[2] = {node.hi[0], node.hi[1]};
    for (int i = first; i < first + count; ++i) {
      const int f = order_[static_cast<std::size_t>(i)];
      for (int d = 0; d < 2; ++d) {
        double sum = 0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (int k = 0; k < 3; ++k) {
          const double p = P_(F_(f, k), d);
          lo = std::min(lo, p);
          hi = std::max(hi, p);
          sum += p;
        }
        node.lo[d] = std::min(node.lo[d], lo);
        node.hi[d] = std::max(node.hi[d], hi);
        clo[d] = std::min(clo[d], sum);
        chi[d] = std::max(chi[d], sum);
      }
    }
    if (count > kLeafSize) {
      const int axis = chi[1] - clo[1] > chi[0] - clo[0] ? 1 : 0;
      const int mid = first + count / 2;
      auto key = [&](int f) { return P_(F_(f, 0), axis) + P_(F_(f, 1), axis) + P_(F_(f, 2), axis); };
      std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + first + count,
                       [&](int p, int q) { return key(p) < key(q) || (key(p) == key(q) && p < q); });
      node.own = 0;
      node.left = Build(first, mid - first);
      node.right = Build(mid, first + count - mid);
    }
    nodes_[static_cast<std::size_t>(index)] = node;
    return index;
  }

  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> P_;
  const FaceMatrix& F_;
  std::array<int, 3> axes_{};
  std::vector<int> order_;
  std::vector<Box2> nodes_;
};

class WindingSolid final : public ImplicitSolid {
 public:
  WindingSolid(const TriangleMesh& mesh, Scalar beta) : V_(mesh.V), F_(mesh.F), beta_(beta) {
    if (F_.rows() == 0) throw std::invalid_argument("winding number: the mesh has no triangles");
    if (!(std::isfinite(beta) && beta > 1)) throw std::invalid_argument("winding number: beta must be > 1");
    for (Eigen::Index i = 0; i < V_.rows(); ++i) {
      if (!V_.row(i).allFinite())
        throw std::invalid_argument("winding number: vertex " + std::to_string(i) + " is not finite");
    }
    for (Eigen::Index f = 0; f < F_.rows(); ++f) {
      for (int k = 0; k < 3; ++k) {
        if (F_(f, k) < 0 || F_(f, k) >= V_.rows()) {
          throw std::invalid_argument("winding number: triangle " + std::to_string(f) + " refers to vertex " +
                                      std::to_string(F_(f, k)) + " of " + std::to_string(V_.rows()));
        }
      }
    }
    for (Eigen::Index i = 0; i < V_.rows(); ++i) bounds_.extend(Vector3(V_.row(i)));
    // Closed and consistently oriented: the winding number is an integer, counted exactly.
    if (AnalyzeTopology(ToPolygonMesh(mesh)).BoundsVolume()) {
      crossing_ = std::make_unique<CrossingCounter>(V_, F_);  // the hierarchy waits until needed
    } else {
      BuildHierarchy();
    }
  }

  // Only the side of 1/2 matters: where the quick evaluation lands near it, evaluate again with
  // four times the radius of exact treatment (the dipole error falls as 1/beta²: measured 0.05 at
  // beta = 2 and 6e-4 at 8 on a torus), so the decision is that of the accurate sum.
  Scalar Value(const Vector3& x) const override {
    double count = 0;
    if (crossing_ && crossing_->Count(x, count)) return 0.5 - count;
    const double w = Winding(x, beta_);
    if (std::abs(w - 0.5) > 0.15) return 0.5 - w;
    return 0.5 - Winding(x, 4 * beta_);
  }
  AlignedBox3 Bounds() const override { return bounds_; }
  std::string Describe() const override {
    return "winding number of a mesh (" + std::to_string(F_.rows()) + " triangles)";
  }

  double Winding(const Vector3& x) const { return Winding(x, beta_); }
  double Winding(const Vector3& x, double beta) const {
    std::call_once(built_, [this] { const_cast<WindingSolid*>(this)->BuildHierarchy(); });
    double omega = 0;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[static_cast<std::size_t>(stack[--top])];
      const Vector3 d = n.center - x;
      const double dist = d.norm();
      if (dist > beta * n.radius) {
        omega += n.vector_area.dot(d) / (dist * dist * dist);
      } else if (n.left < 0) {
        for (int i = n.first; i < n.first + n.count; ++i) omega += SolidAngle(order_[static_cast<std::size_t>(i)], x);
      } else {
        for (int i = n.first; i < n.first + n.own; ++i) omega += SolidAngle(order_[static_cast<std::size_t>(i)], x);
        if (top + 2 > 128) throw std::logic_error("winding number: hierarchy too deep");
        stack[top++] = n.left;
        stack[top++] = n.right;
      }
    }
    return omega / kFourPi;
  }

 private:
  Vector3 Corner(int f, int k) const { return V_.row(F_(f, k)); }

  double SolidAngle(int f, const Vector3& x) const {
    const Vector3 a = Corner(f, 0) - x, b = Corner(f, 1) - x, c = Corner(f, 2) - x;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double num = a.dot(b.cross(c));
    const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    return 2.0 * std::atan2(num, den);
  }

  void BuildHierarchy() {
    const auto nf = static_cast<int>(F_.rows());
    order_.resize(static_cast<std::size_t>(nf));
    std::iota(order_.begin(), order_.end(), 0);
    centroids_.resize(static_cast<std::size_t>(nf));
    for (int f = 0; f < nf; ++f)
      centroids_[static_cast<std::size_t>(f)] = (Corner(f, 0) + Corner(f, 1) + Corner(f, 2)) / 3.0;
    nodes_.reserve(static_cast<std::size_t>(2 * nf / kLeafSize + 8));
    Build(0, nf);
  }

  int Build(int first, int count) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Node node;
    node.first = first;
    node.count = count;
    double area = 0;
    Vector3 weighted = Vector3::Zero();
    AlignedBox3 cbox;
    for (int i = first; i < first + count; ++i) {
      const int f = order_[static_cast<std::size_t>(i)];
      const Vector3 a = Corner(f, 0), b = Corner(f, 1), c = Corner(f, 2);
      const Vector3 va = 0.5 * (b - a).cross(c - a);
      node.vector_area += va;
      const double A = va.norm();
      area += A;
      weighted += A * centroids_[static_cast<std::size_t>(f)];
      node.box.extend(a);
      node.box.extend(b);
      node.box.extend(c);
      cbox.extend(centroids_[static_cast<std::size_t>(f)]);
    }
    node.center = area > 0 ? Vector3(weighted / area) : node.box.center();
    for (int k = 0; k < 8; ++k) {
      node.radius =
          std::max(node.radius, (node.box.corner(static_cast<AlignedBox3::CornerType>(k)) - node.center).norm());
    }
    if (count > kLeafSize) {
      // Triangles larger than the spread of the node's centroids stay here, evaluated exactly
      // whenever the node is near: pushed down, each would widen every node on its way to a leaf,
      // and the triangles there would all be evaluated exactly too (a balanced split of a polygon of
      // 10^6 corners has such triangles at every scale; sampling inside took 0.5 ms per point).
      const double spread = cbox.sizes().maxCoeff();
      const auto large = [&](int f) {
        AlignedBox3 b;
        for (int k = 0; k < 3; ++k) b.extend(Corner(f, k));
        return b.sizes().maxCoeff() > spread;
      };
      node.own = static_cast<int>(std::stable_partition(order_.begin() + first, order_.begin() + first + count, large) -
                                  (order_.begin() + first));
      const int below = count - node.own, start = first + node.own;
      if (below > kLeafSize) {
        AlignedBox3 rest;
        for (int i = start; i < first + count; ++i)
          rest.extend(centroids_[static_cast<std::size_t>(order_[static_cast<std::size_t>(i)])]);
        int axis;
        rest.sizes().maxCoeff(&axis);
        const int mid = start + below / 2;
        std::nth_element(order_.begin() + start, order_.begin() + mid, order_.begin() + first + count,
                         [&](int p, int q) {
                           const double cp = centroids_[static_cast<std::size_t>(p)][axis],
                                        cq = centroids_[static_cast<std::size_t>(q)][axis];
                           return cp < cq || (cp == cq && p < q);
                         });
        node.left = Build(start, mid - start);
        node.right = Build(mid, first + count - mid);
      } else {
        node.own = 0;  // a leaf after all: all its triangles evaluated exactly when near
      }
    }
    nodes_[static_cast<std::size_t>(index)] = node;
    return index;
  }

  VertexMatrix V_;
  FaceMatrix F_;
  Scalar beta_;
  std::vector<int> order_;
  std::vector<Vector3> centroids_;
  std::vector<Node> nodes_;
  AlignedBox3 bounds_;
  std::unique_ptr<CrossingCounter> crossing_;  // closed, consistent meshes
  mutable std::once_flag built_;               // the hierarchy: at once for other meshes
};

}  // namespace

ImplicitPtr WindingNumberSolid(const TriangleMesh& mesh, Scalar beta) {
  return std::make_shared<WindingSolid>(mesh, beta);
}

Scalar WindingNumber(const ImplicitSolid& solid, const Vector3& x) {
  const auto* w = dynamic_cast<const WindingSolid*>(&solid);
  if (!w) throw std::invalid_argument("WindingNumber: not a winding-number solid");
  return w->Winding(x);
}

}  // namespace massprops::implicit
