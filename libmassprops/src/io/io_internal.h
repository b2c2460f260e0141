#pragma once
// Shared pieces of the mesh readers.

#include <string>
#include <vector>

#include "massprops/io.h"

namespace massprops {

[[noreturn]] void Fail(const std::string& path, const std::string& what);

LoadedMesh WeldCorners(const std::string& path, const std::vector<double>& xyz,
                       const std::vector<int>& face_sizes, const char* format);

LoadedMesh ReadPly(const std::string& path);
LoadedMesh ReadOff(const std::string& path);

/// True when assimp has an importer for this (lower-case) extension.
bool AssimpCanRead(const std::string& extension);
/// Reads any format assimp knows; node transforms are applied, all meshes are merged, corners
/// welded by position. Debian's assimp stores coordinates as 32-bit floats: LoadedMesh says so.
LoadedMesh ReadWithAssimp(const std::string& path);

}  // namespace massprops
