#include "plugins.h"

#include <dlfcn.h>
#include <stdlib.h>

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

void* Open(const std::vector<std::string>& candidates, std::string& error) {
  std::string tried;
  for (const std::string& c : candidates) {
    if (void* handle = ::dlopen(c.c_str(), RTLD_NOW | RTLD_LOCAL)) return handle;
    tried += (tried.empty() ? "" : ", ") + c;
  }
  error = "tried " + tried;
  return nullptr;
}

}  // namespace massprops::plugins
