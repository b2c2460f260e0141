#pragma once
/// @file
/// One bounding-box hierarchy, for every tree of boxes in the project: the winding number's
/// hierarchy of triangles and its plane-projected tree for counting ray crossings (core), and the
/// mesh field's tree of triangles for closest distances and ray hits (libdynamics).
///
/// Items (triangles, usually) are ordered so that every node holds a contiguous range of `order`;
/// a node splits at the median of its items' centroids along the longest side of their box (ties
/// broken by item index, so the tree is the same on every machine) until it holds at most
/// `leaf_size` items. Optionally, items that `stays` says are too large for the node's spread stay
/// at the node itself (`own` of them at the front of its range) instead of widening every node on
/// their way down.

#include <algorithm>
#include <numeric>
#include <vector>

#include <Eigen/Geometry>

namespace massprops {

template <int Dim>
struct BoxTree {
  using Box = Eigen::AlignedBox<double, Dim>;
  using Point = Eigen::Matrix<double, Dim, 1>;
  struct Node {
    Box box;        ///< holds every item of the node
    int first = 0;  ///< its items: order[first, first + count)
    int count = 0;
    int own = 0;    ///< the first `own` of them are held here, not below (a leaf: all of them)
    int left = -1;  ///< children (both −1 for a leaf)
    int right = -1;
    bool leaf() const { return left < 0; }
  };
  std::vector<int> order;   ///< item indices
  std::vector<Node> nodes;  ///< nodes[0] is the root
};

namespace box_tree {
/// No item stays above the leaves.
struct NoneStay {
  template <typename Box>
  bool operator()(int, const Box&) const {
    return false;
  }
};
/// Nothing to compute per node.
struct NoNodeData {
  template <typename Tree>
  void operator()(const Tree&, int, int, int) const {}
};
}  // namespace box_tree

/// Builds the hierarchy of `n` items. `box_of(i)` is item i's box, `centroid_of(i)` the point it is
/// sorted by. `on_node(tree, index, first, count)` is called for each node before its items are
/// reordered (for sums over a node's items in a fixed order). `stays(i, centroid_box)`: whether
/// item i stays at a node whose items' centroids span `centroid_box`.
template <int Dim, typename BoxOf, typename CentroidOf, typename OnNode = box_tree::NoNodeData,
          typename Stays = box_tree::NoneStay>
BoxTree<Dim> BuildBoxTree(int n, int leaf_size, const BoxOf& box_of, const CentroidOf& centroid_of,
                          const OnNode& on_node = {}, const Stays& stays = {}) {
  using Tree = BoxTree<Dim>;
  Tree tree;
  tree.order.resize(static_cast<std::size_t>(n));
  std::iota(tree.order.begin(), tree.order.end(), 0);
  tree.nodes.reserve(static_cast<std::size_t>(2 * n / std::max(leaf_size, 1) + 8));
  auto item = [&tree](int i) { return tree.order[static_cast<std::size_t>(i)]; };
  auto build = [&](auto& self, int first, int count) -> int {
    const int index = static_cast<int>(tree.nodes.size());
    tree.nodes.emplace_back();
    typename Tree::Node node;
    node.first = first;
    node.count = count;
    node.own = count;
    typename Tree::Box centroids;
    for (int i = first; i < first + count; ++i) {
      node.box.extend(box_of(item(i)));
      centroids.extend(centroid_of(item(i)));
    }
    tree.nodes[static_cast<std::size_t>(index)] = node;
    on_node(tree, index, first, count);
    if (count > leaf_size) {
      const auto begin = tree.order.begin() + first, end = begin + count;
      const int own =
          static_cast<int>(std::stable_partition(begin, end, [&](int f) { return stays(f, centroids); }) - begin);
      const int below = count - own, start = first + own;
      if (below > leaf_size) {
        typename Tree::Box rest;
        for (int i = start; i < first + count; ++i) rest.extend(centroid_of(item(i)));
        int axis = 0;
        rest.sizes().maxCoeff(&axis);
        const int mid = start + below / 2;
        std::nth_element(tree.order.begin() + start, tree.order.begin() + mid, end, [&](int p, int q) {
          const double cp = centroid_of(p)[axis], cq = centroid_of(q)[axis];
          return cp < cq || (cp == cq && p < q);
        });
        node.own = own;
        node.left = self(self, start, mid - start);
        node.right = self(self, mid, first + count - mid);
      }
    }
    tree.nodes[static_cast<std::size_t>(index)].own = node.own;
    tree.nodes[static_cast<std::size_t>(index)].left = node.left;
    tree.nodes[static_cast<std::size_t>(index)].right = node.right;
    return index;
  };
  if (n > 0) build(build, 0, n);
  return tree;
}

}  // namespace massprops
