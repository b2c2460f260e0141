#pragma once
/// @file
/// Robot descriptions (target massprops::robot): every link's inertial of a URDF, SDFormat or
/// MJCF file computed from its geometries and written back, the rest of the file kept.
///
/// A link's geometries are its `<collision>` elements (or `<visual>`) in URDF and SDFormat, and
/// the geoms of an MJCF body (those that collide, or those that do not). Meshes go through the
/// pipeline of load.h (read, check, integrate) and are scaled and placed by the element's scale
/// and pose; boxes, spheres, cylinders, capsules and ellipsoids take their closed forms. A link's
/// geometries are taken to be disjoint: their mass properties add.
///
/// Inertials are written in each format's convention: URDF and SDFormat get the tensor about the
/// center of mass in the link's axes (ixy = I_xy, the negated product of inertia); MJCF gets
/// `pos`, `quat` (link axes to principal axes) and `diaginertia`.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "massprops/io/load.h"
#include "massprops/io/mesh_io.h"
#include "massprops/mass_properties.h"
#include "massprops/mass_spec.h"
#include "massprops/principal_axes.h"

namespace massprops {

enum class RobotFormat { kUrdf, kSdf, kMjcf };
/// "urdf", "sdf", "mjcf".
const char* RobotFormatName(RobotFormat format);

/// Which geometries make a link's mass.
enum class GeometrySource {
  kCollision,  ///< URDF/SDF <collision>; MJCF geoms that collide (contype or conaffinity non-zero)
  kVisual,     ///< URDF/SDF <visual>; MJCF geoms that do not collide
  kAll,        ///< MJCF: every geom, as MuJoCo's inertiafromgeom counts them; URDF/SDF: as kCollision
};

struct FillOptions {
  double density = 1000.0;  ///< kg/m^3, for links without an entry in `link_masses`
  /// Per link, by name or glob (first match wins): a density, or the link's total mass.
  std::vector<PartMass> link_masses;
  /// Keep the mass each link's inertial states and fill only the center of mass and inertia
  /// (the geometry's mass distribution scaled to it). Links without a mass take the density.
  bool keep_mass = false;
  GeometrySource from = GeometrySource::kCollision;
  /// Roots for `package://NAME/...` (URDF) and `model://NAME/...` (SDFormat): NAME → folder.
  /// Unmapped names are looked for among the robot file's ancestor folders (a folder called NAME,
  /// or one whose package.xml names NAME), then in SDF's model paths (GZ_SIM_RESOURCE_PATH,
  /// IGN_GAZEBO_RESOURCE_PATH, SDF_PATH, GAZEBO_MODEL_PATH).
  std::vector<std::pair<std::string, std::string>> packages;
  /// How meshes are read and checked (repair, allow_open, threads, ...). Their unit is the
  /// metre (as all three formats define it) unless the mesh file declares another; `mass` and
  /// `parts` are ignored.
  LoadOptions load;
};

enum class LinkStatus {
  kFilled,      ///< its inertial was written
  kNoGeometry,  ///< nothing to compute from: left as it is
  kFailed,      ///< a geometry could not be computed (message): left as it is
};

struct LinkFill {
  std::string name;
  LinkStatus status = LinkStatus::kNoGeometry;
  Advice message;     ///< why it failed (naming options as markers, wording.h); empty otherwise
  MassProperties mp;  ///< SI, in the link frame
  PrincipalInertia principal;
  int geometries = 0;         ///< how many were composed
  std::vector<Advice> notes;  ///< the mesh pipeline's findings (option markers), choices made
};

struct FillResult {
  RobotFormat format = RobotFormat::kUrdf;
  std::string document;  ///< the whole file, with the filled inertials
  std::vector<LinkFill> links;
  std::vector<std::string> notes;  ///< about the file as a whole
  bool AllFilled() const;          ///< no link failed
};

/// The format of a robot description, from its root element (<robot>, <sdf>, <mujoco>).
/// @throws std::runtime_error naming the file when it is none of the three.
RobotFormat DetectRobotFormat(const std::string& path);

/// Reads `path`, computes every link's mass properties and returns the filled document.
/// Links that cannot be computed are reported, not thrown.
/// @throws FileAccessError (io.h) when the file cannot be opened or is not a regular file;
///         std::runtime_error naming the file when it cannot be parsed as XML, or uses a
///         construct this reader does not follow (MJCF <include>); std::invalid_argument for a
///         bad option or a density-map entry that matches no link.
FillResult FillRobotDescription(const std::string& path, const FillOptions& options = {});

/// A package mapping as front ends take it, "NAME=DIR" (`--package`): {NAME, DIR}; none when
/// the text is not of that form (an empty name or folder, no '=').
std::optional<std::pair<std::string, std::string>> PackageMapping(const std::string& text);

}  // namespace massprops
