#pragma once
// The pieces of massprops::robot: what a link is made of, read from each format (urdf.cpp,
// sdf.cpp, mjcf.cpp), and the helpers they share (xml.cpp). fill.cpp computes and writes.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <pugixml.hpp>

#include "massprops/primitive.h"
#include "massprops/robot/robot.h"
#include "massprops/robot/robot_model.h"

namespace massprops::robot {

struct MeshRef {
  std::string path;  ///< resolved to a file
  Vector3 scale = Vector3::Ones();
};

/// One geometry of a link: its shape in its own frame, placed in the link frame by x ↦ R x + t.
struct Geometry {
  std::variant<Primitive, MeshRef> shape;
  Matrix3 rotation = Matrix3::Identity();
  Vector3 translation = Vector3::Zero();
  std::optional<MassSpec> own;                 ///< MJCF: the geom's own density or mass
  bool massless = false;                       ///< MJCF: mass or density 0 — it collides, but adds no mass
  std::uint32_t contype = 1, conaffinity = 1;  ///< MJCF's collision bits
  std::optional<double> friction;              ///< MJCF: the sliding friction MuJoCo gives it
  std::string name;                            ///< MJCF: the geom's name attribute (for <contact><pair>)
  std::string where;                           ///< "collision 'base_box'", for messages
};

struct Link {
  std::string name;
  pugi::xml_node element;  ///< the link (URDF, SDF) or body (MJCF) element
  std::vector<Geometry> geometries;
  std::optional<double> stated_mass;  ///< the mass its inertial states now
  std::string error;                  ///< a geometry that could not be understood
  std::vector<std::string> notes;
};

struct Document {
  std::string path;
  std::string dir;   ///< the folder of `path`, for relative references
  std::string text;  ///< the file's bytes
  pugi::xml_document xml;
  std::vector<std::string> notes;
  std::vector<std::string> simulation_notes;  ///< for a simulator only (ReadRobotModel), not `massprops fill`
};

/// A fault in one element, with the element named; caught per link.
struct ElementError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The name of an element for messages: its name attribute, else "<tag> #k" (k-th of its kind).
std::string Describe(pugi::xml_node element, int k);

/// Each `tag` child of the link's element read by read(element, "collision 'name'") into
/// link.geometries; the first fault stops there and becomes link.error.
template <typename Read>
void ReadGeometries(Link& link, const char* tag, const Read& read) {
  int k = 0;
  for (pugi::xml_node geometry : link.element.children(tag)) {
    ++k;
    try {
      link.geometries.push_back(read(geometry, Describe(geometry, k)));
    } catch (const ElementError& e) {
      link.error = e.what();
      return;
    }
  }
}

/// Reads `path` into doc (comments and blanks kept). @throws FileAccessError, std::runtime_error.
void Parse(Document& doc, const std::string& path);
/// The same from the file's text (a filled document).
void ParseText(Document& doc, const std::string& path, std::string text);
/// The format of a parsed document, from its root element. @throws std::runtime_error.
RobotFormat FormatOf(const Document& doc);

std::vector<Link> UrdfLinks(Document& doc, const FillOptions& options);
std::vector<Link> SdfLinks(Document& doc, const FillOptions& options);
std::vector<Link> MjcfLinks(Document& doc, const FillOptions& options);
/// The kinematic tree (robot_model.h): each link's inertial and frame, the joints; `links` are
/// the format's links in order (their geometries already read), model.links matches them.
/// @throws ElementError naming the element.
void UrdfKinematics(const Document& doc, RobotModel& model);
/// URDF <mimic>s as couplings (after the joints). @throws ElementError naming the joint.
void UrdfMimics(pugi::xml_node root, RobotModel& model);
/// Each link's mass properties from its geometries, as massprops fill computes them (nothing
/// written).
std::vector<LinkFill> ComputeLinkFills(const std::vector<Link>& links, const FillOptions& options);
/// A URDF's massless root links (and the links welded to them) as the world (fixed_base.cpp).
void MasslessRootsAsWorld(RobotModel& model);
void SdfKinematics(const Document& doc, const std::vector<Link>& links, RobotModel& model);
void MjcfKinematics(const Document& doc, const std::vector<Link>& links, RobotModel& model);
/// MuJoCo 3's <replicate>s and <frame>s written out as MuJoCo 2's structure in `doc` (copies; the
/// frames' children moved up, placed through them), noted; for reading a model to simulate.
/// @throws ElementError naming the element.
void MjcfExpandFrames(Document& doc);
/// The closed solid of the <asset><hfield name="name"> (mjcf_hfield.cpp, robot_model.h's
/// RobotTerrain). @throws ElementError naming the asset.
TriangleMesh HfieldSolid(pugi::xml_node root, const std::string& name, const Document& doc, const FillOptions& options);
/// MJCF <option>s: the medium into model.medium; gravity, time step and flags noted (mjcf_option.cpp).
void MjcfOptions(pugi::xml_node root, RobotModel& model);
/// An MJCF element's frame (pos and orientation) in its parent's, as the compiler reads it.
using MjcfFrame = std::function<Placement(pugi::xml_node, const std::string&)>;
/// MJCF <tendon>s and <equality>s into model.tendons, couplings and loops (mjcf_constraints.cpp),
/// after the joints. @throws ElementError naming the element.
void MjcfConstraints(pugi::xml_node root, const std::vector<Link>& links, bool autolimits, const MjcfFrame& frame_of,
                     RobotModel& model);
/// An MJCF range (an actuator's ctrlrange or forcerange, a tendon's range) as its `limited`
/// attribute says: "auto" (the default) is a limit when <compiler autolimits> is on, as for joints'
/// ranges; a range that is not a limit is noted (none). @throws ElementError naming `what`.
std::optional<std::pair<double, double>> MjcfRange(pugi::xml_attribute limited, pugi::xml_attribute range,
                                                   const std::string& what, bool autolimits,
                                                   std::vector<std::string>& notes);
/// The joint type a URDF or SDFormat `type` names, among `allowed` (by RobotJointTypeName).
/// @throws ElementError naming `what` and listing the allowed types.
RobotJointType JointTypeNamed(const std::string& type, const std::vector<RobotJointType>& allowed,
                              const std::string& what);
/// A 3 × 3 inertia tensor from its six elements (ixx ixy ixz iyy iyz izz: the tensor's own
/// entries, products of inertia negated), rotated into the link by R. @throws ElementError.
Matrix3 InertiaTensor(const std::vector<double>& six, const Matrix3& R, const std::string& what);
void WriteUrdfInertial(Link& link, const MassProperties& mp);
void WriteSdfInertial(Link& link, const MassProperties& mp);
void WriteMjcfInertial(Link& link, const MassProperties& mp, const PrincipalInertia& principal);

// Shared helpers (xml.cpp).

/// Exactly `n` numbers, blank-separated. @throws ElementError naming `what`.
std::vector<double> Numbers(const std::string& text, std::size_t n, const std::string& what);
/// As many finite numbers as `text` holds, blank-separated (MJCF's size, gear, gainprm, a key's
/// qpos: MuJoCo reads what it needs). @throws ElementError naming `what` for a word that is no
/// finite number (`expected`, when not 0, the count the message speaks of).
std::vector<double> NumberList(const std::string& text, const std::string& what, std::size_t expected = 0);
/// One finite, positive number. @throws ElementError naming `what`.
double Positive(const std::string& text, const std::string& what);
/// R = Rz(yaw) Ry(pitch) Rx(roll): URDF and SDFormat's fixed-axis roll, pitch, yaw.
Matrix3 FromRollPitchYaw(double roll, double pitch, double yaw);
/// The rotation of a unit quaternion (w, x, y, z), normalized first. @throws ElementError.
Matrix3 FromQuaternion(double w, double x, double y, double z, const std::string& what);
/// A file named by a robot description: package://, model://, file:// or a path (relative to
/// the description's folder). @throws ElementError when it does not resolve to a regular file.
std::string ResolveUri(const std::string& uri, const Document& doc, const FillOptions& options);
/// Replaces `old` (when it exists) by the elements of `snippet`, or inserts them as the first
/// children of `parent`, indented as its other children are.
void ReplaceOrInsert(pugi::xml_node parent, pugi::xml_node old, const std::string& snippet);
/// Every element named `name` under `root`, in document order (without recursion: XML may nest
/// deeper than the stack would hold).
std::vector<pugi::xml_node> FindElements(pugi::xml_node root, const char* name);
/// The first of them, or a null node.
pugi::xml_node FindElement(pugi::xml_node root, const char* name);

}  // namespace massprops::robot
