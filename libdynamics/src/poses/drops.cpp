// Drops: a part released from random orientations onto a ground plane, simulated until it rests,
// and classified by the hull face it rests on (poses.h).

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dynamics/forces.h"
#include "dynamics/poses.h"
#include "massprops/parallel.h"

namespace dynamics::poses {
namespace {

using massprops::kPi;

std::uint64_t SplitMix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

// A double in [0, 1) from the top 53 bits.
double Unit(std::uint64_t x) { return static_cast<double>(x >> 11) * 0x1.0p-53; }

void CheckOptions(const DropOptions& o) {
  auto positive = [](double x, const char* name) {
    if (!(x > 0) || !std::isfinite(x)) throw std::invalid_argument(std::string("drops: ") + name + " must be positive");
  };
  if (!(o.height >= 0) || !std::isfinite(o.height)) throw std::invalid_argument("drops: height must be >= 0");
  positive(o.dt, "dt");
  positive(o.max_time, "max_time");
  positive(o.rest_speed, "rest_speed");
  positive(o.rest_time, "rest_time");
  if (!(o.face_tolerance_degrees > 0 && o.face_tolerance_degrees < 45))
    throw std::invalid_argument("drops: face_tolerance_degrees must be in (0, 45)");
  if (o.threads < 0) throw std::invalid_argument("drops: threads must be >= 0");
}

// One drop, start to rest. `placed`: the part's body (frame B: principal axes at the center of
// mass; its orientation R_MB, the principal axes in part axes); `collider` in frame B.
DropOutcome RunOne(const Part& part, const Estimate& estimate, const DropOptions& o, const PlacedBody& placed,
                   const Collider& collider, std::int64_t k) {
  const Matrix3 R_MB = placed.body.orientation.toRotationMatrix();
  const Vector3 c = part.mass_properties.center_of_mass;
  const Quaternion q_WM = DropOrientation(o.seed, k);
  double lowest = std::numeric_limits<double>::infinity();
  for (const Vector3& v : part.hull_vertices) lowest = std::min(lowest, (q_WM * (v - c)).z());

  ContactOptions contact;
  contact.sleeping = true;
  contact.sleep_speed = o.rest_speed;
  contact.sleep_time = o.rest_time;
  ContactWorld world(World(), contact);
  world.set_num_threads(1);
  world.AddGround(Ground{Vector3::UnitZ(), 0.0, o.ground});
  world.AddForce(Gravity(Vector3(0, 0, -9.80665)));
  RigidBody body = placed.body;
  body.position = Vector3(0, 0, o.height - lowest);
  body.orientation = (q_WM * Quaternion(R_MB)).normalized();
  world.AddBody(body, collider);

  DropOutcome out;
  const auto steps = static_cast<std::int64_t>(std::ceil(o.max_time / o.dt));
  bool rested = false;
  for (std::int64_t s = 0; s < steps && !rested; ++s) {
    const StepStatus status = world.Step(o.dt);
    if (!status.ok) throw std::runtime_error("drop " + std::to_string(k) + ": " + status.message);
    rested = world.stats().sleeping == 1;
  }
  const RigidBody& end = world.world().bodies()[0];
  out.time = world.world().time();
  out.orientation = (end.orientation * Quaternion(R_MB).conjugate()).normalized();
  out.position = end.position - out.orientation * c;
  if (!rested) return out;
  const Vector3 down = out.orientation.conjugate() * -Vector3::UnitZ();  // in part axes
  const HullFaces& faces = estimate.faces;
  std::size_t best = 0;
  for (std::size_t f = 1; f < faces.normals.size(); ++f)
    if (faces.normals[f].dot(down) > faces.normals[best].dot(down)) best = f;
  const bool flat = faces.normals[best].dot(down) >= std::cos(o.face_tolerance_degrees * kPi / 180);
  out.pose = flat && faces.pose_of[best] >= 0 ? faces.pose_of[best] : DropOutcome::kOtherFace;
  return out;
}

}  // namespace

Quaternion DropOrientation(std::uint64_t seed, std::int64_t k) {
  const std::uint64_t key = SplitMix64(seed ^ SplitMix64(static_cast<std::uint64_t>(k)));
  const double u1 = Unit(SplitMix64(key + 1)), u2 = Unit(SplitMix64(key + 2)), u3 = Unit(SplitMix64(key + 3));
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  return Quaternion(b * std::cos(2 * kPi * u3), a * std::sin(2 * kPi * u2), a * std::cos(2 * kPi * u2),
                    b * std::sin(2 * kPi * u3));
}

std::vector<DropOutcome> Drop(const Part& part, const Estimate& estimate, const DropOptions& options,
                              std::int64_t first, std::int64_t count) {
  CheckOptions(options);
  if (first < 0 || count < 0) throw std::invalid_argument("drops: first and count must be >= 0");
  if (estimate.faces.normals.empty()) throw std::invalid_argument("drops: the estimate has no hull faces");
  const PlacedBody placed = BodyFromMassProperties(part.mass_properties);
  const Matrix3 R_MB = placed.body.orientation.toRotationMatrix();
  const Vector3 c = part.mass_properties.center_of_mass;
  // The collider in frame B: x_B = R_MBᵀ (x_M − c).
  Collider collider;
  if (part.collider) {
    collider = *part.collider;
  } else {
    collider.shape = shape::Convex{part.hull_vertices, part.hull_triangles};
    collider.material = part.material;
  }
  collider.translation = R_MB.transpose() * (collider.translation - c);
  collider.rotation = R_MB.transpose() * collider.rotation;
  if (auto* convex = std::get_if<shape::Convex>(&collider.shape); convex != nullptr && convex->polytope == nullptr) {
    *convex = MakeConvex(std::move(convex->vertices), std::move(convex->triangles));  // once for every drop
  }
  if (auto* mesh = std::get_if<shape::Mesh>(&collider.shape); mesh != nullptr && mesh->field == nullptr) {
    *mesh = MakeMesh(std::move(mesh->vertices), std::move(mesh->triangles), mesh->cell, options.threads);  // once
  }

  std::vector<DropOutcome> out(static_cast<std::size_t>(count));
  massprops::ParallelForBlocks(count, options.threads, [&](std::int64_t i) {
    out[static_cast<std::size_t>(i)] = RunOne(part, estimate, options, placed, collider, first + i);
  });
  return out;
}

}  // namespace dynamics::poses
