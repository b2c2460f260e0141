// Mesh colliders (shape::Mesh, signed distance fields) against closed forms and against what only
// a non-convex collider can do: the field's distances against the exact ones; a box given as a
// mesh slides down an incline at the kinetic rate and a mesh sphere rolls, as the primitives do; a
// mesh box rests on a table; a ring slides down a peg that its hull cannot pass; a cup stands and
// holds a ball dropped into it.

#include <cmath>
#include <cstring>
#include <functional>

#include <gtest/gtest.h>

#include "dynamics/contact.h"
#include "massprops/io/mesh_io.h"
#include "massprops/mass_properties.h"
#include "massprops/repair/repair.h"
#include "massprops/solids.h"
#include "mesh_field.h"
#include "narrow_phase.h"
#include "sample_bounds.h"

namespace dynamics {
namespace {

constexpr double kG = 9.81;

Material Mat(double mu_s, double mu_k, double e = 0) { return Material{mu_s, mu_k, e}; }

// A body made from a closed mesh (its center of mass and principal axes) and the mesh, in the body
// frame, as its collider; placed with its mesh frame at `at`.
struct MeshBody {
  RigidBody body;
  shape::Mesh shape;
  massprops::RigidTransform mesh_to_body;
};

MeshBody FromMesh(const massprops::TriangleMesh& m, double density, const Vector3& at, double cell = 0) {
  const PlacedBody placed = BodyFromMassProperties(massprops::ComputeMassProperties(m, density));
  std::vector<Vector3> v;
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) v.push_back(placed.mesh_to_body.Apply(m.V.row(i).transpose()));
  std::vector<std::array<int, 3>> t;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) t.push_back({m.F(f, 0), m.F(f, 1), m.F(f, 2)});
  MeshBody out{placed.body, MakeMesh(std::move(v), std::move(t), cell), placed.mesh_to_body};
  out.body.position += at;
  return out;
}

Collider Of(Shape s, const Material& m = Material{}) {
  return Collider{std::move(s), Matrix3::Identity(), Vector3::Zero(), m};
}

// Steps n times. The contact impulses never add kinetic energy, and the total energy rises in no
// step by more than the weight (g = 9.81) times the distance overlaps were pushed out.
void Simulate(ContactWorld& w, double h, int n, const std::function<void(int)>& each = nullptr) {
  double energy = w.world().Diagnose().total_energy, mass = 0;
  for (const RigidBody& b : w.world().bodies()) mass += b.mass;
  for (int i = 0; i < n; ++i) {
    const StepStatus s = w.Step(h);
    ASSERT_TRUE(s.ok) << s.message;
    ASSERT_GE(w.stats().dissipated, -1e-12 * std::max(1.0, std::abs(energy))) << "step " << i;
    const double now = w.world().Diagnose().total_energy;
    // (plus 1e-7 of the energy: what the solver's residual velocities lift in a resting stack of
    // ten, its sweeps stopped at 10⁻⁹ m/s; 1e-8 in exact mode)
    ASSERT_LE(now, energy + mass * kG * w.stats().pushed + 1e-7 * std::max(1.0, std::abs(energy)))
        << "energy rose at step " << i << " by " << now - energy << " (pushed " << w.stats().pushed << ")";
    energy = now;
    if (each) each(i);
  }
}

TEST(MeshContact, FieldDistancesAreTheMeshsOwn) {
  // A sphere of 1024 triangles: at points inside it, the depth a probe finds against the exact
  // depth below the tessellated surface (between the depth below the sphere and that less the
  // facets' sag), within the trilinear error (second order in the cell away from edges).
  const double r = 0.1;
  const massprops::TriangleMesh m = massprops::solids::Sphere(r, 16);
  const MeshBody b = FromMesh(m, 1000, Vector3::Zero());
  const MeshFieldInfo info = DescribeMeshField(b.shape);
  EXPECT_NEAR(info.cell, 2 * r / 64, 1e-3 * r);                // 64 cells along the longest side
  const double sag = r * (1 - std::cos(massprops::kPi / 16));  // how far the facets lie inside the sphere
  ContactWorld w;  // the field is reached through contacts: a small probe sphere at points
  int checked = 0;
  for (double d : {-0.03, -0.02, -0.01, -0.004}) {
    for (int k = 0; k < 20; ++k) {
      const Vector3 dir = Vector3(std::cos(0.7 * k) * std::sin(0.3 + 0.13 * k),
                                  std::sin(0.7 * k) * std::sin(0.3 + 0.13 * k), std::cos(0.3 + 0.13 * k))
                              .normalized();
      // The probe: a sphere of radius 1 mm at distance d from the sphere's surface.
      ContactWorld probe;
      probe.AddStatic(Of(b.shape));
      RigidBody s;
      s.mass = 1;
      s.inertia = Vector3::Constant(1);
      s.position = dir * (r + d + 0.001);
      probe.AddBody(s, Of(shape::Sphere{0.001}));
      ASSERT_TRUE(probe.Step(1e-9).ok);
      if (probe.stats().contacts == 0) continue;  // beyond the margin
      ++checked;
      EXPECT_GE(-probe.stats().max_penetration, d - 1e-4 - 1e-9) << d;
      EXPECT_LE(-probe.stats().max_penetration, d + sag + 1e-4) << d;
    }
  }
  EXPECT_EQ(checked, 80);
}

// The field is built on the threads asked for (ContactWorld::set_num_threads's when the world
// builds it), and its bits do not depend on how many there were.
TEST(MeshContact, FieldBitsAreTheSameOnOneAndTwoThreads) {
  // A coarse field (24 cells across): quick under the sanitizers, and still many slices a thread.
  const massprops::TriangleMesh m = massprops::solids::Sphere(0.1, 8);
  const shape::Mesh mesh = MeshOf(m);
  const double cell = 0.2 / 24;
  const shape::Mesh one = MakeMesh(mesh.vertices, mesh.triangles, cell, 1);
  const shape::Mesh two = MakeMesh(mesh.vertices, mesh.triangles, cell, 2);
  ASSERT_FALSE(one.field->values.empty());
  ASSERT_EQ(one.field->values.size(), two.field->values.size());
  EXPECT_EQ(std::memcmp(one.field->values.data(), two.field->values.data(), one.field->values.size() * sizeof(double)),
            0);
}

// The bounds a mesh pair keeps between steps answer tests the field would have answered the
// same way: along a path on which a ring moves into another, turning, then creeps (1 µm a step),
// with the margin changing every step, the points are bit for bit those found without them; while
// it creeps, most tests are answered by the bounds.
TEST(MeshContact, KeptFieldBoundsFindTheSamePointsAndAnswerMostTests) {
  const Shape a = FromMesh(massprops::solids::Torus(0.05, 0.015, 24), 1000, Vector3::Zero()).shape;
  const Shape b = FromMesh(massprops::solids::Torus(0.045, 0.012, 16), 1000, Vector3::Zero()).shape;
  contact::PairSampleBounds kept;
  std::size_t points = 0;
  std::uint64_t skipped = 0, evaluated = 0;
  for (int k = 0; k < 600; ++k) {
    if (k == 300) {
      for (contact::SampleBounds& d : kept.of) d.skipped = d.evaluated = 0;
    }
    const double s = k < 300 ? k : 300 + 0.005 * (k - 300);  // 0.2 mm a step, then 1 µm
    const contact::Posed pa{&a, nullptr, Matrix3::Identity(), Vector3::Zero(), {}};
    const Matrix3 R =
        (Eigen::AngleAxisd(0.001 * s, Vector3::UnitZ()) * Eigen::AngleAxisd(1.5, Vector3::UnitX())).toRotationMatrix();
    const contact::Posed pb{&b, nullptr, R, Vector3(0.11 - 0.0002 * s, 0.002 * std::sin(0.05 * s), 0.0), {}};
    const double margin = 0.002 + 0.001 * std::sin(0.7 * k);
    std::vector<contact::ContactPoint> with, without;
    contact::CollideMeshes(pa, pb, margin, with, &kept);
    contact::CollideMeshes(pa, pb, margin, without, nullptr);
    ASSERT_EQ(with.size(), without.size()) << "step " << k;
    for (std::size_t i = 0; i < with.size(); ++i) {
      ASSERT_EQ(std::memcmp(&with[i].point, &without[i].point, sizeof(Vector3)), 0) << "step " << k;
      ASSERT_EQ(std::memcmp(&with[i].normal, &without[i].normal, sizeof(Vector3)), 0) << "step " << k;
      ASSERT_EQ(std::memcmp(&with[i].separation, &without[i].separation, sizeof(double)), 0) << "step " << k;
      ASSERT_EQ(with[i].feature, without[i].feature) << "step " << k;
    }
    points += with.size();
  }
  for (const contact::SampleBounds& d : kept.of) skipped += d.skipped, evaluated += d.evaluated;
  EXPECT_GT(points, 1000u);  // (the rings touch for most of the path)
  EXPECT_GT(skipped, 3 * evaluated);
}

// The same for two tilted mesh boxes closing in 10 µm a step, whose corners and edge samples come
// within the margin one by one: each step's points (fewer than the sixteen a pair keeps, so none
// is left out by the reduction) are the same with the bounds and without.
TEST(MeshContact, KeptFieldBoundsMissNoSampleThatComesWithinTheMargin) {
  const massprops::TriangleMesh cube = massprops::Triangulate(massprops::solids::Box(Vector3(0.1, 0.1, 0.1)));
  const Shape a = FromMesh(cube, 1000, Vector3::Zero(), 0.01).shape;
  const Shape b = FromMesh(cube, 1000, Vector3::Zero(), 0.01).shape;
  const Matrix3 R =
      (Eigen::AngleAxisd(0.08, Vector3::UnitX()) * Eigen::AngleAxisd(0.05, Vector3::UnitY())).toRotationMatrix();
  contact::PairSampleBounds kept;
  std::size_t most = 0, changes = 0, last = 0;
  for (int k = 0; k < 430; ++k) {
    const contact::Posed pa{&a, nullptr, Matrix3::Identity(), Vector3::Zero(), {}};
    const contact::Posed pb{&b, nullptr, R, Vector3(0.01, -0.02, 0.107 - 1e-5 * k), {}};
    std::vector<contact::ContactPoint> with, without;
    contact::CollideMeshes(pa, pb, 0.002, with, &kept);
    contact::CollideMeshes(pa, pb, 0.002, without, nullptr);
    ASSERT_EQ(with.size(), without.size()) << "step " << k;
    for (std::size_t i = 0; i < with.size(); ++i) {
      ASSERT_EQ(std::memcmp(&with[i].point, &without[i].point, sizeof(Vector3)), 0) << "step " << k;
    }
    most = std::max(most, with.size());
    changes += with.size() != last;
    last = with.size();
  }
  EXPECT_LT(most, contact::kMaxContactPoints);
  EXPECT_GT(changes, 10u);  // (the points come in one by one)
  EXPECT_GT(kept.of[0].skipped + kept.of[1].skipped, kept.of[0].evaluated + kept.of[1].evaluated);
}

TEST(MeshContact, MeshBoxSlidesDownAnInclineAtTheKineticRate) {
  const double theta = 30 * massprops::kPi / 180, mu_s = 0.3, mu_k = 0.2;
  const Vector3 half(0.1, 0.05, 0.025);
  const MeshBody b = FromMesh(massprops::Triangulate(massprops::solids::Box(2 * half)), 500, Vector3(0, 0, half.z()));
  ContactWorld w;
  w.AddBody(b.body, Of(b.shape, Mat(mu_s, mu_k)));
  w.AddGround({Vector3::UnitZ(), 0, Mat(mu_s, mu_k)});
  w.AddForce(Gravity(Vector3(kG * std::sin(theta), 0, -kG * std::cos(theta))));
  Simulate(w, 1e-3, 1000);
  const double a = kG * (std::sin(theta) - mu_k * std::cos(theta));
  const RigidBody& r = w.world().bodies()[0];
  EXPECT_NEAR(r.velocity.x(), a, 0.01 * a);
  EXPECT_NEAR(r.position.z(), half.z(), 1e-9);
}

// A polyhedral sphere does not roll as a sphere: each vertex it rolls over is a small inelastic
// impact, and it reaches a terminal speed. So the mesh path is held to the same polyhedron as a
// convex collider (the exact path of the first contact issue), and both to the closed form of the
// sphere for the first 0.1 s, before the losses add up.
TEST(MeshContact, MeshBoxSticksOnAnInclineWithinStaticFriction) {
  // tan 30° = 0.577 < μs = 0.7: no creep, as the box primitive.
  const double theta = 30 * massprops::kPi / 180;
  const Vector3 half(0.1, 0.05, 0.025);
  const MeshBody b = FromMesh(massprops::Triangulate(massprops::solids::Box(2 * half)), 500, Vector3(0, 0, half.z()));
  ContactWorld w;
  w.AddBody(b.body, Of(b.shape, Mat(0.7, 0.6)));
  w.AddGround({Vector3::UnitZ(), 0, Mat(0.7, 0.6)});
  w.AddForce(Gravity(Vector3(kG * std::sin(theta), 0, -kG * std::cos(theta))));
  Simulate(w, 1e-3, 10000);
  EXPECT_LT(std::abs(w.world().bodies()[0].position.x()), 1e-6);
}

// Ten boxes given as meshes, 10 cm tall and each 4 mm narrower than the one below, stacked on a
// static mesh slab: the stack stands (as the box primitives' stack does on the ground). Aligned
// edges of equal boxes are where a field is least accurate (its gradient turns within a cell of an
// edge): the narrowing keeps every corner on a face below.
TEST(MeshContact, StackOfTenMeshBoxesStands) {
  const MeshBody slab =
      FromMesh(massprops::Triangulate(massprops::solids::Box(Vector3(0.5, 0.5, 0.05))), 1000, Vector3::Zero());
  ContactWorld w;
  std::vector<shape::Mesh> shapes;
  for (int i = 0; i < 10; ++i) {
    const double half = 0.05 - 0.002 * i;
    const MeshBody b = FromMesh(massprops::Triangulate(massprops::solids::Box(Vector3(2 * half, 2 * half, 0.1))), 500,
                                Vector3(0, 0, 0.025 + 0.05 + 0.1 * i));
    w.AddBody(b.body, Of(b.shape, Mat(0.6, 0.5)));
    shapes.push_back(b.shape);
  }
  w.AddStatic(Of(slab.shape, Mat(0.6, 0.5)));  // top at z = 0.025
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  std::vector<Vector3> start;
  for (const RigidBody& b : w.world().bodies()) start.push_back(b.position);
  double deepest = 0;
  Simulate(w, 1e-3, 5000, [&](int) { deepest = std::max(deepest, w.stats().max_penetration); });
  for (std::size_t i = 0; i < start.size(); ++i) {
    const RigidBody& b = w.world().bodies()[i];
    EXPECT_LT(b.velocity.norm(), 1e-4) << "box " << i;
    EXPECT_LT((b.position - start[i]).norm(), 1e-3) << "box " << i;
  }
  EXPECT_LT(deepest, 0.5 * DescribeMeshField(shapes.back()).cell);
}

TEST(MeshContact, MeshSphereRollsAsTheSamePolyhedronDoes) {
  const double theta = 20 * massprops::kPi / 180, r = 0.1;
  const massprops::TriangleMesh m = massprops::solids::Sphere(r, 32);
  const MeshBody b = FromMesh(m, 1000, Vector3(0, 0, r));
  shape::Convex polyhedron{b.shape.vertices, b.shape.triangles};
  std::vector<Vector3> speeds;
  for (const Shape& collider : {Shape(b.shape), Shape(polyhedron)}) {
    ContactWorld w;
    w.AddBody(b.body, Of(collider, Mat(0.8, 0.8)));
    w.AddGround({Vector3::UnitZ(), 0, Mat(0.8, 0.8)});
    w.AddForce(Gravity(Vector3(kG * std::sin(theta), 0, -kG * std::cos(theta))));
    Simulate(w, 1e-3, 100);
    const RigidBody& s = w.world().bodies()[0];
    const double a = kG * std::sin(theta) / (1 + s.inertia.mean() / (s.mass * r * r));
    EXPECT_NEAR(s.velocity.x(), 0.1 * a, 0.02 * 0.1 * a) << ShapeName(collider);
    Simulate(w, 1e-3, 900);
    speeds.push_back(w.world().bodies()[0].velocity);
  }
  EXPECT_NEAR(speeds[0].x(), speeds[1].x(), 0.005 * speeds[1].x());
}

// A bouncing polyhedral sphere as its mesh and as the same polyhedron's convex collider: the apexes
// of three bounces agree within 1 % (each near e² of the one before: the vertex it lands on turns it
// a little, which both paths see alike).
TEST(MeshContact, MeshBallBouncesAsTheSamePolyhedronDoes) {
  const double r = 0.05, e = 0.8, drop = 0.5;
  const MeshBody b = FromMesh(massprops::solids::Sphere(r, 24), 1000, Vector3(0, 0, drop + r));
  const shape::Convex polyhedron{b.shape.vertices, b.shape.triangles};
  std::vector<std::vector<double>> apexes;
  for (const Shape& collider : {Shape(b.shape), Shape(polyhedron)}) {
    ContactWorld w;
    w.AddBody(b.body, Of(collider, Mat(0.5, 0.5, e)));
    w.AddGround({Vector3::UnitZ(), 0, Mat(0.5, 0.5, e)});
    w.AddForce(Gravity(Vector3(0, 0, -kG)));
    std::vector<double> found;
    double previous_vz = 0;
    Simulate(w, 1e-4, 20000, [&](int) {
      const RigidBody& s = w.world().bodies()[0];
      if (previous_vz > 0 && s.velocity.z() <= 0) found.push_back(s.position.z() - r);
      previous_vz = s.velocity.z();
    });
    ASSERT_GE(found.size(), 3u) << ShapeName(collider);
    apexes.push_back(found);
  }
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(apexes[0][k], apexes[1][k], 0.01 * apexes[1][k]) << "bounce " << k;
    EXPECT_NEAR(apexes[1][k], drop * std::pow(e, 2.0 * static_cast<double>(k + 1)), 0.05 * apexes[1][k])
        << "bounce " << k;
  }
}

// Two mesh tori thrown at each other in free space: momentum and angular momentum kept to
// rounding, energy lost (not gained).
TEST(MeshContact, MeshCollisionsInFreeSpaceConserveMomentum) {
  const MeshBody a = FromMesh(massprops::solids::Torus(0.05, 0.015, 16), 1000, Vector3(-0.1, 0, 0));
  const MeshBody c = FromMesh(massprops::solids::Torus(0.05, 0.015, 16), 700, Vector3(0.1, 0.02, 0.01));
  ContactWorld w;
  RigidBody ba = a.body, bc = c.body;
  ba.velocity = Vector3(1, 0, 0);
  bc.velocity = Vector3(-1, 0.1, 0);
  bc.angular_momentum = Vector3(0, 0, 1e-4);
  w.AddBody(ba, Of(a.shape, Mat(0.5, 0.4, 0.5)));
  w.AddBody(bc, Of(c.shape, Mat(0.5, 0.4, 0.5)));
  const Diagnostics before = w.world().Diagnose();
  int touching = 0;
  Simulate(w, 1e-3, 300, [&](int) { touching += w.stats().contacts > 0; });
  const Diagnostics after = w.world().Diagnose();
  EXPECT_GT(touching, 0);
  EXPECT_LT((after.linear_momentum - before.linear_momentum).norm(), 1e-12 * before.linear_momentum.norm() + 1e-15);
  EXPECT_LT((after.angular_momentum - before.angular_momentum).norm(), 1e-12 + 1e-9 * before.angular_momentum.norm());
  EXPECT_LT(after.total_energy, before.total_energy);
}

// A polyhedral ball thrown with backspin: as its mesh and as the same polyhedron's convex collider
// it slides, then rolls, at the same time and speed (within 2 %), and both near the sphere's closed
// form t* = 2(v0 + rω0)/(7μg), v = (5v0 − 2rω0)/7 (within 5 %: the facets' bumping).
TEST(MeshContact, MeshBallWithBackspinAsTheSamePolyhedron) {
  const double r = 0.1, v0 = 3, w0 = 10, mu = 0.2;
  const MeshBody b = FromMesh(massprops::solids::Sphere(r, 32), 1000, Vector3(0, 0, r));
  const shape::Convex polyhedron{b.shape.vertices, b.shape.triangles};
  std::vector<double> speeds;
  for (const Shape& collider : {Shape(b.shape), Shape(polyhedron)}) {
    ContactWorld w;
    RigidBody body = b.body;
    body.velocity = Vector3(v0, 0, 0);
    body.SetAngularVelocity(Vector3(0, -w0, 0));
    w.AddBody(body, Of(collider, Mat(mu, mu)));
    w.AddGround({Vector3::UnitZ(), 0, Mat(mu, mu)});
    w.AddForce(Gravity(Vector3(0, 0, -kG)));
    Simulate(w, 1e-4, 8000);  // t* = 0.87 s
    speeds.push_back(w.world().bodies()[0].velocity.x());
  }
  EXPECT_NEAR(speeds[0], speeds[1], 0.02 * speeds[1]);
  const double v_final = (5 * v0 - 2 * r * w0) / 7;
  EXPECT_NEAR(speeds[1], v_final, 0.05 * v_final);
}

TEST(MeshContact, MeshBoxRestsOnATable) {
  const Vector3 half(0.05, 0.04, 0.03);
  const MeshBody b =
      FromMesh(massprops::Triangulate(massprops::solids::Box(2 * half)), 700, Vector3(0.02, 0, 0.2 + half.z() + 0.02));
  ContactWorld w;
  w.AddBody(b.body, Of(b.shape, Mat(0.6, 0.5)));
  w.AddStatic(Of(shape::Box{Vector3(0.3, 0.3, 0.1)}, Mat(0.6, 0.5)), Matrix3::Identity(), Vector3(0, 0, 0.1));
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  double deepest = 0;
  Simulate(w, 1e-3, 1000, [&](int) { deepest = std::max(deepest, w.stats().max_penetration); });
  const Vector3 settled = w.world().bodies()[0].position;
  Simulate(w, 1e-3, 4000, [&](int) { deepest = std::max(deepest, w.stats().max_penetration); });
  const RigidBody& r = w.world().bodies()[0];
  EXPECT_LT(r.velocity.norm(), 1e-4);
  EXPECT_LT((r.position - settled).norm(), 1e-3);
  EXPECT_NEAR(r.position.z(), 0.2 + half.z(), 5e-4);
  EXPECT_LT(deepest, 0.5 * DescribeMeshField(b.shape).cell);
}

// A torus ring (inner radius 35 mm) dropped over a peg of radius 34.5 mm: as itself it slides down
// the peg to the ground, its center within the 0.5 mm of clearance of the axis; as its convex hull
// (what MuJoCo, Bullet and Jolt collide) it lands on top of the peg.
TEST(MeshContact, RingSlidesDownAPegThatItsHullCannotPass) {
  const double R = 0.045, a = 0.01, peg_r = 0.0345, peg_h = 0.3;
  const massprops::TriangleMesh torus = massprops::solids::Torus(R, a, 32);
  for (bool hull : {false, true}) {
    MeshBody ring = FromMesh(torus, 1200, Vector3(0.0002, 0, peg_h + 0.05));
    Collider c = Of(ring.shape, Mat(0.3, 0.2));
    if (hull) {
      massprops::PolygonMesh pm;
      pm.V.resize(static_cast<Eigen::Index>(ring.shape.vertices.size()), 3);
      for (std::size_t i = 0; i < ring.shape.vertices.size(); ++i)
        pm.V.row(static_cast<Eigen::Index>(i)) = ring.shape.vertices[i].transpose();
      for (const auto& t : ring.shape.triangles) pm.AddFace(t);
      const massprops::PolygonMesh h = massprops::ConvexHull(pm);
      shape::Convex cv;
      for (Eigen::Index i = 0; i < h.V.rows(); ++i) cv.vertices.push_back(h.V.row(i).transpose());
      for (std::int64_t f = 0; f < h.num_faces(); ++f) {
        cv.triangles.push_back({h.indices[static_cast<std::size_t>(h.offsets[f])],
                                h.indices[static_cast<std::size_t>(h.offsets[f] + 1)],
                                h.indices[static_cast<std::size_t>(h.offsets[f] + 2)]});
      }
      c.shape = cv;
    }
    ContactWorld w;
    w.AddBody(ring.body, c);
    w.AddStatic(Of(shape::Cylinder{peg_r, peg_h / 2}, Mat(0.3, 0.2)), Matrix3::Identity(), Vector3(0, 0, peg_h / 2));
    w.AddGround({Vector3::UnitZ(), 0, Mat(0.3, 0.2)});
    w.AddForce(Gravity(Vector3(0, 0, -kG)));
    double deepest = 0;
    Simulate(w, 5e-4, hull ? 1000 : 3000,  // the hull lands within 0.2 s (and its 2000-corner SAT is slow)
             [&](int) { deepest = std::max(deepest, w.stats().max_penetration); });
    const RigidBody& b = w.world().bodies()[0];
    if (!hull) {
      EXPECT_LT(deepest, 0.5 * DescribeMeshField(ring.shape).cell);
      EXPECT_LT(b.position.head<2>().norm(), 1e-3) << "off the axis";
      EXPECT_LT(b.position.z(), a + 0.002) << "not down the peg";
    } else {
      EXPECT_GT(b.position.z(), peg_h) << "the hull passed the peg";
    }
  }
}

// The cup of data/meshes (10 cm, walls and bottom 6.6 mm) stands upright on a table and keeps a
// ball dropped into it.
TEST(MeshContact, CupStandsAndHoldsABall) {
  massprops::LoadedMesh loaded = massprops::ReadMeshFile(std::string(MASSPROPS_DATA_DIR) + "/meshes/cube_cup_quad.obj");
  const massprops::TriangleMesh cup_mesh = massprops::Triangulate(loaded.mesh);
  const MeshBody cup = FromMesh(cup_mesh, 1100, Vector3::Zero());
  ContactWorld w;
  const Vector3 com = cup.mesh_to_body.Inverse().Apply(Vector3::Zero());  // in the mesh frame
  RigidBody cb = cup.body;
  cb.position = com + Vector3(0, 0, 0.001);  // the mesh's bottom is at z = 0: 1 mm above the table
  w.AddBody(cb, Of(cup.shape, Mat(0.6, 0.5)));
  w.AddGround({Vector3::UnitZ(), 0, Mat(0.6, 0.5)});
  RigidBody ball;
  const double r = 0.015;
  ball.mass = 1000 * 4.0 / 3 * massprops::kPi * r * r * r;
  ball.inertia = Vector3::Constant(0.4 * ball.mass * r * r);
  ball.position = Vector3(0.01, 0.005, 0.2);
  w.AddBody(ball, Of(shape::Sphere{r}, Mat(0.6, 0.5, 0.3)));
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  double deepest = 0;
  Simulate(w, 1e-3, 3000, [&](int) { deepest = std::max(deepest, w.stats().max_penetration); });
  const RigidBody& c = w.world().bodies()[0];
  const RigidBody& b = w.world().bodies()[1];
  const double tilt = std::acos(std::min(1.0, (c.Rotation() * cup.mesh_to_body.rotation.transpose()).col(2).z()));
  EXPECT_LT(tilt, massprops::kPi / 180) << "tilted";
  EXPECT_LT((c.position - cb.position).head<2>().norm(), 1e-3) << "drifted";
  const Vector3 in_cup = cup.mesh_to_body.Inverse().Apply(c.Rotation().transpose() * (b.position - c.position));
  EXPECT_LT(std::abs(in_cup.x()), 0.05) << "the ball left the cup";
  EXPECT_LT(std::abs(in_cup.y()), 0.05);
  EXPECT_LT(in_cup.z(), 0.1);
  EXPECT_GT(in_cup.z(), 0.0);
  EXPECT_LT(deepest, 0.5 * DescribeMeshField(cup.shape).cell);
}

// No tunnelling: a 1 cm mesh ball at 30 m/s (3 cm a step, three times its size) against a 4 mm
// mesh plate stops on it. Contacts are made within the step's reach (speculative), and the
// field's distance beyond its grid is a bound from below, so the approach is never missed.
TEST(MeshContact, FastMeshBallDoesNotTunnelThroughAThinMeshPlate) {
  const double r = 0.01;
  const MeshBody ball = FromMesh(massprops::solids::Sphere(r, 12), 1000, Vector3(0, 0, 0.05));
  const MeshBody plate =
      FromMesh(massprops::Triangulate(massprops::solids::Box(Vector3(0.2, 0.2, 0.004))), 1000, Vector3::Zero());
  ContactWorld w;
  RigidBody b = ball.body;
  b.velocity = Vector3(0, 0, -30);
  w.AddBody(b, Of(ball.shape));
  w.AddStatic(Of(plate.shape));
  double lowest = 1;
  Simulate(w, 1e-3, 20, [&](int) { lowest = std::min(lowest, w.world().bodies()[0].position.z()); });
  EXPECT_GT(lowest, 0.002 + 0.9 * r);                          // on the plate's top (z = 2 mm), to the ball's facets
  EXPECT_NEAR(w.world().bodies()[0].velocity.z(), 0.0, 1e-3);  // stopped from 30 m/s (it may slide on a facet)
}

TEST(MeshContact, OpenMeshesAreRefused) {
  massprops::TriangleMesh m = massprops::solids::Sphere(0.1, 8);
  std::vector<Vector3> v;
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) v.push_back(m.V.row(i).transpose());
  std::vector<std::array<int, 3>> t;
  for (Eigen::Index f = 1; f < m.F.rows(); ++f) t.push_back({m.F(f, 0), m.F(f, 1), m.F(f, 2)});
  EXPECT_THROW(MakeMesh(v, t), std::invalid_argument);
  ContactWorld w;
  EXPECT_THROW(w.AddStatic(Of(shape::Mesh{v, t, 0, nullptr})), std::invalid_argument);
}

}  // namespace
}  // namespace dynamics
