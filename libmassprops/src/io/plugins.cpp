// The definitions of plugins.h: the one way massprops::io reaches code it does not link.

#include "io/plugins.h"

#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>

#include <filesystem>
#include <stdexcept>

#include "io/io_internal.h"
#include "massprops/io/isolation.h"

namespace massprops::plugins {

std::string HomeDir() {
  Dl_info info{};
  std::string file;
  if (::dladdr(reinterpret_cast<void*>(&HomeDir), &info) != 0 && info.dli_fname != nullptr) file = info.dli_fname;
  if (file.empty() || file.find('/') == std::string::npos) file = "/proc/self/exe";
  std::vector<char> buf(4096);
  if (char* real = ::realpath(file.c_str(), buf.data())) file = real;
  const auto slash = file.find_last_of('/');
  return slash == std::string::npos ? "." : file.substr(0, slash);
}

namespace {

// dlopen()s the first of `candidates` that loads, with lazy binding (OpenCASCADE's seventeen
// libraries then bind only the functions a read calls: about 50 ms less per process). Null, with
// `error` saying what was tried, when none does.
void* Open(const std::vector<std::string>& candidates, std::string& error) {
  std::string tried;
  for (const std::string& c : candidates) {
    if (void* handle = ::dlopen(c.c_str(), RTLD_LAZY | RTLD_LOCAL)) return handle;
    tried += (tried.empty() ? "" : ", ") + c;
  }
  error = "tried " + tried;
  return nullptr;
}

}  // namespace

Module LoadModule(const ModuleSpec& spec) {
  Module m;
  auto resolve = [&](void* handle) {
    m.entries.clear();
    for (const char* name : spec.entries) {
      void* entry = ::dlsym(handle, name);
      if (entry == nullptr) return false;
      m.entries.push_back(entry);
    }
    return true;
  };
  if (spec.program_first && resolve(RTLD_DEFAULT)) return m;
  std::string tried;
  void* handle = Open(spec.candidates, tried);
  if (handle == nullptr) {
    m.error = spec.what + " was not found (" + tried + "; " + spec.advice + ")";
  } else if (!resolve(handle)) {
    m.error = spec.what + " lacks its entry points (a mismatched build?)";
  }
  if (!m.error.empty()) m.entries.clear();
  return m;
}

std::vector<std::string> ModuleCandidates(const std::string& name, const char* env_var) {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv(env_var)) candidates.emplace_back(env);
  const std::string dir = HomeDir();
  candidates.push_back(dir + "/massprops/" + name);
#ifdef MASSPROPS_PLUGIN_FROM_BINDIR
  candidates.push_back(dir + "/" + MASSPROPS_PLUGIN_FROM_BINDIR + "/" + name);
#endif
  candidates.push_back(dir + "/" + name);
#ifdef MASSPROPS_BUILD_DIR
  // The build tree's module, only for programs of this build tree (an installed or copied binary
  // must find its own, or say that it cannot).
  if (dir.rfind(MASSPROPS_BUILD_DIR, 0) == 0)
    candidates.push_back(std::string(MASSPROPS_PLUGIN_BUILD_DIR) + "/" + name);
#endif
  candidates.push_back(name);  // the library search path
  return candidates;
}

double TimeLimitSeconds(const std::string& path, const char* env_var, double base, double per_megabyte) {
  if (const char* env = std::getenv(env_var)) {
    const double t = std::atof(env);
    if (t > 0) return t;
  }
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  return base + (ec ? 0.0 : per_megabyte * static_cast<double>(bytes) / 1e6);
}

void FailOutcome(const std::string& path, const std::string& who, const IsolatedOutcome& outcome, double limit,
                 const char* timeout_env) {
  if (outcome.end == IsolatedEnd::kTimedOut) {
    Fail(path, who + " did not finish reading it within " + std::to_string(static_cast<long long>(limit)) +
                   " s and was stopped (a malformed file can make " + who + " loop; " + timeout_env +
                   " sets the limit in seconds)");
  }
  if (outcome.end == IsolatedEnd::kCrashed) {
    const int sig = outcome.signal;
    Fail(path, who + " crashed while reading it (signal " + std::to_string(sig) + ", " + ::strsignal(sig) +
                   "); the file is probably malformed, and no result is given for it");
  }
  Fail(path, "the " + who + " reader process failed");
}

std::string ReadIsolated(const std::string& path, const std::string& who, double limit, const char* timeout_env,
                         const std::function<std::string()>& work) {
  IsolatedOutcome outcome;
  try {
    RunIsolated(
        1, 1, limit, [&](std::size_t) { return work(); },
        [&](std::size_t, IsolatedOutcome&& o) { outcome = std::move(o); });
  } catch (const std::runtime_error& e) {
    Fail(path, "cannot start the " + who + " reader process (" + e.what() + ")");
  }
  if (outcome.end != IsolatedEnd::kFinished) FailOutcome(path, who, outcome, limit, timeout_env);
  return std::move(outcome.output);
}

IsolatedOutcome ReadIsolatedPieces(const std::string& path, const std::string& who, double limit,
                                   const std::function<void(const IsolatedSend&)>& work) {
  IsolatedOutcome outcome;
  try {
    RunIsolatedStreaming(
        1, 1, limit, [&](std::size_t, const IsolatedSend& send) { work(send); },
        [&](std::size_t, IsolatedOutcome&& o) { outcome = std::move(o); });
  } catch (const std::runtime_error& e) {
    Fail(path, "cannot start the " + who + " reader process (" + e.what() + ")");
  }
  return outcome;
}

}  // namespace massprops::plugins
