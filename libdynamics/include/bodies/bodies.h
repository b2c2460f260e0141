#pragma once
// One body builder (target massprops::bodies): what a body is made of — a mesh file, an implicit
// shape or a closed-form solid — to its mass properties, its display mesh and its collider, for
// rbsim's scenes, `rbsim poses` and the Python module alike.
//
//   dynamics::BodyBuilder builder(massprops::report::WordsFor(massprops::report::FrontEnd::kScene));
//   dynamics::BuiltShape part = builder.Load(shape, warnings);       // mass properties, display mesh
//   auto collider = builder.ColliderOf(collision, shape, part);      // in the principal frame
//   dynamics::RigidBody body = dynamics::BodyFromMassProperties(part.mp, part.principal).body;

#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "dynamics/contact.h"
#include "massprops/implicit.h"
#include "massprops/mass_spec.h"
#include "massprops/mesh.h"
#include "massprops/primitive.h"
#include "massprops/principal_axes.h"
#include "massprops/units.h"
#include "massprops/wording.h"

namespace massprops {
struct SolidResult;  // massprops/io/load.h
}  // namespace massprops

namespace dynamics {

/// A closed mesh file, checked by massprops' pipeline (whole: the display mesh needs it).
struct MeshSource {
  std::string path;
  bool repair = false;
  bool allow_open = false;
  /// The file's parts (OBJ groups, glTF/3MF nodes, CAD solids) each computed on its own and the
  /// whole as their composition (massprops::LoadOptions::parts: each part's own density).
  bool parts = false;
  /// With parts: this part alone (its index in the file's parts), where the file places it; -1:
  /// the whole.
  int part = -1;
};

/// A shape in massprops' shape syntax, parsed once; mass properties by quasi-Monte Carlo.
struct ImplicitSource {
  std::string text;  ///< as written, for descriptions
  massprops::ImplicitPtr shape;
};

/// What a body is made of, in which unit, and how heavy.
struct BodyShape {
  std::variant<MeshSource, ImplicitSource, massprops::Primitive> source;
  massprops::LengthUnit unit = massprops::LengthUnit::kMetre;  ///< of the mesh or the shape
  bool unit_stated = false;  ///< the unit was given (else implausible sizes draw a warning)
  massprops::MassSpec mass = massprops::Density{1000.0};

  const massprops::Primitive* solid() const { return std::get_if<massprops::Primitive>(&source); }
};

/// What a body collides as.
enum class CollisionKind {
  kAuto,       ///< a box, sphere, capsule or cylinder solid as itself; anything else: no contact
  kNone,       ///< passes through everything
  kHull,       ///< the convex hull of its mesh (or of its solid's or shape's tessellation)
  kMesh,       ///< its closed mesh (or its solid's tessellation) as it is: a signed distance field
  kPrimitive,  ///< the primitive given, centred on the center of mass, in the mesh's axes
  /// As itself: a box, sphere, capsule or cylinder solid as that primitive; any other shape as its
  /// convex hull when it is convex (the hull's volume is its own), else as its mesh (kMesh).
  kItself,
};

struct CollisionSpec {
  CollisionKind kind = CollisionKind::kAuto;
  std::optional<massprops::Primitive> primitive;  ///< kPrimitive: a box, sphere, capsule or cylinder
  Material material;
};

/// True for the solids that collide as themselves: box, sphere, capsule and cylinder.
bool CollidesAsItself(const massprops::Primitive& p);

/// A body's shape, loaded.
struct BuiltShape {
  massprops::MassProperties mp;           ///< SI, in the mesh (or solid) frame M
  massprops::PrincipalInertia principal;  ///< axes = R_MB
  massprops::TriangleMesh display;        ///< metres, mesh axes, relative to the center of mass
  std::string source;                     ///< "spot.obj (unit m, 5856 triangles)", "cone r=0.1 h=0.3"
};

/// A shape that cannot be a body. field(): which part of the description is at fault ("mesh",
/// "implicit", "solid", or empty for the body as a whole); what(): the fault, worded in the
/// builder's vocabulary.
class BodyError : public std::runtime_error {
 public:
  BodyError(std::string field, const std::string& what) : std::runtime_error(what), field_(std::move(field)) {}
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

/// A finding that does not stop the build, with the field it concerns (as BodyError::field).
struct BodyWarning {
  std::string field;
  std::string text;
};

class BodyBuilder {
 public:
  /// `words`: the caller's names for the options findings advise (massprops::report::WordsFor).
  explicit BodyBuilder(massprops::Vocabulary words, int threads = 1);

  /// Mass properties and display mesh: a mesh file through massprops' pipeline (full check), an
  /// implicit shape by quasi-Monte Carlo to a relative standard error of 1e-4 (and a surface by
  /// marching tetrahedra), a solid from its closed form (and a tessellation). A mesh file read
  /// before with the same unit, mass and checks is not read again (its findings were given the
  /// first time). @throws BodyError.
  BuiltShape Load(const BodyShape& shape, std::vector<BodyWarning>& warnings);

  /// The collider of a loaded shape in its principal frame (x_B = R_MBᵀ (x_M − com)), or none.
  /// Mesh colliders of equal display meshes share one signed distance field.
  std::optional<Collider> ColliderOf(const CollisionSpec& collision, const BodyShape& shape, const BuiltShape& built);

 private:
  BuiltShape LoadMeshFile(const MeshSource& m, const BodyShape& shape, std::vector<BodyWarning>& warnings);
  massprops::Vocabulary words_;
  int threads_;
  std::map<std::string, shape::Mesh> meshes_;  // by the display mesh's bytes
  std::map<std::string, BuiltShape> files_;    // mesh files (and parts) read, by path and options
  std::map<std::string, std::shared_ptr<const massprops::SolidResult>> assemblies_;  // files read by parts
};

}  // namespace dynamics
