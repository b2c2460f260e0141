// The shape syntax (implicit::ParseShape) in isolation: what each form builds, checked by the sign
// of φ at points whose side is known from the closed form, and the faults it names.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "massprops/implicit.h"

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
