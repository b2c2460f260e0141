// The partitioned weld against the obvious one (an ordered map over all corners, in order): the
// same vertices in the same order, whatever the thread count, for corners spread over many chunks
// and partitions.

#include "io/weld.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <tuple>
#include <vector>

namespace massprops {
namespace {

using weld::PositionKey;

std::vector<PositionKey> Corners(std::size_t n, std::size_t pool, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<PositionKey> positions(pool);
  for (auto& p : positions) p = {u(rng), u(rng), u(rng)};
  positions[0] = {0.0, 0.5, -0.0};  // signed zeros are one position
  positions[1] = {-0.0, 0.5, 0.0};
  std::vector<PositionKey> out(n);
  std::size_t near = 0;
  for (std::size_t c = 0; c < n; ++c) {
    // Mostly near the previous corners (as faces in a file), sometimes anywhere.
    near = rng() % 8 == 0 ? rng() % pool : (near + rng() % 5) % pool;
    out[c] = positions[near];
  }
  return out;
}

template <typename Key>
void ExpectTheObviousWeld(const std::vector<Key>& corners);

// Binary STL's corners as they are stored (three floats each: weld::FloatKey), welded by the
// same equality as the doubles they convert to.
std::vector<weld::FloatKey> AsFloats(const std::vector<PositionKey>& corners) {
  std::vector<weld::FloatKey> out;
  for (const PositionKey& k : corners) {
    out.push_back({static_cast<float>(k.x), static_cast<float>(k.y), static_cast<float>(k.z)});
  }
  return out;
}

TEST(Weld, SameVerticesInOrderOfFirstAppearanceWhateverTheThreads) {
  ExpectTheObviousWeld(Corners(400000, 50000, 7));  // many chunks and partitions
  ExpectTheObviousWeld(Corners(3000, 500, 5));      // one chunk
  ExpectTheObviousWeld(AsFloats(Corners(400000, 50000, 7)));
  ExpectTheObviousWeld(AsFloats(Corners(3000, 500, 5)));
}

template <typename Key>
void ExpectTheObviousWeld(const std::vector<Key>& corners) {
  // The obvious weld.
  std::map<std::tuple<double, double, double>, std::int32_t> seen;
  std::vector<std::int32_t> expected(corners.size());
  std::vector<std::uint32_t> expected_first;
  for (std::size_t c = 0; c < corners.size(); ++c) {
    const Key& k = corners[c];
    auto z = [](double d) { return d == 0.0 ? 0.0 : d; };
    const auto [it, inserted] =
        seen.emplace(std::make_tuple(z(k.x), z(k.y), z(k.z)), static_cast<std::int32_t>(seen.size()));
    if (inserted) expected_first.push_back(static_cast<std::uint32_t>(c));
    expected[c] = it->second;
  }
  ASSERT_GT(corners.size(), 4 * expected_first.size());  // many corners per vertex
  for (int threads : {1, 2, 7}) {
    // Either hint (what the positions are like) gives the same weld.
    for (weld::Positions kind : {weld::Positions::kCorners, weld::Positions::kVertices}) {
      const weld::Grouping g = weld::GroupByPosition(
          corners.size(), [&](std::size_t c) { return corners[c]; }, threads, kind);
      EXPECT_EQ(g.first_non_finite, corners.size());
      EXPECT_EQ(g.vertex_of, expected) << threads << " threads";
      EXPECT_EQ(g.first_corner, expected_first) << threads << " threads";
    }
  }
}

// Triangles in strips, as files list them: most corners are at the position of one of the last
// few (the weld takes those without a lookup). The zero column is written as 0.0 and −0.0 in turn.
TEST(Weld, StripsOfTrianglesAsFilesListThem) {
  const int m = 300;  // 2 m² triangles, many chunks
  std::vector<PositionKey> corners;
  std::size_t written = 0;
  auto at = [&](int i, int j) {
    const double x = i == 0 ? (written++ % 2 == 0 ? 0.0 : -0.0) : 0.01 * i;
    return PositionKey{x, 0.01 * j, 0.0};
  };
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      for (const PositionKey& k : {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)})
        corners.push_back(k);
    }
  }
  ExpectTheObviousWeld(corners);
  ExpectTheObviousWeld(AsFloats(corners));
}

TEST(Weld, FindsTheFirstNonFiniteCorner) {
  std::vector<PositionKey> corners = Corners(200000, 1000, 3);
  corners[150001].y = std::numeric_limits<double>::infinity();
  corners[70000].z = std::nan("");
  const weld::Grouping g = weld::GroupByPosition(
      corners.size(), [&](std::size_t c) { return corners[c]; }, 2);
  EXPECT_EQ(g.first_non_finite, 70000u);
  // A non-finite position repeated right after itself: the first of them.
  corners[70000] = corners[69999];
  corners[90000].x = std::numeric_limits<double>::infinity();
  corners[90001] = corners[90000];
  corners[90003] = corners[90000];
  EXPECT_EQ(weld::GroupByPosition(
                corners.size(), [&](std::size_t c) { return corners[c]; }, 2)
                .first_non_finite,
            90000u);
  const std::vector<weld::FloatKey> floats = AsFloats(corners);  // as a binary STL stores them
  EXPECT_EQ(weld::GroupByPosition(
                floats.size(), [&](std::size_t c) { return floats[c]; }, 2)
                .first_non_finite,
            90000u);
  // A vertex list: every position an entry of its chunk; the first non-finite one on any thread.
  for (int threads : {1, 2}) {
    EXPECT_EQ(weld::GroupByPosition(
                  corners.size(), [&](std::size_t c) { return corners[c]; }, threads, weld::Positions::kVertices)
                  .first_non_finite,
              90000u);
  }
  // A vertex list of one chunk (its own path): the first non-finite vertex, not a later one.
  std::vector<PositionKey> list = Corners(3000, 3000, 1);
  list[2500].x = std::numeric_limits<double>::infinity();
  list[1700].y = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(weld::GroupByPosition(
                list.size(), [&](std::size_t c) { return list[c]; }, 1, weld::Positions::kVertices)
                .first_non_finite,
            1700u);
}

}  // namespace
}  // namespace massprops
