// The picture of a result (massprops/report/picture.h) is right, not just present: the SVG is drawn
// to pixels (librsvg), the center-of-mass mark and the principal axes' ends are found by their
// colours, and each lies within 1 px of where this test's own projection of the closed-form
// numbers puts it, in every view where it is not hidden under another mark.

#include <unistd.h>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "massprops/io/load.h"
#include "massprops/report/picture.h"

namespace massprops {
namespace {

// The views as the header documents them (the test's own camera model).
struct View {
  std::string id;
  Vector3 right, up;
};
std::vector<View> DocumentedViews() {
  return {{"isometric", Vector3(1, 1, 0) / std::sqrt(2.0), Vector3(-1, 1, 2) / std::sqrt(6.0)},
          {"front", Vector3::UnitX(), Vector3::UnitZ()},
          {"top", Vector3::UnitX(), Vector3::UnitY()},
          {"right", Vector3::UnitY(), Vector3::UnitZ()}};
}

// A view's placement as the SVG states it: scale, the pixel of the origin, the origin.
struct Placement {
  Vector3 right, up, origin;
  double scale = 0;
  Eigen::Vector2d center;
  Eigen::Vector2d Px(const Vector3& x) const {
    return {center.x() + scale * right.dot(x - origin), center.y() - scale * up.dot(x - origin)};
  }
};

Vector3 Numbers3(const std::string& text) {
  Vector3 v;
  EXPECT_EQ(std::sscanf(text.c_str(), "%lf %lf %lf", &v[0], &v[1], &v[2]), 3) << text;
  return v;
}

Placement PlacementOf(const std::string& svg, const std::string& id) {
  const std::regex group("<g id='view-" + id +
                         "' data-view='[a-z]+' data-right='([^']*)' data-up='([^']*)' data-scale='([^']*)' "
                         "data-center='([^']*)' data-origin='([^']*)'>");
  std::smatch m;
  EXPECT_TRUE(std::regex_search(svg, m, group)) << "no view " << id;
  Placement p;
  p.right = Numbers3(m[1].str());
  p.up = Numbers3(m[2].str());
  p.scale = std::stod(m[3].str());
  std::sscanf(m[4].str().c_str(), "%lf %lf", &p.center.x(), &p.center.y());
  p.origin = Numbers3(m[5].str());
  return p;
}

// The centroid of the pixels within `tolerance` (RGB distance) of `colour`, within `radius` px of
// `near`; nothing when there are fewer than 12 such pixels.
std::optional<Eigen::Vector2d> FindMark(const report::Raster& image, const Vector3& colour, const Eigen::Vector2d& near,
                                        double radius, double tolerance = 40) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int count = 0;
  for (int y = std::max(0, static_cast<int>(near.y() - radius));
       y < std::min(image.height, static_cast<int>(near.y() + radius)); ++y) {
    for (int x = std::max(0, static_cast<int>(near.x() - radius));
         x < std::min(image.width, static_cast<int>(near.x() + radius)); ++x) {
      const std::uint8_t* p = &image.rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                                           static_cast<std::size_t>(x)) *
                                          4];
      if ((Vector3(p[0], p[1], p[2]) - colour).norm() > tolerance) continue;
      sum += Eigen::Vector2d(x + 0.5, y + 0.5);
      ++count;
    }
  }
  if (count < 12) return std::nullopt;
  return sum / count;
}

// An axis-aligned box a × b × c turned by R and moved by t, written as an OBJ object.
void WriteBox(std::ofstream& out, const std::string& name, const Vector3& size, const Matrix3& R, const Vector3& t,
              int& base) {
  out << "o " << name << "\n";
  for (int i = 0; i < 8; ++i) {
    const Vector3 c((i & 1 ? 0.5 : -0.5) * size.x(), (i & 2 ? 0.5 : -0.5) * size.y(), (i & 4 ? 0.5 : -0.5) * size.z());
    const Vector3 x = R * c + t;
    out.precision(17);
    out << "v " << x.x() << " " << x.y() << " " << x.z() << "\n";
  }
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    out << "f";
    for (int k : q) out << " " << base + k;
    out << "\n";
  }
  base += 8;
}

struct Expected {
  Vector3 com;
  Matrix3 axes;      // columns, moments ascending (closed form)
  Vector3 gyration;  // radii of gyration
};

// Finds every mark in every view and compares it with the projection of `want`.
void CheckMarks(const SolidResult& r, const Expected& want) {
  const std::string svg = report::PictureSvg(r);
  const report::Raster image = report::RasterizeSvg(svg);
  ASSERT_GT(image.width, 400);
  int checked = 0;
  for (const View& view : DocumentedViews()) {
    SCOPED_TRACE(view.id);
    const Placement p = PlacementOf(svg, view.id);
    EXPECT_LT((p.right - view.right).norm(), 1e-12);  // the views are the documented ones
    EXPECT_LT((p.up - view.up).norm(), 1e-12);
    const Eigen::Vector2d com = p.Px(want.com);
    std::vector<Eigen::Vector2d> marks = {com};
    std::vector<Eigen::Vector2d> ends;
    for (int i = 0; i < 3; ++i) {
      // The sign of an axis is the result's (either is right); the direction is the closed form's.
      const Vector3 e = want.axes.col(i) * (want.axes.col(i).dot(r.principal.axes.col(i)) < 0 ? -1.0 : 1.0);
      ends.push_back(p.Px(want.com + want.gyration[i] * e));
      marks.push_back(ends.back());
    }
    const auto found_com = FindMark(image, Vector3(255, 0, 255), com, 20);
    ASSERT_TRUE(found_com);
    EXPECT_LT((*found_com - com).norm(), 1.0) << found_com->transpose() << " vs " << com.transpose();
    ++checked;
    const Vector3 colours[3] = {Vector3(255, 0, 0), Vector3(0, 200, 0), Vector3(0, 0, 255)};
    for (int i = 0; i < 3; ++i) {
      bool clear = true;  // no other mark within 16 px: this one is whole in the picture
      for (std::size_t j = 0; j < marks.size(); ++j) {
        if (j != static_cast<std::size_t>(i) + 1 && (marks[j] - ends[static_cast<std::size_t>(i)]).norm() < 16)
          clear = false;
      }
      if (!clear) continue;
      const auto found = FindMark(image, colours[i], ends[static_cast<std::size_t>(i)], 20);
      ASSERT_TRUE(found) << "axis " << i + 1;
      EXPECT_LT((*found - ends[static_cast<std::size_t>(i)]).norm(), 1.0)
          << "axis " << i + 1 << ": " << found->transpose() << " vs " << ends[static_cast<std::size_t>(i)].transpose();
      ++checked;
    }
  }
  EXPECT_GE(checked, 12);  // the center in four views and most axes' ends
}

std::filesystem::path TempDir() {
  const auto dir = std::filesystem::temp_directory_path() / ("picture_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(Picture, TurnedBoxMarksWhereItsNumbersProject) {
  if (!report::CanRasterize()) GTEST_FAIL() << "built without librsvg";
  const Vector3 size(0.1, 0.2, 0.3), t(0.05, -0.02, 0.1);
  const Matrix3 R = (Eigen::AngleAxisd(0.5, Vector3::UnitZ()) * Eigen::AngleAxisd(0.3, Vector3::UnitX()) *
                     Eigen::AngleAxisd(-0.2, Vector3::UnitY()))
                        .toRotationMatrix();
  const auto dir = TempDir();
  const std::string file = (dir / "turned_box.obj").string();
  {
    std::ofstream out(file);
    int base = 1;
    WriteBox(out, "box", size, R, t, base);
  }
  const SolidResult r = LoadSolid(file);
  // A box's moments about its own axes: m (b² + c²) / 12 ...; the smallest about its longest side.
  Expected want;
  want.com = t;
  want.axes << R.col(2), R.col(1), R.col(0);  // about z (0.3): smallest moment, then y, then x
  want.gyration = Vector3(std::sqrt((0.01 + 0.04) / 12), std::sqrt((0.01 + 0.09) / 12), std::sqrt((0.04 + 0.09) / 12));
  CheckMarks(r, want);
  // The same picture through the file writer, as PNG and SVG, whole.
  report::WritePicture((dir / "box.png").string(), r);
  report::WritePicture((dir / "box.svg").string(), r);
  std::ifstream png((dir / "box.png").string(), std::ios::binary);
  char magic[8] = {};
  png.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
  EXPECT_THROW(report::WritePicture((dir / "box.jpg").string(), r), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "box.jpg"));
  std::filesystem::remove_all(dir);
}

TEST(Picture, AssemblyOfTwoBoxesMarksTheWholesCenter) {
  if (!report::CanRasterize()) GTEST_FAIL() << "built without librsvg";
  // Two axis-aligned boxes side by side: a 0.2 × 0.1 × 0.1 at the origin and a 0.1 cube at
  // x = 0.25, same density: the whole's center at x = (2 · 0 + 1 · 0.25) / 3.
  const auto dir = TempDir();
  const std::string file = (dir / "assembly.obj").string();
  {
    std::ofstream out(file);
    int base = 1;
    WriteBox(out, "plate", Vector3(0.2, 0.1, 0.1), Matrix3::Identity(), Vector3::Zero(), base);
    WriteBox(out, "cube", Vector3(0.1, 0.1, 0.1), Matrix3::Identity(), Vector3(0.25, 0, 0), base);
  }
  LoadOptions o;
  o.parts = true;
  const SolidResult r = LoadSolid(file, o);
  ASSERT_EQ(r.parts.size(), 2u);
  const double m = 1000 * (0.002 + 0.001), x = 0.25 / 3;
  // Each box about its own center, then moved to the whole's (parallel axes along x only).
  // Masses 2 kg and 1 kg; each box's moments m (b² + c²) / 12 about its center, moved to the
  // whole's center along x (parallel axes: y and z gain m d²).
  const double ixx = 2 * (0.01 + 0.01) / 12 + 1 * (0.01 + 0.01) / 12;
  const double iyy_plate = 2 * (0.04 + 0.01) / 12, iyy_cube = 1 * (0.01 + 0.01) / 12;
  const double shift = 2 * x * x + 1 * (0.25 - x) * (0.25 - x);
  const Vector3 I(ixx, iyy_plate + iyy_cube + shift, iyy_plate + iyy_cube + shift);  // kg·m²
  Expected want;
  want.com = Vector3(x, 0, 0);
  want.axes = Matrix3::Identity();  // moments ascending: x, then y and z (equal: either order)
  want.gyration = (I / 3).cwiseSqrt();
  ASSERT_NEAR(r.mp.mass, m, 1e-12);
  ASSERT_LT(I.x(), I.y());
  // y and z share a moment: the result may pick any pair in that plane; take its own there.
  want.axes.col(1) = r.principal.axes.col(1);
  want.axes.col(2) = r.principal.axes.col(2);
  EXPECT_NEAR(std::abs(r.principal.axes.col(1).x()), 0, 1e-9);
  CheckMarks(r, want);
  const std::string svg = report::PictureSvg(r);
  EXPECT_NE(svg.find(">plate</text>"), std::string::npos);  // the parts' key
  EXPECT_NE(svg.find(">cube</text>"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace massprops
