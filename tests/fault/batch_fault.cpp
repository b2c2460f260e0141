// Fault injection for the batch tests, kept out of the shipped code: preloaded into `massprops
// batch` (or a Dask worker) with LD_PRELOAD, this library stands in for massprops::LoadSolid and
// crashes or hangs on the files MASSPROPS_BATCH_FAULT names ("crash:NAME,hang:NAME": a file whose
// path contains NAME), as a reader crashing or looping on a malformed file would. Every other file
// goes to the real LoadSolid. The batch must record such a file as crashed or timed out and go on.

#include <dlfcn.h>
#include <signal.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "massprops/io/load.h"

namespace {

// "crash" or "hang" when MASSPROPS_BATCH_FAULT names this file, else empty.
std::string FaultFor(const std::string& file) {
  const char* env = std::getenv("MASSPROPS_BATCH_FAULT");
  if (env == nullptr) return {};
  const std::string spec(env);
  for (std::size_t at = 0; at < spec.size();) {
    const std::size_t end = std::min(spec.find(',', at), spec.size());
    const std::string item = spec.substr(at, end - at);
    const std::size_t colon = item.find(':');
    if (colon != std::string::npos && file.find(item.substr(colon + 1)) != std::string::npos)
      return item.substr(0, colon);
    at = end + 1;
  }
  return {};
}

}  // namespace

namespace massprops {

SolidResult LoadSolid(const std::string& path, const LoadOptions& options) {
  const std::string fault = FaultFor(path);
  if (fault == "crash") {
    std::signal(SIGSEGV, SIG_DFL);  // a real crash, also under the sanitizers' handlers
    std::raise(SIGSEGV);
  }
  if (fault == "hang")
    for (;;) ::pause();
  using Fn = SolidResult (*)(const std::string&, const LoadOptions&);
  static const auto real = [] {
    const char* name =
        "_ZN9massprops9LoadSolidERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEERKNS_11LoadOptionsE";
    void* found = ::dlsym(RTLD_NEXT, name);  // a program linked with massprops::io
    if (found == nullptr) {                  // a Python module, which loaded massprops::io out of the global scope
      if (void* io = ::dlopen("libmassprops_io.so", RTLD_LAZY | RTLD_NOLOAD)) found = ::dlsym(io, name);
    }
    return reinterpret_cast<Fn>(found);
  }();
  if (real == nullptr) {
    std::fprintf(stderr, "batch fault: the real massprops::LoadSolid was not found after this library\n");
    std::abort();
  }
  return real(path, options);
}

}  // namespace massprops
