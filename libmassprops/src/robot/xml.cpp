// Helpers shared by the robot formats: numbers and rotations from attributes, file references,
// and the edit that puts an inertial into a link without disturbing the rest of the file.

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>
#include <vector>

#include <Eigen/Geometry>

#include "robot/robot_internal.h"

namespace massprops::robot {

namespace fs = std::filesystem;

std::vector<double> Numbers(const std::string& text, std::size_t n, const std::string& what) {
  std::vector<double> out = NumberList(text, what, n);
  if (out.size() != n) {
    throw ElementError(what + ": expected " + std::to_string(n) + " numbers, got '" + text + "'");
  }
  return out;
}

std::vector<double> NumberList(const std::string& text, const std::string& what, std::size_t expected) {
  std::vector<double> out;
  const char* p = text.c_str();
  while (true) {
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') ++p;
    if (*p == 0) break;
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p || !std::isfinite(v) || (*end != 0 && *end != ' ' && *end != '\t' && *end != '\n' && *end != '\r')) {
      throw ElementError(what + ": '" + text + "' is not a list of " +
                         (expected > 0 ? std::to_string(expected) + " " : std::string()) + "finite numbers");
    }
    out.push_back(v);
    p = end;
  }
  return out;
}

double Positive(const std::string& text, const std::string& what) {
  const double v = Numbers(text, 1, what)[0];
  if (!(v > 0)) throw ElementError(what + ": must be positive, got '" + text + "'");
  return v;
}

Matrix3 FromRollPitchYaw(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Vector3::UnitZ()) * Eigen::AngleAxisd(pitch, Vector3::UnitY()) *
          Eigen::AngleAxisd(roll, Vector3::UnitX()))
      .toRotationMatrix();
}

Matrix3 FromQuaternion(double w, double x, double y, double z, const std::string& what) {
  Eigen::Quaterniond q(w, x, y, z);
  const double norm = q.norm();
  if (!(norm > 1e-12)) throw ElementError(what + ": a zero quaternion is no rotation");
  q.coeffs() /= norm;
  return q.toRotationMatrix();
}

namespace {

bool IsRegular(const fs::path& p) {
  std::error_code e;
  return fs::is_regular_file(p, e);
}

// The folders an environment variable lists, ':'-separated (empty entries left out).
std::vector<std::string> PathList(const char* variable) {
  std::vector<std::string> out;
  const char* value = std::getenv(variable);
  if (value == nullptr) return out;
  std::stringstream list(value);
  for (std::string dir; std::getline(list, dir, ':');) {
    if (!dir.empty()) out.push_back(dir);
  }
  return out;
}

// Whether folder `dir` is ROS package `name`: its package.xml says <name>NAME</name>.
bool ManifestNames(const fs::path& dir, const std::string& name) {
  std::ifstream manifest(dir / "package.xml");
  if (!manifest) return false;
  std::stringstream text;
  text << manifest.rdbuf();
  return text.str().find("<name>" + name + "</name>") != std::string::npos;
}

// ROS 1's search (rospack): below each folder of ROS_PACKAGE_PATH, a package whose manifest names
// it (or a folder of that name holding a manifest); a package's own folders are not searched
// further, nor hidden ones; folders in name order, 8 levels at most.
std::string SearchRosPackagePath(const std::string& name) {
  for (const std::string& root : PathList("ROS_PACKAGE_PATH")) {
    std::vector<std::pair<fs::path, int>> stack{{fs::path(root), 0}};
    while (!stack.empty()) {
      const auto [dir, depth] = stack.back();
      stack.pop_back();
      std::error_code e;
      if (!fs::is_directory(dir, e)) continue;
      if (fs::exists(dir / "package.xml", e)) {
        if (ManifestNames(dir, name)) return dir.string();
        continue;  // (another package: not searched below)
      }
      if (depth >= 8) continue;
      std::vector<fs::path> children;
      for (fs::directory_iterator it(dir, e), end; !e && it != end; it.increment(e)) {
        const std::string leaf = it->path().filename().string();
        if (!leaf.empty() && leaf[0] != '.' && it->is_directory(e)) children.push_back(it->path());
      }
      std::sort(children.rbegin(), children.rend());  // (popped in name order)
      for (const fs::path& c : children) stack.emplace_back(c, depth + 1);
    }
  }
  return "";
}

// ROS 2's (ament): PREFIX/share/NAME for each prefix of AMENT_PREFIX_PATH.
std::string SearchAmentPrefixPath(const std::string& name) {
  std::error_code e;
  for (const std::string& prefix : PathList("AMENT_PREFIX_PATH")) {
    const fs::path dir = fs::path(prefix) / "share" / name;
    if (fs::is_directory(dir, e)) return dir.string();
  }
  return "";
}

// The folder a package:// or model:// NAME stands for, or empty.
std::string FindPackage(const std::string& name, const Document& doc, const FillOptions& options, bool model) {
  for (const auto& [pkg, dir] : options.packages) {
    if (pkg == name) return dir;
  }
  if (!model) {
    if (std::string dir = SearchRosPackagePath(name); !dir.empty()) return dir;
    if (std::string dir = SearchAmentPrefixPath(name); !dir.empty()) return dir;
  }
  // The description's ancestors: a folder called NAME, or one whose package.xml says <name>NAME.
  std::error_code e;
  fs::path at = fs::absolute(fs::path(doc.path), e).parent_path();
  for (int depth = 0; depth < 32 && !at.empty(); ++depth) {
    if (at.filename() == name) return at.string();
    if (ManifestNames(at, name)) return at.string();
    if (at == at.parent_path()) break;
    at = at.parent_path();
  }
  if (model) {
    for (const char* var : {"GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH", "SDF_PATH", "GAZEBO_MODEL_PATH"}) {
      for (const std::string& dir : PathList(var)) {
        if (fs::is_directory(fs::path(dir) / name, e)) return (fs::path(dir) / name).string();
      }
    }
  }
  return "";
}

}  // namespace

std::string ResolveUri(const std::string& uri, const Document& doc, const FillOptions& options) {
  for (const char* scheme : {"package://", "model://"}) {
    const std::string s = scheme;
    if (uri.compare(0, s.size(), s) != 0) continue;
    const std::string rest = uri.substr(s.size());
    const std::size_t slash = rest.find('/');
    const std::string name = rest.substr(0, slash);
    const std::string dir = FindPackage(name, doc, options, s == "model://");
    if (dir.empty()) {
      const std::string searched = s == "model://"
                                       ? "the description's folders and the Gazebo resource paths"
                                       : "the description's folders, ROS_PACKAGE_PATH and AMENT_PREFIX_PATH";
      throw ElementError("'" + uri + "': the " + (s == "model://" ? "model" : "package") + " '" + name +
                         "' is not found in " + searched + " (map it with {package=" + name + "})");
    }
    const fs::path file = fs::path(dir) / (slash == std::string::npos ? "" : rest.substr(slash + 1));
    if (!IsRegular(file)) throw ElementError("'" + uri + "': " + file.string() + " is not a readable file");
    return file.string();
  }
  std::string path = uri;
  if (path.compare(0, 7, "file://") == 0) path = path.substr(7);
  if (path.find("://") != std::string::npos) throw ElementError("'" + uri + "': an unsupported kind of address");
  fs::path file(path);
  if (file.is_relative()) file = fs::path(doc.dir) / file;
  if (!IsRegular(file)) throw ElementError("'" + uri + "': " + file.string() + " is not a readable file");
  return file.string();
}

namespace {

// The indentation of a node: the blanks after the last line break of the text before it.
std::string IndentBefore(pugi::xml_node node) {
  const pugi::xml_node before = node.previous_sibling();
  if (!before || before.type() != pugi::node_pcdata) return "";
  const std::string text = before.value();
  const std::size_t eol = text.find_last_of('\n');
  return eol == std::string::npos ? "" : text.substr(eol + 1);
}

}  // namespace

void ReplaceOrInsert(pugi::xml_node parent, pugi::xml_node old, const std::string& snippet) {
  pugi::xml_document fragment;
  const pugi::xml_parse_result parsed =
      fragment.load_string(snippet.c_str(), pugi::parse_default | pugi::parse_fragment | pugi::parse_ws_pcdata);
  if (!parsed) throw std::logic_error("robot: an inertial snippet is not XML");
  pugi::xml_node element = fragment.first_child();
  while (element && element.type() != pugi::node_element) element = element.next_sibling();
  if (!element) throw std::logic_error("robot: an empty inertial snippet");
  // Indentation: as the parent's first element child, else one step deeper than the parent.
  const pugi::xml_node first = parent.find_child([](pugi::xml_node n) { return n.type() == pugi::node_element; });
  const std::string indent = old ? IndentBefore(old) : first ? IndentBefore(first) : IndentBefore(parent) + "  ";
  // Re-indent the snippet's own line breaks (it is written with none).
  for (pugi::xml_node n = element; n;) {
    if (n.type() == pugi::node_pcdata) {
      std::string text = n.value();
      for (std::size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at + 1)) {
        text.insert(at + 1, indent);
      }
      n.set_value(text.c_str());
    }
    // Depth-first walk of the element's subtree.
    if (n.first_child()) {
      n = n.first_child();
    } else {
      while (n && n != element && !n.next_sibling()) n = n.parent();
      if (!n || n == element) break;
      n = n.next_sibling();
    }
  }
  if (old) {
    parent.insert_copy_before(element, old);
    parent.remove_child(old);
  } else if (first) {
    const pugi::xml_node added = parent.insert_copy_before(element, first);
    parent.insert_child_after(pugi::node_pcdata, added).set_value(("\n" + indent).c_str());
  } else {
    const std::string closing = IndentBefore(parent);
    pugi::xml_node text = parent.last_child();
    if (!text || text.type() != pugi::node_pcdata) text = parent.append_child(pugi::node_pcdata);
    text.set_value(("\n" + indent).c_str());
    parent.append_copy(element);
    parent.append_child(pugi::node_pcdata).set_value(("\n" + closing).c_str());
  }
}

std::vector<pugi::xml_node> FindElements(pugi::xml_node root, const char* name) {
  std::vector<pugi::xml_node> found;
  if (!root) return found;
  // pugixml's own depth-first walk, which keeps its place in the nodes, not on the stack.
  struct Walker : pugi::xml_tree_walker {
    const char* name;
    std::vector<pugi::xml_node>* found;
    bool for_each(pugi::xml_node& node) override {
      if (node.type() == pugi::node_element && std::strcmp(node.name(), name) == 0) found->push_back(node);
      return true;
    }
  } walker;
  walker.name = name;
  walker.found = &found;
  root.traverse(walker);
  return found;
}

pugi::xml_node FindElement(pugi::xml_node root, const char* name) {
  const std::vector<pugi::xml_node> all = FindElements(root, name);
  return all.empty() ? pugi::xml_node() : all.front();
}

std::string Describe(pugi::xml_node element, int k) {
  const char* name = element.attribute("name").value();
  if (*name != 0) return std::string(element.name()) + " '" + name + "'";
  return std::string(element.name()) + " #" + std::to_string(k);
}

RobotFormat FormatOf(const Document& doc) {
  const pugi::xml_node root = doc.xml.document_element();
  const std::string name = root.name();
  if (name == "robot") return RobotFormat::kUrdf;
  if (name == "sdf") return RobotFormat::kSdf;
  if (name == "mujoco") return RobotFormat::kMjcf;
  throw std::runtime_error(doc.path + ": the root element <" + name +
                           "> is none of <robot> (URDF), <sdf> (SDFormat) or <mujoco> (MJCF)");
}

void Parse(Document& doc, const std::string& path) {
  std::error_code e;
  if (!std::filesystem::is_regular_file(path, e)) throw FileAccessError(path + ": not a regular file");
  std::ifstream file(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << file.rdbuf();
  if (!file) throw FileAccessError(path + ": cannot be read");
  ParseText(doc, path, bytes.str());
}

namespace {

// MJCF's <include file="..."/>: the children of the named file's <mujoco> take the element's
// place, the file named relative to the main model's folder (MuJoCo's rule), includes within
// included files too. A file included twice, or more than 256 includes, is refused.
void ExpandIncludes(Document& doc) {
  std::vector<std::string> seen = {fs::path(doc.path).lexically_normal().string()};
  for (int expanded = 0;; ++expanded) {
    const pugi::xml_node include = FindElement(doc.xml.document_element(), "include");
    if (!include) return;
    const std::string file = include.attribute("file").value();
    if (file.empty()) throw std::runtime_error(doc.path + ": an <include> without a file");
    if (expanded >= 256) throw std::runtime_error(doc.path + ": more than 256 <include>s");
    fs::path target = file;
    if (target.is_relative()) target = fs::path(doc.dir) / target;
    const std::string name = target.lexically_normal().string();
    if (std::find(seen.begin(), seen.end(), name) != seen.end()) {
      throw std::runtime_error(doc.path + ": <include file=\"" + file + "\"> names a file included already");
    }
    seen.push_back(name);
    if (!IsRegular(target)) {
      throw std::runtime_error(doc.path + ": <include file=\"" + file + "\">: " + name + " is not a regular file");
    }
    pugi::xml_document included;
    const pugi::xml_parse_result parsed = included.load_file(name.c_str(), pugi::parse_default);
    if (!parsed) {
      throw std::runtime_error(name + " (included by " + doc.path + "): not well-formed XML at byte " +
                               std::to_string(parsed.offset) + " (" + parsed.description() + ")");
    }
    const pugi::xml_node root = included.document_element();
    if (std::string(root.name()) != "mujoco") {
      throw std::runtime_error(name + " (included by " + doc.path + "): its root is <" + root.name() +
                               ">, not <mujoco>");
    }
    pugi::xml_node parent = include.parent();
    for (pugi::xml_node child : root.children()) parent.insert_copy_before(child, include);
    parent.remove_child(include);
    doc.notes.push_back("<include file=\"" + file + "\"> followed (" + name + ")");
  }
}

}  // namespace

void ParseText(Document& doc, const std::string& path, std::string text) {
  doc.path = path;
  doc.dir = std::filesystem::path(path).parent_path().string();
  doc.text = std::move(text);
  // Comments and the blanks between elements are kept, so that the file is written back as it
  // was, but for the inertials. Offsets are then offsets into doc.text.
  const pugi::xml_parse_result parsed = doc.xml.load_buffer(
      doc.text.data(), doc.text.size(), (pugi::parse_full | pugi::parse_ws_pcdata) & ~pugi::parse_eol);
  if (!parsed) {
    throw std::runtime_error(path + ": not well-formed XML at byte " + std::to_string(parsed.offset) + " (" +
                             parsed.description() + ")");
  }
  if (std::string(doc.xml.document_element().name()) == "mujoco") ExpandIncludes(doc);
}

}  // namespace massprops::robot

namespace massprops {

std::optional<std::pair<std::string, std::string>> PackageMapping(const std::string& text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) return std::nullopt;
  return std::make_pair(text.substr(0, eq), text.substr(eq + 1));
}

}  // namespace massprops
