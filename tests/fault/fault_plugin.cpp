// A stand-in reader plugin for the isolation tests: fault injection lives here, in the tests, not
// in the shipped readers. Loaded in place of the real plugin (MASSPROPS_CAD_PLUGIN or
// MASSPROPS_ASSIMP_PLUGIN pointing here), it forwards every call to the real plugin
// (MASSPROPS_FAULT_REAL_CAD, MASSPROPS_FAULT_REAL_ASSIMP) unless MASSPROPS_TEST_FAULT asks for a
// fault in the reader's child process:
//   crash              killed by SIGKILL before reading (what a reader's crash looks like)
//   hang               never returns (a reader in an endless loop)
//   hang-after-result  CAD: sends the result, then never returns (a boolean that never ends)

#include <dlfcn.h>
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "io/cad/plugin_abi.h"

namespace {

bool FaultIs(const char* name) {
  const char* fault = std::getenv("MASSPROPS_TEST_FAULT");
  return fault != nullptr && std::strcmp(fault, name) == 0;
}

void InjectFault() {
  if (FaultIs("crash")) ::kill(::getpid(), SIGKILL);
  if (FaultIs("hang"))
    for (;;) ::pause();
}

// The real plugin's entry point `name`, from the module the environment variable `env` names.
void* Real(const char* env, const char* name) {
  const char* path = std::getenv(env);
  void* handle = path != nullptr ? ::dlopen(path, RTLD_LAZY | RTLD_LOCAL) : nullptr;
  void* entry = handle != nullptr ? ::dlsym(handle, name) : nullptr;
  if (entry == nullptr) {
    std::fprintf(stderr, "fault plugin: %s does not name a module with %s\n", env, name);
    std::abort();
  }
  return entry;
}

struct HangAfterFirst {
  MasspropsCadSendFn send;
  void* context;
};

void SendThenHang(void* context, const char* bytes, std::size_t size) {
  auto* real = static_cast<HangAfterFirst*>(context);
  real->send(real->context, bytes, size);
  for (;;) ::pause();
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) int massprops_cad_read(const char* path, const MasspropsCadOptions* options,
                                                              MasspropsCadSendFn send, void* context) {
  InjectFault();
  const auto read = reinterpret_cast<MasspropsCadReadFn>(Real("MASSPROPS_FAULT_REAL_CAD", "massprops_cad_read"));
  if (FaultIs("hang-after-result")) {
    HangAfterFirst wrapped{send, context};
    return read(path, options, SendThenHang, &wrapped);
  }
  return read(path, options, send, context);
}

// The assimp plugin's three entry points (assimp_loader.cpp): asking which formats it reads runs
// in the program itself, so it takes no fault; reading does, in the child.
__attribute__((visibility("default"))) int massprops_assimp_can_read(const char* extension) {
  using Fn = int (*)(const char*);
  return reinterpret_cast<Fn>(Real("MASSPROPS_FAULT_REAL_ASSIMP", "massprops_assimp_can_read"))(extension);
}

__attribute__((visibility("default"))) int massprops_assimp_read_parts(const char* path, double** xyz,
                                                                       std::size_t* corners, int** sizes, int** parts,
                                                                       std::size_t* faces, char** names,
                                                                       std::size_t* names_size, char* error,
                                                                       std::size_t error_size) {
  InjectFault();
  using Fn = int (*)(const char*, double**, std::size_t*, int**, int**, std::size_t*, char**, std::size_t*, char*,
                     std::size_t);
  return reinterpret_cast<Fn>(Real("MASSPROPS_FAULT_REAL_ASSIMP", "massprops_assimp_read_parts"))(
      path, xyz, corners, sizes, parts, faces, names, names_size, error, error_size);
}

__attribute__((visibility("default"))) void massprops_assimp_free(void* p) {
  using Fn = void (*)(void*);
  reinterpret_cast<Fn>(Real("MASSPROPS_FAULT_REAL_ASSIMP", "massprops_assimp_free"))(p);
}

}  // extern "C"
