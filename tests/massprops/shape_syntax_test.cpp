// The shape syntax (implicit::ParseShape) in isolation: what each form builds, checked by the sign
// of φ at points whose side is known from the closed form, and the faults it names.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "massprops/implicit.h"
#include "massprops/primitive.h"

namespace massprops {
namespace {

using ::testing::HasSubstr;

bool In(const ImplicitPtr& s, double x, double y, double z) { return s->Inside(Vector3(x, y, z)); }

TEST(ShapeSyntax, Primitives) {
  const ImplicitPtr sphere = implicit::ParseShape("sphere(r=2)");
  EXPECT_TRUE(In(sphere, 1.99, 0, 0));
  EXPECT_FALSE(In(sphere, 2.01, 0, 0));
  const ImplicitPtr box = implicit::ParseShape("box(x=2, y=4, z=6)");  // full sizes, centred
  EXPECT_TRUE(In(box, 0.99, 1.99, 2.99));
  EXPECT_FALSE(In(box, 1.01, 0, 0));
  EXPECT_FALSE(In(box, 0, 0, 3.01));
  const ImplicitPtr torus = implicit::ParseShape("torus(R=1, r=0.25)");
  EXPECT_TRUE(In(torus, 1.2, 0, 0));
  EXPECT_FALSE(In(torus, 0, 0, 0));  // the hole
  EXPECT_FALSE(In(torus, 1.0, 0, 0.26));
  const ImplicitPtr cylinder = implicit::ParseShape("cylinder(r=1, h=2)");
  EXPECT_TRUE(In(cylinder, 0.99, 0, 0.99));
  EXPECT_FALSE(In(cylinder, 0, 0, 1.01));
  const ImplicitPtr capsule = implicit::ParseShape("capsule(r=0.5, h=2)");  // h: the cylinder part
  EXPECT_TRUE(In(capsule, 0, 0, 1.49));
  EXPECT_FALSE(In(capsule, 0, 0, 1.51));
}

TEST(ShapeSyntax, CsgAndMotions) {
  const ImplicitPtr hollow = implicit::ParseShape("difference(sphere(r=2), sphere(r=1))");
  EXPECT_FALSE(In(hollow, 0, 0, 0));
  EXPECT_TRUE(In(hollow, 1.5, 0, 0));
  const ImplicitPtr both = implicit::ParseShape("union(sphere(r=1), move(sphere(r=1), x=3))");
  EXPECT_TRUE(In(both, 0, 0, 0));
  EXPECT_TRUE(In(both, 3, 0, 0));
  EXPECT_FALSE(In(both, 1.5, 0, 0));
  const ImplicitPtr lens = implicit::ParseShape("intersection(move(sphere(r=1), x=0.5), move(sphere(r=1), x=-0.5))");
  EXPECT_TRUE(In(lens, 0, 0, 0));
  EXPECT_FALSE(In(lens, 0.9, 0, 0));
  // A 2 × 0.2 × 0.2 bar turned 90° about z lies along y.
  const ImplicitPtr turned = implicit::ParseShape("rotate(box(x=2, y=0.2, z=0.2), axis=[0,0,1], deg=90)");
  EXPECT_TRUE(In(turned, 0, 0.9, 0));
  EXPECT_FALSE(In(turned, 0.9, 0, 0));
  const ImplicitPtr big = implicit::ParseShape("scale(sphere(r=1), s=3)");
  EXPECT_TRUE(In(big, 2.9, 0, 0));
  EXPECT_FALSE(In(big, 3.1, 0, 0));
}

TEST(ShapeSyntax, DescribeParsesBackToTheSameSolid) {
  for (const char* text : {"sphere(r=1)", "difference(box(x=1, y=2, z=3), cylinder(r=0.25, h=4))",
                           "move(rotate(torus(R=1, r=0.25), axis=[1,0,0], deg=30), x=1, y=2, z=3)"}) {
    const ImplicitPtr a = implicit::ParseShape(text);
    const ImplicitPtr b = implicit::ParseShape(a->Describe());
    for (int i = 0; i < 200; ++i) {  // points on a fixed lattice through the bounds
      const AlignedBox3 box = a->Bounds();
      const Vector3 f((i % 7) / 6.0, ((i / 7) % 7) / 6.0, ((i / 49) % 5) / 4.0);
      const Vector3 x = box.min() + f.cwiseProduct(box.max() - box.min());
      EXPECT_EQ(a->Inside(x), b->Inside(x)) << text << " vs " << a->Describe();
    }
  }
}

// The one table of primitives' names and sizes (primitive.h): every primitive has its keys in the
// shape syntax and in scenes, and the sizes they give make the primitive named, with the closed
// form of those sizes.
TEST(ShapeSyntax, OneTableOfPrimitiveSizes) {
  for (const char* name : kPrimitiveNames) {
    for (const SizeSyntax syntax : {SizeSyntax::kShapeSyntax, SizeSyntax::kScene}) {
      const std::vector<SizeKey>& keys = SizeKeys(name, syntax);
      ASSERT_FALSE(keys.empty()) << name;
      std::vector<double> sizes;
      for (const SizeKey& k : keys) sizes.insert(sizes.end(), static_cast<std::size_t>(k.components), 0.0);
      // Sizes 1, 0.5, 0.25, ... in order: a valid torus (minor below major) and positive elsewhere.
      for (std::size_t i = 0; i < sizes.size(); ++i) sizes[i] = std::ldexp(1.0, -static_cast<int>(i));
      const Primitive p = MakePrimitive(name, sizes);
      EXPECT_STREQ(PrimitiveName(p), name);
      EXPECT_GT(ClosedForm(p, 1.0).volume, 0) << name;
    }
  }
  EXPECT_TRUE(SizeKeys("torus", SizeSyntax::kRobot).empty());  // URDF and SDFormat have none
  EXPECT_EQ(SizeKeys("cylinder", SizeSyntax::kRobot)[1].key, std::string("length"));
  EXPECT_EQ(SizeKeys("cylinder", SizeSyntax::kScene)[1].key, std::string("height"));
  EXPECT_THROW(MakePrimitive("prism", {1.0}), std::invalid_argument);
  EXPECT_THROW(MakePrimitive("box", {1.0, 2.0}), std::invalid_argument);
  // The same solid by each syntax: a 1 × 2 × 3 box from the shape syntax and from the table.
  const MassProperties a = ClosedForm(MakePrimitive("box", {1, 2, 3}), 1.0);
  EXPECT_DOUBLE_EQ(a.volume, 6.0);
  EXPECT_TRUE(implicit::ParseShape("box(x=1, y=2, z=3)")->Inside(Vector3(0.49, 0.99, 1.49)));
}

TEST(ShapeSyntax, FaultsNameThePlace) {
  const auto fault = [](const std::string& text) {
    try {
      implicit::ParseShape(text);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(fault("torus(R=1)"), HasSubstr("missing r="));
  EXPECT_THAT(fault("sphere(r=-1)"), HasSubstr("sphere"));
  EXPECT_THAT(fault("sphre(r=1)"), HasSubstr("character"));
  EXPECT_THAT(fault("sphere(r=1"), HasSubstr("character"));
  EXPECT_THAT(fault("sphere(r=1) extra"), HasSubstr("character"));
  EXPECT_THAT(fault("grid(file=\"part.sdf\")"), HasSubstr("grid"));  // no file reader: the core opens no file
  EXPECT_THAT(fault("torus(R=0.2, r=0.25)"), HasSubstr("torus"));    // minor above major
}

}  // namespace
}  // namespace massprops
