// Every other format assimp reads (PLY, OFF, glTF/GLB, 3MF, COLLADA, ...). The only translation
// unit that includes assimp.

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "io_internal.h"

namespace massprops {

bool AssimpCanRead(const std::string& extension) {
  if (extension.empty()) return false;
  Assimp::Importer importer;
  return importer.IsExtensionSupported("." + extension);
}

LoadedMesh ReadWithAssimp(const std::string& path) {
  Assimp::Importer importer;
  // Bake node transforms into the vertices (glTF, COLLADA and 3MF place meshes through nodes);
  // keep polygons whole; drop points and lines, which bound no volume.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_PreTransformVertices | aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (scene == nullptr) Fail(path, std::string("assimp could not read it: ") + importer.GetErrorString());
  std::vector<double> xyz;
  std::vector<int> sizes;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices < 3) continue;
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        const aiVector3D& v = mesh->mVertices[face.mIndices[k]];
        xyz.insert(xyz.end(), {static_cast<double>(v.x), static_cast<double>(v.y),
                               static_cast<double>(v.z)});
      }
      sizes.push_back(static_cast<int>(face.mNumIndices));
    }
  }
  if (sizes.empty()) Fail(path, "no faces found (the file holds no surface mesh)");
  std::string ext = path.substr(path.find_last_of('.') + 1);
  LoadedMesh out = WeldCorners(path, xyz, sizes, "assimp");
  out.format = "assimp:" + ext;
  out.float32_coordinates = true;
  return out;
}

}  // namespace massprops
