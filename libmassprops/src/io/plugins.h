#pragma once
// The one way massprops::io reaches code it does not link: a shared module found relative to the
// library (or the program it is linked into). The assimp reader and the CGAL steps come this way;
// an own 3MF reader or a CAD reader would too.

#include <string>
#include <vector>

namespace massprops::plugins {

/// The folder of the file this code was loaded from: the shared library, or the program a static
/// library is linked into (its realpath, so that a symlink in /usr/local/bin still leads home).
std::string HomeDir();

/// dlopen()s the first of `candidates` that loads. Null, with `error` saying what was tried, when
/// none does.
void* Open(const std::vector<std::string>& candidates, std::string& error);

}  // namespace massprops::plugins
