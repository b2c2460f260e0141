// The generalized winding number of a triangle mesh (Jacobson, Kavan & Sorkine-Hornung 2013),
// evaluated hierarchically: exact solid angles (Van Oosterom & Strackee 1983) for triangles near
// the query point, the dipole (first-order) term of each far cluster of a bounding volume
// hierarchy (Barill, Dickson, Schmidt, Levin & Jacobson 2018).

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "massprops/implicit.h"

namespace massprops::implicit {
namespace {

constexpr int kLeafSize = 8;
constexpr double kFourPi = 4.0 * M_PI;

struct Node {
  AlignedBox3 box;
  Vector3 center = Vector3::Zero();       // area-weighted centroid of its triangles
  Vector3 vector_area = Vector3::Zero();  // Σ ½ (b−a)×(c−a)
  double radius = 0;                      // of the ball about center that holds its triangles
  int first = 0, count = 0;               // leaf: triangles order[first, first+count)
  int left = -1, right = -1;
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
    const auto nf = static_cast<int>(F_.rows());
    order_.resize(static_cast<std::size_t>(nf));
    std::iota(order_.begin(), order_.end(), 0);
    centroids_.resize(static_cast<std::size_t>(nf));
    for (int f = 0; f < nf; ++f)
      centroids_[static_cast<std::size_t>(f)] = (Corner(f, 0) + Corner(f, 1) + Corner(f, 2)) / 3.0;
    nodes_.reserve(static_cast<std::size_t>(2 * nf / kLeafSize + 8));
    Build(0, nf);
    for (Eigen::Index i = 0; i < V_.rows(); ++i) bounds_.extend(Vector3(V_.row(i)));
  }

  // Only the side of 1/2 matters: where the quick evaluation lands near it, evaluate again with
  // four times the radius of exact treatment (the dipole error falls as 1/beta²: measured 0.05 at
  // beta = 2 and 6e-4 at 8 on a torus), so the decision is that of the accurate sum.
  Scalar Value(const Vector3& x) const override {
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
      int axis;
      cbox.sizes().maxCoeff(&axis);
      const int mid = first + count / 2;
      std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + first + count, [&](int p, int q) {
        const double cp = centroids_[static_cast<std::size_t>(p)][axis],
                     cq = centroids_[static_cast<std::size_t>(q)][axis];
        return cp < cq || (cp == cq && p < q);
      });
      node.left = Build(first, mid - first);
      node.right = Build(mid, first + count - mid);
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
