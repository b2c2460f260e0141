#pragma once
// The one way massprops::io reaches code it does not link: a shared module found relative to the
// library (or the program it is linked into), run in a child process when it reads files. The
// assimp reader, the CAD reader (OpenCASCADE) and the CGAL steps come this way.

#include <functional>
#include <string>
#include <vector>

#include "massprops/io/isolation.h"

namespace massprops::plugins {

/// The folder of the file this code was loaded from: the shared library, or the program a static
/// library is linked into (its realpath, so that a symlink in /usr/local/bin still leads home).
std::string HomeDir();

/// A module to load: what it is (for messages), where to look, and the entry points it must have.
struct ModuleSpec {
  std::string what;                     ///< "the assimp plugin (libmassprops_assimp.so)"
  std::vector<std::string> candidates;  ///< where to look, in order (ModuleCandidates)
  std::string advice;                   ///< how a user points at it: "set MASSPROPS_ASSIMP_PLUGIN to its path"
  std::vector<const char*> entries;     ///< its entry points, every one required
  bool program_first = false;           ///< look in the program (and what it links) before any file
};

/// A loaded module's entry points (in the order asked), or why it could not be loaded.
struct Module {
  std::vector<void*> entries;
  std::string error;  ///< empty when loaded
  bool loaded() const { return error.empty(); }
};

/// The one loader of modules: the program itself (when `program_first`), then the first
/// candidate that opens; every entry point resolved, or an error naming what was tried. Callers
/// keep the answer in a function-local static, so that each module is loaded once per process.
Module LoadModule(const ModuleSpec& spec);

/// Where a reader module `name` (libmassprops_assimp.so, ...) is looked for, in order: the path in
/// the environment variable `env_var`, beside the library (lib/massprops/), the install layout seen
/// from bin/, beside the program, this build tree (only for programs of this build tree), and the
/// library search path.
std::vector<std::string> ModuleCandidates(const std::string& name, const char* env_var);

/// A reader's time limit: `base` seconds plus `per_megabyte` for each MB of the file, unless the
/// environment variable `env_var` gives one (seconds).
double TimeLimitSeconds(const std::string& path, const char* env_var, double base, double per_megabyte);

/// Runs `work` in a forked child with a time limit and returns what it sent back. A crash, a hang
/// or a failure inside the third-party reader `who` ("assimp", "OpenCASCADE") becomes a
/// MeshFileError naming `path`, so that the program and its other files go on. (The tests inject
/// crashes and hangs through a stand-in plugin, tests/fault/fault_plugin.cpp.)
std::string ReadIsolated(const std::string& path, const std::string& who, double seconds, const char* timeout_env,
                         const std::function<std::string()>& work);

/// As ReadIsolated, for work that sends its output in pieces (`send`): each piece restarts the
/// time limit, and what came before a crash or a stop is kept in the outcome, which is returned as
/// it ended (FailOutcome words one that did not finish).
IsolatedOutcome ReadIsolatedPieces(const std::string& path, const std::string& who, double seconds,
                                   const std::function<void(const IsolatedSend&)>& work);

/// The MeshFileError for an outcome that did not finish: a stop at the time limit, a crash or a
/// failure of the reader `who`.
[[noreturn]] void FailOutcome(const std::string& path, const std::string& who, const IsolatedOutcome& outcome,
                              double seconds, const char* timeout_env);

}  // namespace massprops::plugins
