// Friction as Coulomb's law says it for the whole contact (dynamics/contact.h, the friction patch):
// boxes of many shapes at rest on inclines just below μs stay put, just above it slide at the
// kinetic rate from the first step, on a tilted ground, a static box ramp and a static mesh ramp;
// pushes just below and above μs m g; Coulomb's hysteresis at a landing; torsion at the
// uniform-pressure limit; sliding over a static mesh's internal edges; cylinders rolling down
// static ramps. Every figure is a closed form written here.

#include <cmath>
#include <functional>
#include <random>

#include <gtest/gtest.h>

#include "dynamics/contact.h"

namespace dynamics {
namespace {

constexpr double kG = 9.81;
constexpr double kH = 1e-3;  // the step

Material Mat(double mu_s, double mu_k) { return Material{mu_s, mu_k, 0}; }

RigidBody BoxBody(const Vector3& half, double density) {
  RigidBody b;
  const Vector3 s = 2 * half;
  b.mass = density * s.prod();
  b.inertia = Vector3(s[1] * s[1] + s[2] * s[2], s[0] * s[0] + s[2] * s[2], s[0] * s[0] + s[1] * s[1]) * (b.mass / 12);
  return b;
}

// Steps n times; the total energy never rises (contact is dissipative; no pushes happen here).
void Simulate(ContactWorld& w, int n, const std::function<void(int)>& each = nullptr) {
  double energy = w.world().Diagnose().total_energy;
  for (int i = 0; i < n; ++i) {
    const StepStatus s = w.Step(kH);
    ASSERT_TRUE(s.ok) << s.message;
    const double now = w.world().Diagnose().total_energy;
    ASSERT_LE(now, energy + 1e-9 * std::max(1.0, std::abs(energy))) << "energy rose at step " << i;
    energy = now;
    if (each) each(i);
  }
}

// A closed slab [-lx, lx] × [-ly, ly] × [-t, 0] whose top and bottom are grids of nx × ny squares,
// each split into two triangles along a diagonal drawn at random (seeded): flat, but full of
// internal edges in every direction.
shape::Mesh Slab(double lx, double ly, double t, int nx, int ny, unsigned seed) {
  std::vector<Vector3> v;
  std::vector<std::array<int, 3>> f;
  auto id = [&](int i, int j, int layer) { return layer * (nx + 1) * (ny + 1) + j * (nx + 1) + i; };
  for (int layer = 0; layer < 2; ++layer) {
    for (int j = 0; j <= ny; ++j) {
      for (int i = 0; i <= nx; ++i) v.emplace_back(-lx + 2 * lx * i / nx, -ly + 2 * ly * j / ny, layer == 0 ? 0.0 : -t);
    }
  }
  std::mt19937 rng(seed);
  for (int layer = 0; layer < 2; ++layer) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const int a = id(i, j, layer), b = id(i + 1, j, layer), c = id(i + 1, j + 1, layer), d = id(i, j + 1, layer);
        std::array<std::array<int, 3>, 2> tri = (rng() & 1) ? std::array<std::array<int, 3>, 2>{{{a, b, c}, {a, c, d}}}
                                                            : std::array<std::array<int, 3>, 2>{{{a, b, d}, {b, c, d}}};
        for (auto& x : tri) {
          if (layer == 1) std::swap(x[1], x[2]);  // the bottom faces down
          f.push_back(x);
        }
      }
    }
  }
  // The sides: a quad between each boundary edge of the top and the bottom, outward.
  auto side = [&](int p, int q) {  // p → q counter-clockwise seen from above
    f.push_back({p, id(0, 0, 1) + p, id(0, 0, 1) + q});
    f.push_back({p, id(0, 0, 1) + q, q});
  };
  for (int i = 0; i < nx; ++i) side(id(i, 0, 0), id(i + 1, 0, 0));
  for (int j = 0; j < ny; ++j) side(id(nx, j, 0), id(nx, j + 1, 0));
  for (int i = nx; i > 0; --i) side(id(i, ny, 0), id(i - 1, ny, 0));
  for (int j = ny; j > 0; --j) side(id(0, j, 0), id(0, j - 1, 0));
  return MakeMesh(std::move(v), std::move(f));
}

// An incline of angle θ through the origin, rising along +x: a tilted ground, a static box or a
// static mesh slab (2 m × 0.6 m).
enum class Support { kGround, kStaticBox, kStaticMesh };
const char* Name(Support s) {
  return s == Support::kGround ? "ground" : s == Support::kStaticBox ? "static box" : "static mesh";
}

Matrix3 InclineRotation(double theta) { return Eigen::AngleAxisd(-theta, Vector3::UnitY()).toRotationMatrix(); }

void AddIncline(ContactWorld& w, Support s, double theta, const Material& m) {
  const Matrix3 R = InclineRotation(theta);
  const Vector3 n = R * Vector3::UnitZ();
  switch (s) {
    case Support::kGround: w.AddGround({n, 0, m}); break;
    case Support::kStaticBox:
      w.AddStatic(Collider{shape::Box{Vector3(1, 0.3, 0.05)}, Matrix3::Identity(), Vector3::Zero(), m}, R, -0.05 * n);
      break;
    case Support::kStaticMesh: {
      static const shape::Mesh slab = Slab(1, 0.3, 0.1, 40, 12, 7);
      w.AddStatic(Collider{slab, Matrix3::Identity(), Vector3::Zero(), m}, R, Vector3::Zero());
      break;
    }
  }
}

// Boxes lying flat, in units of u = 2 cm (full sizes along the slope, across it, up).
struct BoxCase {
  const char* name;
  Vector3 size;
};
constexpr double kU = 0.02;
const BoxCase kBoxes[] = {{"cube", {1, 1, 1}},
                          {"plate 6x6x1", {6, 6, 1}},
                          {"bar 6x1x1 up the slope", {6, 1, 1}},
                          {"bar 1x6x1 across", {1, 6, 1}},
                          {"tall 1x1x2", {1, 1, 2}}};
const Material kMaterials[] = {Mat(0.4, 0.3), Mat(0.8, 0.5)};

// Every box of kBoxes in every material of kMaterials at rest, touching, on each kind of incline
// of angle atan(ratio μs), its centre `up` metres up the slope, gravity on: `check` gets the body
// after `steps` steps, as it started, the angle and the material. Boxes that would tip (tan θ beyond their
// width over height) are another test.
// A box of half extents `half` (500 kg/m³) at rest on an incline of angle theta, `up` along it
// from the origin, under gravity; returns the body as it was added.
RigidBody BoxOnIncline(ContactWorld& w, Support s, double theta, const Vector3& half, double up, const Material& m) {
  AddIncline(w, s, theta, m);
  const Matrix3 R = InclineRotation(theta);
  RigidBody b = BoxBody(half, 500);
  b.position = R * Vector3(up, 0, half.z());
  b.orientation = Quaternion(R);
  w.AddBody(b, Collider{shape::Box{half}, Matrix3::Identity(), Vector3::Zero(), m});
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  return b;
}

void ForEachBoxOnAnIncline(
    double ratio, double up, int steps,
    const std::function<void(const RigidBody&, const RigidBody&, double, const Material&)>& check) {
  for (const Support s : {Support::kGround, Support::kStaticBox, Support::kStaticMesh}) {
    for (const Material& m : kMaterials) {
      for (const BoxCase& box : kBoxes) {
        const double theta = std::atan(ratio * m.static_friction);
        const Vector3 half = box.size * (kU / 2);
        if (std::tan(theta) >= half.x() / half.z()) continue;
        ContactWorld w;
        const RigidBody b = BoxOnIncline(w, s, theta, half, up, m);
        SCOPED_TRACE(std::string(Name(s)) + ", " + box.name + ", μs " + std::to_string(m.static_friction));
        Simulate(w, steps);
        check(w.world().bodies()[0], b, theta, m);
      }
    }
  }
}

// Within static friction (tan θ = 0.9 μs) every box stays put: less than 1 µm in 5 s.
TEST(Friction, BoxesAtRestOnInclinesBelowStaticFrictionStayPut) {
  ForEachBoxOnAnIncline(0.9, 0.5, 5000, [](const RigidBody& b, const RigidBody& start, double, const Material&) {
    EXPECT_LT((b.position - start.position).norm(), 1e-6) << (b.position - start.position).transpose();
    EXPECT_LT(b.orientation.angularDistance(start.orientation), 1e-6);
  });
}

// Beyond static friction (tan θ = 1.05 μs) every box slides at a = g (sin θ − μk cos θ) from the
// first step: its speed at 1 s within a h of a t.
TEST(Friction, BoxesOnInclinesBeyondStaticFrictionSlideAtTheKineticRateAtOnce) {
  ForEachBoxOnAnIncline(1.05, 0.8, 1000, [](const RigidBody& b, const RigidBody&, double theta, const Material& m) {
    const Vector3 downhill = -(InclineRotation(theta) * Vector3::UnitX());
    const double a = kG * (std::sin(theta) - m.kinetic_friction * std::cos(theta));
    EXPECT_NEAR(b.velocity.dot(downhill), a * 1.0, a * kH);
    EXPECT_LT(b.AngularVelocity().norm(), 1e-6);
  });
}

// Pushed on flat ground, at the centre of mass or at a point below it, by a force of fixed
// direction: 0.9 μs m g holds it (less than 1 µm in 2 s), 1.1 μs m g slides it at F/m − μk g
// (1 %). Pushes that would tip the box (F times the push's height above the ground, less the
// sliding box's inertia times its centre's, beyond m g times half its width) are left out.
TEST(Friction, PushedBoxesHoldBelowStaticFrictionAndSlideAboveIt) {
  const Material m = Mat(0.6, 0.4);
  for (const BoxCase& box : kBoxes) {
    for (const double below : {0.0, 0.4}) {  // how far below the centre, in half heights
      for (const double ratio : {0.9, 1.1}) {
        const Vector3 half = box.size * (kU / 2);
        const double a_over_g = ratio < 1 ? 0.0 : ratio * m.static_friction - m.kinetic_friction;
        const double lever = ratio * m.static_friction * (1 - below) - a_over_g;  // moment about the front edge / m g
        if (lever * half.z() >= 0.9 * half.x()) continue;
        ContactWorld w;
        w.AddGround({Vector3::UnitZ(), 0, m});
        RigidBody b = BoxBody(half, 500);
        b.position = Vector3(0, 0, half.z());
        const double force = ratio * m.static_friction * b.mass * kG;
        const int i = w.AddBody(b, Collider{shape::Box{half}, Matrix3::Identity(), Vector3::Zero(), m});
        w.AddForce(Gravity(Vector3(0, 0, -kG)));
        w.AddForce(PointForce(i, Vector3(0, 0, -below * half.z()), Vector3(force, 0, 0), false));
        // The push adds energy: Simulate's passivity check does not apply.
        for (int k = 0; k < 2000; ++k) ASSERT_TRUE(w.Step(kH).ok);
        const RigidBody& now = w.world().bodies()[0];
        SCOPED_TRACE(std::string(box.name) + " pushed " + std::to_string(below) +
                     " half heights below its centre, F/μs m g " + std::to_string(ratio));
        if (ratio < 1) {
          EXPECT_LT((now.position - b.position).norm(), 1e-6);
        } else {
          const double a = force / b.mass - m.kinetic_friction * kG;
          EXPECT_NEAR(now.velocity.x(), a * 2.0, 0.01 * a * 2.0);
          // It does not tip: by default its sweeps stop at 10⁻⁹ m/s, which leaves its turning
          // below 10⁻⁵ rad/s.
          EXPECT_LT(now.AngularVelocity().norm(), 1e-5);
        }
      }
    }
  }
}

// Coulomb's hysteresis: a box landing flat (e = 0) on a slope with μk < tan θ < μs keeps sliding;
// with tan θ < μk it stops during the impact and then holds.
TEST(Friction, LandingOnASlopeKeepsSlidingOrStopsAsCoulombSays) {
  const Material m = Mat(0.8, 0.5);
  for (const Support s : {Support::kGround, Support::kStaticBox, Support::kStaticMesh}) {
    for (const double tan_theta : {0.65, 0.4}) {
      const double theta = std::atan(tan_theta);
      const Vector3 half = Vector3(3, 2, 1) * (kU / 2);
      ContactWorld w;
      AddIncline(w, s, theta, m);
      const Matrix3 R = InclineRotation(theta);
      RigidBody b = BoxBody(half, 500);
      b.position = R * Vector3(0.6, 0, half.z()) + Vector3(0, 0, 0.02);  // 2 cm above, falling
      b.orientation = Quaternion(R);
      w.AddBody(b, Collider{shape::Box{half}, Matrix3::Identity(), Vector3::Zero(), m});
      w.AddForce(Gravity(Vector3(0, 0, -kG)));
      const Vector3 downhill = -(R * Vector3::UnitX());
      double landed = -1, speed_after = 0;
      Vector3 at_rest = Vector3::Zero();
      Simulate(w, 1000, [&](int k) {
        if (landed < 0 && w.stats().contacts > 0 && w.world().bodies()[0].velocity.dot(R * Vector3::UnitZ()) > -1e-9) {
          landed = k * kH;
          speed_after = w.world().bodies()[0].velocity.dot(downhill);
          at_rest = w.world().bodies()[0].position;
        }
      });
      SCOPED_TRACE(std::string(Name(s)) + ", tan θ " + std::to_string(tan_theta));
      ASSERT_GE(landed, 0);
      const RigidBody& now = w.world().bodies()[0];
      if (tan_theta > m.kinetic_friction) {
        const double a = kG * (std::sin(theta) - m.kinetic_friction * std::cos(theta));
        EXPECT_GT(speed_after, 0);
        EXPECT_NEAR(now.velocity.dot(downhill), speed_after + a * (1.0 - landed - kH), 0.01 * a);
      } else {
        EXPECT_LT(std::abs(speed_after), 1e-9);
        EXPECT_LT((now.position - at_rest).norm(), 1e-6);
      }
    }
  }
}

// Torsion: a flat square box (side s) spun about the vertical stops after I ω0 / T, with T the
// uniform-pressure limit μk m g s (√2 + asinh 1) / 6 = 0.3826 μk m g s (2 %).
TEST(Friction, SpinningSquareStopsAtTheUniformPressureTorque) {
  const Material m = Mat(0.5, 0.3);
  const double s = 0.12;
  const Vector3 half(s / 2, s / 2, 0.01);
  ContactWorld w;
  w.AddGround({Vector3::UnitZ(), 0, m});
  RigidBody b = BoxBody(half, 500);
  b.position = Vector3(0, 0, half.z());
  const double omega0 = 6;
  b.angular_momentum = Vector3(0, 0, b.inertia.z() * omega0);
  w.AddBody(b, Collider{shape::Box{half}, Matrix3::Identity(), Vector3::Zero(), m});
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  const double T = m.kinetic_friction * b.mass * kG * s * (std::sqrt(2.0) + std::asinh(1.0)) / 6;
  const double expected = b.inertia.z() * omega0 / T;
  double stopped = -1;
  Simulate(w, 3000, [&](int k) {
    if (stopped < 0 && w.world().bodies()[0].AngularVelocity().z() <= 1e-9) stopped = (k + 1) * kH;
  });
  EXPECT_NEAR(stopped, expected, 0.02 * expected);
  EXPECT_LT(w.world().bodies()[0].position.head<2>().norm(), 1e-9);  // it turned in place
}

// Bodies that slide along their x axis: a 6 × 4 × 2 cm box, an octagonal hull prism 2 cm high,
// a capsule with its axis along x (across it, it would roll); each with the height of its centre
// above the surface it lies on.
struct Slider {
  const char* name;
  Collider collider;
  double lift;
};
std::vector<Slider> Sliders(const Material& m) {
  const Vector3 half(0.03, 0.02, 0.01);
  shape::Convex hull;
  for (const double z : {-0.01, 0.01}) {
    for (int k = 0; k < 8; ++k) {
      const double phi = k * massprops::kPi / 4 + massprops::kPi / 8;
      hull.vertices.emplace_back(0.03 * std::cos(phi), 0.03 * std::sin(phi), z);
    }
  }
  for (int k = 1; k + 1 < 8; ++k) {
    hull.triangles.push_back({8, 8 + k, 8 + k + 1});  // top
    hull.triangles.push_back({0, k, k + 1});          // bottom
  }
  for (int k = 0; k < 8; ++k) {
    const int j = (k + 1) % 8;
    hull.triangles.push_back({k, j, 8 + j});
    hull.triangles.push_back({k, 8 + j, 8 + k});
  }
  for (auto& t : hull.triangles) {  // every triangle outward
    const Vector3 c = (hull.vertices[t[0]] + hull.vertices[t[1]] + hull.vertices[t[2]]) / 3;
    if ((hull.vertices[t[1]] - hull.vertices[t[0]]).cross(hull.vertices[t[2]] - hull.vertices[t[0]]).dot(c) < 0)
      std::swap(t[1], t[2]);
  }
  const Matrix3 along_x = Eigen::AngleAxisd(massprops::kPi / 2, Vector3::UnitY()).toRotationMatrix();
  return {{"box", Collider{shape::Box{half}, Matrix3::Identity(), Vector3::Zero(), m}, half.z()},
          {"hull", Collider{hull, Matrix3::Identity(), Vector3::Zero(), m}, 0.01},
          {"capsule", Collider{shape::Capsule{0.01, 0.03}, along_x, Vector3::Zero(), m}, 0.01}};
}

// Internal edges: bodies sliding down a static mesh ramp whose flat top is split along random
// diagonals travel as on a flat face: distance ½ a t² within 1 %, orientation within 1°.
TEST(Friction, SlidingOverAStaticMeshsInternalEdgesIsSlidingOnItsFace) {
  const Material m = Mat(0.4, 0.3);
  const double theta = std::atan(0.5);
  const Matrix3 R = InclineRotation(theta);
  const double a = kG * (std::sin(theta) - m.kinetic_friction * std::cos(theta));
  for (const unsigned seed : {1u, 2u, 3u}) {
    const shape::Mesh slab = Slab(1, 0.3, 0.1, 40, 12, seed);
    for (const Slider& slider : Sliders(m)) {
      ContactWorld w;
      w.AddStatic(Collider{slab, Matrix3::Identity(), Vector3::Zero(), m}, R, Vector3::Zero());
      RigidBody b = BoxBody(Vector3(0.03, 0.02, 0.01), 500);  // the inertia matters little: it slides
      b.position = R * Vector3(0.8, 0, slider.lift);
      b.orientation = Quaternion(R);
      w.AddBody(b, slider.collider);
      w.AddForce(Gravity(Vector3(0, 0, -kG)));
      Simulate(w, 1000);
      const RigidBody& now = w.world().bodies()[0];
      const double travelled = (now.position - b.position).dot(-(R * Vector3::UnitX()));
      SCOPED_TRACE(std::string(slider.name) + ", diagonals seeded " + std::to_string(seed));
      EXPECT_NEAR(travelled, 0.5 * a, 0.01 * 0.5 * a);
      EXPECT_LT(now.orientation.angularDistance(b.orientation), massprops::kPi / 180);
    }
  }
}

// The same across a flat static floor tessellated as a 20 × 20 grid of triangle pairs: each
// body sliding at 2 m/s at 30° to the grid stops after v²/(2 μk g) (1 %), still facing the same way.
TEST(Friction, SlidingAcrossATessellatedFloorStopsAtTheClosedFormDistance) {
  const Material m = Mat(0.4, 0.3);
  const shape::Mesh floor = Slab(0.6, 0.6, 0.1, 20, 20, 11);
  const Vector3 direction(std::cos(massprops::kPi / 6), std::sin(massprops::kPi / 6), 0);
  const double v0 = 2, d = v0 * v0 / (2 * m.kinetic_friction * kG);
  for (const Slider& slider : Sliders(m)) {
    ContactWorld w;
    w.AddStatic(Collider{floor, Matrix3::Identity(), Vector3::Zero(), m});
    RigidBody b = BoxBody(Vector3(0.03, 0.02, 0.01), 500);
    b.position = Vector3(-0.4, -0.25, slider.lift);
    b.orientation = Quaternion(Eigen::AngleAxisd(massprops::kPi / 6, Vector3::UnitZ()));  // x along the sliding
    b.velocity = v0 * direction;
    w.AddBody(b, slider.collider);
    w.AddForce(Gravity(Vector3(0, 0, -kG)));
    Simulate(w, 1000);
    const RigidBody& now = w.world().bodies()[0];
    SCOPED_TRACE(slider.name);
    EXPECT_NEAR((now.position - b.position).dot(direction), d, 0.01 * d);
    EXPECT_LT(now.orientation.angularDistance(b.orientation), massprops::kPi / 180);
    EXPECT_LT(now.velocity.norm(), 1e-9);
  }
}

// A cylinder rolls down a static box ramp and a static mesh ramp at a = (2/3) g sin θ (1 %).
TEST(Friction, CylinderRollsDownStaticRampsAtTwoThirdsGSinTheta) {
  const Material m = Mat(0.5, 0.5);
  const double theta = 15 * massprops::kPi / 180, r = 0.03, half_length = 0.05;
  for (const Support s : {Support::kGround, Support::kStaticBox, Support::kStaticMesh}) {
    ContactWorld w;
    AddIncline(w, s, theta, m);
    const Matrix3 R = InclineRotation(theta);
    RigidBody b;
    b.mass = 1000 * massprops::kPi * r * r * 2 * half_length;
    const double across = b.mass * (3 * r * r + 4 * half_length * half_length) / 12;
    b.inertia = Vector3(across, across, 0.5 * b.mass * r * r);
    b.position = R * Vector3(0.8, 0, r);
    b.orientation =
        Quaternion(R * Eigen::AngleAxisd(massprops::kPi / 2, Vector3::UnitX()).toRotationMatrix());  // axis across
    w.AddBody(b, Collider{shape::Cylinder{r, half_length}, Matrix3::Identity(), Vector3::Zero(), m});
    w.AddForce(Gravity(Vector3(0, 0, -kG)));
    Simulate(w, 700);
    const RigidBody& now = w.world().bodies()[0];
    const double a = 2.0 / 3 * kG * std::sin(theta), t = 0.7;
    SCOPED_TRACE(Name(s));
    EXPECT_NEAR(now.velocity.dot(-(R * Vector3::UnitX())), a * t, 0.01 * a * t);
    EXPECT_NEAR((now.position - b.position).dot(-(R * Vector3::UnitX())), 0.5 * a * t * t, 0.01 * 0.5 * a * t * t);
  }
}

}  // namespace
}  // namespace dynamics

namespace dynamics {
namespace {

// A capsule lying across a box's edge between its ends rests on the edge: lying along x with its
// centre of mass over the box and one end beyond the edge, it stays level, at its radius above
// the top (the end spheres alone would let it tip through the edge).
TEST(Contact, CapsuleLyingAcrossABoxEdgeRestsOnIt) {
  const Material m = Mat(0.6, 0.5);
  const double r = 0.01, half_length = 0.1;
  ContactWorld w;
  w.AddStatic(Collider{shape::Box{Vector3(0.25, 0.25, 0.05)}, Matrix3::Identity(), Vector3::Zero(), m},
              Matrix3::Identity(), Vector3(0, 0, -0.05));  // top at z = 0, edge at x = 0.25
  RigidBody b;
  b.mass = 0.1;
  b.inertia = Vector3(b.mass * half_length * half_length / 3, b.mass * half_length * half_length / 3, 1e-6);
  b.position = Vector3(0.2, 0, r);
  b.orientation = Quaternion(Eigen::AngleAxisd(massprops::kPi / 2, Vector3::UnitY()));  // axis along x
  w.AddBody(b, Collider{shape::Capsule{r, half_length}, Matrix3::Identity(), Vector3::Zero(), m});
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  Simulate(w, 1000);
  const RigidBody& now = w.world().bodies()[0];
  EXPECT_NEAR(now.position.z(), r, 1e-6);
  EXPECT_LT(now.orientation.angularDistance(b.orientation), 1e-5);
}

// Overlaps of primitive bodies are pushed out: a box sunk 2 mm into the ground rises to within
// its slop (half a percent of its bounding radius) in 0.2 s, its velocity untouched by the
// push, and the energy rises in no step by more than its weight times the distance pushed.
TEST(Contact, OverlapsOfPrimitivesArePushedOutPayingOnlyThePotentialEnergy) {
  const Material m = Mat(0.6, 0.5);
  const Vector3 half(0.03, 0.02, 0.01);
  ContactWorld w;
  w.AddGround({Vector3::UnitZ(), 0, m});
  RigidBody b = BoxBody(half, 500);
  b.position = Vector3(0, 0, half.z() - 0.002);
  w.AddBody(b, Collider{shape::Box{half}, Matrix3::Identity(), Vector3::Zero(), m});
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  double energy = w.world().Diagnose().total_energy, pushed = 0;
  for (int i = 0; i < 200; ++i) {
    ASSERT_TRUE(w.Step(kH).ok);
    const double now = w.world().Diagnose().total_energy;
    EXPECT_LE(now, energy + b.mass * kG * w.stats().pushed + 1e-12) << "step " << i;
    pushed += w.stats().pushed;
    energy = now;
  }
  const double slop = 0.005 * half.norm();
  const RigidBody& now = w.world().bodies()[0];
  EXPECT_GT(pushed, 0.002 - slop - 1e-9);
  EXPECT_NEAR(now.position.z(), half.z() - slop, 1e-6);
  EXPECT_LT(now.velocity.norm(), 1e-9);
}

// The contacts the outputs report (ContactWorld::Contacts) are the impulses the step applied: a box
// held on an incline by static friction gets from its points together exactly what gravity takes
// (m g h upward: the normal impulses and the friction's shares add up); a box sliding beyond it
// gets friction μk times the normal impulse, up the slope.
TEST(Friction, ReportedContactImpulsesBalanceGravityOrSlideAtMuK) {
  const double h = 1e-3;
  for (const double ratio : {0.9, 1.05}) {
    for (const Support s : {Support::kGround, Support::kStaticMesh}) {
      SCOPED_TRACE(std::string(Name(s)) + (ratio < 1 ? ", holding" : ", sliding"));
      const Material m = Mat(0.6, 0.4);
      const double theta = std::atan(ratio * m.static_friction);
      ContactWorld w;
      const Matrix3 R = InclineRotation(theta);
      const Vector3 half(0.04, 0.03, 0.02), n = R * Vector3::UnitZ(), up_slope = R * Vector3::UnitX();
      const RigidBody b = BoxOnIncline(w, s, theta, half, 0.3, m);
      Simulate(w, 200);
      const std::vector<ContactReport> contacts = w.Contacts();
      ASSERT_GE(contacts.size(), 3u);
      Vector3 sum = Vector3::Zero();
      for (const ContactReport& c : contacts) {
        EXPECT_EQ(c.a, 0);
        EXPECT_EQ(c.b, -1);
        EXPECT_LT((c.normal - n).norm(), 1e-9);
        EXPECT_LT(std::abs(n.dot(c.point)), 1e-4);  // on the incline's surface (through the origin)
        sum += c.impulse;
      }
      const double weight = b.mass * kG * h;
      const double normal = sum.dot(n), friction = sum.dot(up_slope);
      EXPECT_NEAR(normal, weight * std::cos(theta), 1e-8 * weight);
      if (ratio < 1) {
        EXPECT_LT((sum - Vector3(0, 0, weight)).norm(), 1e-9 * weight) << sum.transpose();
      } else {
        EXPECT_NEAR(friction, m.kinetic_friction * normal, 1e-9 * weight);
      }
      EXPECT_FALSE(w.asleep(0));
    }
  }
}

// A box held on an incline by static friction is one patch alone in its island, solved whole
// (its normals and friction as one system, UpdatePatchJointly): settled, a step takes two sweeps
// (the second confirms the first), and its impulses balance gravity to 10⁻¹² of the weight — flat,
// halfway to the friction limit and at 0.99 of it, where the joint answer must still be accepted.
TEST(Friction, AHoldingPatchAloneIsSolvedWholeInTwoSweeps) {
  const double h = 1e-3;
  for (const double ratio : {0.0, 0.5, 0.99}) {
    for (const BoxCase& box : kBoxes) {
      SCOPED_TRACE(std::string(box.name) + ", tan θ = " + std::to_string(ratio) + " μs");
      const Material m = Mat(0.6, 0.4);
      const double theta = std::atan(ratio * m.static_friction);
      const Vector3 half = box.size * (kU / 2);
      if (std::tan(theta) >= half.x() / half.z()) continue;
      ContactWorld w;
      const RigidBody b = BoxOnIncline(w, Support::kGround, theta, half, 0.3, m);
      Simulate(w, 100);
      for (int k = 0; k < 20; ++k) {
        ASSERT_TRUE(w.Step(h).ok);
        EXPECT_LE(w.stats().iterations, 2);
        Vector3 sum = Vector3::Zero();
        for (const ContactReport& c : w.Contacts()) sum += c.impulse;
        const double weight = b.mass * kG * h;
        EXPECT_LT((sum - Vector3(0, 0, weight)).norm(), 1e-12 * weight) << sum.transpose();
      }
      EXPECT_LT((w.world().bodies()[0].position - b.position).norm(), 1e-7);
    }
  }
}

// The reported rows carry the whole wrench of the step, turning included: a box that slides and
// spins on a support changes its momentum by gravity's impulse plus the rows' impulses, and its
// angular momentum about its center by Σ (point − center) × impulse + torque, the torsional
// friction and the friction's moment among them (as the body's own state change measures them).
TEST(Friction, ReportedContactsCarryTheStepsWholeWrench) {
  for (const Support s : {Support::kGround, Support::kStaticBox, Support::kStaticMesh}) {
    for (const bool holding : {false, true}) {
      SCOPED_TRACE(std::string(Name(s)) + (holding ? ", coming to rest" : ", sliding and spinning"));
      const Material m = Mat(0.6, 0.4);
      ContactWorld w;
      AddIncline(w, s, 0, m);
      const Vector3 half(0.05, 0.03, 0.02);
      RigidBody b = BoxBody(half, 500);
      b.position = Vector3(0.3, 0.01, half.z());
      b.orientation = Quaternion(Eigen::AngleAxisd(0.4, Vector3::UnitZ()));
      // Slow enough for friction to stop it within a step, or fast enough to slide for many.
      b.velocity = holding ? Vector3(0.002, -0.001, 0) : Vector3(0.3, -0.2, 0);
      b.SetAngularVelocity(Vector3(0, 0, holding ? 0.02 : 6.0));
      w.AddBody(b, Collider{shape::Box{half}, Matrix3::Identity(), Vector3::Zero(), m});
      w.AddForce(Gravity(Vector3(0, 0, -kG)));
      if (!holding) Simulate(w, 5);
      const RigidBody before = w.world().bodies()[0];
      ASSERT_TRUE(w.Step(kH).ok);
      const RigidBody& after = w.world().bodies()[0];
      const std::vector<ContactReport> contacts = w.Contacts();
      ASSERT_GE(contacts.size(), 3u);
      Vector3 impulse = Vector3::Zero(), angular = Vector3::Zero(), twist = Vector3::Zero();
      for (const ContactReport& c : contacts) {
        impulse += c.impulse;
        angular += (c.point - before.position).cross(c.impulse) + c.torque;
        twist += c.torque;
      }
      const double p_scale = b.mass * kG * kH;
      EXPECT_LT((after.LinearMomentum() - before.LinearMomentum() - impulse - Vector3(0, 0, -p_scale)).norm(),
                1e-9 * p_scale);
      const Vector3 dL = after.angular_momentum - before.angular_momentum;
      const double l_scale = p_scale * half.norm();
      EXPECT_LT((dL - angular).norm(), 1e-9 * l_scale) << dL.transpose() << " vs " << angular.transpose();
      // Friction turns it back: the z part opposes the spin, and is not zero.
      EXPECT_LT(dL.z(), -1e-3 * l_scale);
      EXPECT_LT(twist.dot(Vector3::UnitZ()), 0);
    }
  }
}

}  // namespace
}  // namespace dynamics
