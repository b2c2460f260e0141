// An rbsim scene in Bullet (Debian's libbullet-dev 3.24, its double-precision build): the bodies
// as btRigidBody with their own mass and principal moments, their solids as Bullet's box, sphere,
// capsule and cylinder shapes, ground planes as btStaticPlaneShape, static boxes and hulls as
// static btBoxShape and btConvexHullShape, gravity; Bullet's defaults
// otherwise (btDiscreteDynamicsWorld, sequential impulses, 10 iterations, split impulse). Writes
// rbsim's trajectory CSV and one line of timing. A comparison tool: never a dependency of the
// libraries.
//
//   bullet_peer SCENE.json [--dt S] [--out trajectory.csv]
//
// Convex hulls: btConvexHullShape with a margin of 1 % of the hull's size (below).
// Materials (README "Peers"): Bullet keeps one friction coefficient and one restitution per body
// and multiplies them for a contact; a contact callback combines them as rbsim does instead
// (geometric mean of the kinetic coefficients, the larger restitution). Bullet has one friction
// coefficient: the kinetic one is given.

#include <cmath>
#include <iostream>
#include <memory>

#include <btBulletDynamicsCommon.h>

#include "peer_scene.h"

namespace {

using peers::PeerBody;
using peers::Vector3;

btVector3 Bt(const Vector3& v) { return btVector3(v.x(), v.y(), v.z()); }
Vector3 Ei(const btVector3& v) { return Vector3(v.x(), v.y(), v.z()); }

// rbsim's pair rule, applied to every new contact point (bodies carry their own coefficients).
bool CombineAsRbsim(btManifoldPoint& cp, const btCollisionObjectWrapper* a, int, int, const btCollisionObjectWrapper* b,
                    int, int) {
  const btCollisionObject* oa = a->getCollisionObject();
  const btCollisionObject* ob = b->getCollisionObject();
  const dynamics::Material m = dynamics::CombineMaterials({oa->getFriction(), oa->getFriction(), oa->getRestitution()},
                                                          {ob->getFriction(), ob->getFriction(), ob->getRestitution()});
  cp.m_combinedFriction = m.kinetic_friction;
  cp.m_combinedRestitution = m.restitution;
  return true;
}

std::unique_ptr<btCollisionShape> ShapeOf(const PeerBody& b) {
  switch (b.kind) {
    case PeerBody::Kind::kBox: return std::make_unique<btBoxShape>(Bt(b.half_extents));
    case PeerBody::Kind::kSphere: return std::make_unique<btSphereShape>(b.radius);
    case PeerBody::Kind::kCapsule: return std::make_unique<btCapsuleShapeZ>(b.radius, 2 * b.half_length);
    case PeerBody::Kind::kCylinder:
      return std::make_unique<btCylinderShapeZ>(btVector3(b.radius, b.radius, b.half_length));
    case PeerBody::Kind::kHull: {
      // The one default not kept: a hull's collision margin lies outside its points (a box's lies
      // inside its extents), and 4 cm would make a 10 cm hull an 18 cm pebble: 1 % of its size.
      auto hull = std::make_unique<btConvexHullShape>();
      double size = 0;
      for (const Vector3& v : b.hull) {
        hull->addPoint(Bt(v), false);
        size = std::max(size, v.norm());
      }
      hull->setMargin(std::min<double>(hull->getMargin(), 0.01 * size));
      hull->recalcLocalAabb();
      return hull;
    }
  }
  return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  peers::PeerArgs args;
  peers::PeerScene scene;
  if (const int status = peers::StartPeer(argc, argv, "bullet_peer", args, scene); status >= 0) return status;
  gContactAddedCallback = CombineAsRbsim;
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
  world.setGravity(Bt(scene.gravity));

  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  auto add = [&](std::unique_ptr<btCollisionShape> shape, double mass, const btVector3& inertia,
                 const btTransform& pose, const dynamics::Material& m) {
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape.get(), inertia);
    info.m_startWorldTransform = pose;
    info.m_friction = m.kinetic_friction;
    info.m_restitution = m.restitution;
    auto body = std::make_unique<btRigidBody>(info);
    body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
    world.addRigidBody(body.get());
    shapes.push_back(std::move(shape));
    bodies.push_back(std::move(body));
    return bodies.back().get();
  };
  for (const scene::GroundSpec& g : scene.grounds) {
    btTransform identity;
    identity.setIdentity();
    add(std::make_unique<btStaticPlaneShape>(Bt(g.normal), g.offset), 0, btVector3(0, 0, 0), identity, g.material);
  }
  for (const peers::PeerStatic& st : scene.statics) {
    btTransform pose;
    pose.setIdentity();
    std::unique_ptr<btCollisionShape> shape;
    if (st.box) {
      const Eigen::Quaterniond& q = st.orientation;
      pose = btTransform(btQuaternion(q.x(), q.y(), q.z(), q.w()), Bt(st.position));
      shape = std::make_unique<btBoxShape>(Bt(st.half_extents));
    } else {  // its corners (world) about their centroid, which places it
      Vector3 centre = Vector3::Zero();
      for (const Vector3& v : st.hull) centre += v / static_cast<double>(st.hull.size());
      PeerBody as_hull;
      as_hull.kind = PeerBody::Kind::kHull;
      for (const Vector3& v : st.hull) as_hull.hull.push_back(v - centre);
      shape = ShapeOf(as_hull);
      pose.setOrigin(Bt(centre));
    }
    add(std::move(shape), 0, btVector3(0, 0, 0), pose, st.material);
  }
  std::vector<btRigidBody*> moving;
  for (const PeerBody& b : scene.bodies) {
    const Eigen::Quaterniond& q = b.orientation;
    const btTransform pose(btQuaternion(q.x(), q.y(), q.z(), q.w()), Bt(b.position));
    btRigidBody* body = add(ShapeOf(b), b.mass, Bt(b.inertia), pose, b.material);
    body->setLinearVelocity(Bt(b.velocity));
    body->setAngularVelocity(Bt(b.omega));
    body->setActivationState(DISABLE_DEACTIVATION);  // rbsim does not sleep unless the scene asks
    moving.push_back(body);
  }

  peers::TrajectoryCsv csv;
  double time = 0;
  auto sample = [&] {
    for (std::size_t i = 0; i < moving.size(); ++i) {
      const btTransform& t = moving[i]->getWorldTransform();
      const btQuaternion r = t.getRotation();
      csv.Add(time, scene.bodies[i], Ei(t.getOrigin()), Eigen::Quaterniond(r.w(), r.x(), r.y(), r.z()),
              Ei(moving[i]->getLinearVelocity()), Ei(moving[i]->getAngularVelocity()));
    }
  };
  std::int64_t steps = 0;
  const double seconds = peers::RunPeer(
      scene, args,
      [&] {
        world.stepSimulation(scene.dt, 0);  // one step of exactly dt
        time = static_cast<double>(++steps) * scene.dt;
      },
      sample);
  peers::PrintTiming("bullet", "3.24 (double)", scene, seconds);
  for (auto& b : bodies) world.removeRigidBody(b.get());
  if (!args.out.empty() && !csv.Write(args.out)) return 1;
  return 0;
}
