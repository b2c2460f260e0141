#pragma once
// Reading a scene's JSON: objects whose every key must be known (unknown ones are refused with the
// nearest known key as a suggestion), numbers, vectors, strings and booleans checked as they are
// read, every error naming the file and the JSON path.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene.h"

namespace scene::json_fields {

using nlohmann::json;

/// " (did you mean 'x'?)" for the nearest candidate at most two edits away, or "".
std::string Suggest(const std::string& word, const std::vector<std::string>& candidates);
std::string Join(const std::vector<std::string>& words);
/// "a number", "a string", ... for messages.
std::string TypeName(const json& j);
/// "%.6g".
std::string Num(double v);

// A JSON object being read: remembers which keys were asked for, so that Done() can reject the
// rest as unknown (with the nearest known key as a suggestion).
class Fields {
 public:
  Fields(const json& j, std::string path, const std::string& file) : j_(j), path_(std::move(path)), file_(file) {
    if (!j.is_object()) Fail("must be an object, not " + TypeName(j));
  }

  [[noreturn]] void Fail(const std::string& what) const {
    throw SceneError(file_ + ": " + (path_.empty() ? "" : path_ + ": ") + what);
  }
  [[noreturn]] void Fail(const std::string& key, const std::string& what) const {
    throw SceneError(file_ + ": " + Path(key) + ": " + what);
  }
  std::string Path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const std::string& file() const { return file_; }

  const json* Get(const std::string& key) {
    known_.push_back(key);
    const auto it = j_.find(key);
    return it == j_.end() ? nullptr : &*it;
  }
  bool Has(const std::string& key) const { return j_.contains(key); }
  /// " (the key 'bodys' is there: did you mean 'bodies'?)" when a key of the object is a likely
  /// misspelling of `key`, else "".
  std::string MisspelledAs(const std::string& key) const {
    for (auto it = j_.begin(); it != j_.end(); ++it) {
      if (it.key() != key && !Suggest(it.key(), {key}).empty()) {
        return " (the key '" + it.key() + "' is there: did you mean '" + key + "'?)";
      }
    }
    return "";
  }

  double Number(const std::string& key, double fallback, const char* rule = nullptr) {
    const json* v = Get(key);
    if (!v) return fallback;
    return CheckNumber(key, *v, rule);
  }
  double RequiredNumber(const std::string& key, const char* rule) {
    if (!Has(key)) {
      Get(key);
      Fail(key, "is required");
    }
    return Number(key, 0, rule);
  }
  double CheckNumber(const std::string& key, const json& v, const char* rule) const {
    if (!v.is_number()) Fail(key, "must be a number, not " + TypeName(v));
    const double x = v.get<double>();
    if (!std::isfinite(x)) Fail(key, "must be finite");
    if (rule) {
      const std::string r = rule;
      if (r == "positive" && !(x > 0)) Fail(key, "must be positive (got " + Num(x) + ")");
      if (r == "non-negative" && !(x >= 0)) Fail(key, "must not be negative (got " + Num(x) + ")");
    }
    return x;
  }

  Vector3 Vec3(const std::string& key, const Vector3& fallback, const char* rule = nullptr) {
    const json* v = Get(key);
    if (!v) return fallback;
    return CheckVec3(key, *v, rule);
  }
  Vector3 CheckVec3(const std::string& key, const json& v, const char* rule) const {
    if (!v.is_array() || v.size() != 3) {
      Fail(key, "must be an array of 3 numbers, not " +
                    (v.is_array() ? "an array of " + std::to_string(v.size()) : TypeName(v)));
    }
    Vector3 out;
    for (int i = 0; i < 3; ++i)
      out[i] = CheckNumber(key + "[" + std::to_string(i) + "]", v[static_cast<std::size_t>(i)], rule);
    return out;
  }

  std::string String(const std::string& key, const std::string& fallback,
                     const std::vector<std::string>& allowed = {}) {
    const json* v = Get(key);
    if (!v) return fallback;
    if (!v->is_string()) Fail(key, "must be a string, not " + TypeName(*v));
    const std::string s = v->get<std::string>();
    if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), s) == allowed.end()) {
      Fail(key, "'" + s + "' is not one of " + Join(allowed) + Suggest(s, allowed));
    }
    return s;
  }

  bool Bool(const std::string& key, bool fallback) {
    const json* v = Get(key);
    if (!v) return fallback;
    if (!v->is_boolean()) Fail(key, "must be true or false, not " + TypeName(*v));
    return v->get<bool>();
  }

  // Rejects every key that was not asked for.
  void Done() const {
    for (auto it = j_.begin(); it != j_.end(); ++it) {
      if (std::find(known_.begin(), known_.end(), it.key()) == known_.end()) {
        Fail("unknown key '" + it.key() + "'" + Suggest(it.key(), known_) + "; known keys: " + Join(known_));
      }
    }
  }

 private:
  const json& j_;
  std::string path_;
  const std::string& file_;
  std::vector<std::string> known_;
};

}  // namespace scene::json_fields

namespace scene {
/// Parses and validates a scene's JSON (ParseSceneText after parsing). @throws SceneError.
Scene ParseScene(const nlohmann::json& json, const std::string& file, const std::string& base_dir,
                 std::vector<std::string>& warnings);
/// Reads the scene's "joints" array (the bodies already read). @throws SceneError.
std::vector<JointSpec> ReadJoints(const nlohmann::json& joints, const std::string& file,
                                  const std::vector<BodySpec>& bodies);
/// Reads the scene's "loops", "tendons" and "couplings" (after its bodies and joints; each
/// refers to them by name or index). @throws SceneError naming the field.
void ReadConstraints(json_fields::Fields& f, Scene& scene);
/// Adds the scene's loops, tendons and couplings to a world whose bodies and joints are the
/// scene's, in order (frames placed from the bodies as added). @throws SceneError naming the field.
void AddSceneConstraints(const Scene& scene, dynamics::ContactWorld& world);
/// Reads the scene's "robots" array (files relative to base_dir). @throws SceneError.
std::vector<RobotSpec> ReadRobots(const nlohmann::json& robots, const std::string& file, const std::string& base_dir,
                                  std::vector<std::string>& warnings);
/// A rotation given as a quaternion [w, x, y, z] (normalized, with a warning) or as
/// {"axis": [...], "angle"/"angle_deg": ...}; identity when absent.
Quaternion ReadOrientation(json_fields::Fields& f, const std::string& key, std::vector<std::string>& warnings);
/// The "material" object of an entry; the defaults when absent.
dynamics::Material ReadMaterial(json_fields::Fields& f);
/// A body of the scene by name or index, or -1 for "world" where no body has that name (a joint's
/// parent, a loop's end, a tendon's point). @throws SceneError naming the field.
int BodyOrWorld(json_fields::Fields& f, const std::string& key, const nlohmann::json& v,
                const std::vector<BodySpec>& bodies);
/// A joint motor {"mode", "target" (or "target_deg"), "max_effort", "kp", "kd"}.
dynamics::JointMotor ReadMotor(json_fields::Fields& o, bool degrees_allowed);
}  // namespace scene
