// The assimp plugin: a shared module loaded with dlopen the first time a file needs assimp, so
// that the common formats (OBJ, STL, PLY, OFF: readers of our own) start without loading assimp's
// ~10 MB (about 10 ms of relocations per process). The only translation unit that includes assimp.
// Its C interface is declared in assimp_loader.cpp.

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

extern "C" {

__attribute__((visibility("default"))) int massprops_assimp_can_read(const char* extension) {
  if (extension == nullptr || *extension == 0) return 0;
  Assimp::Importer importer;
  return importer.IsExtensionSupported(std::string(".") + extension) ? 1 : 0;
}

// Reads every mesh of the scene with node transforms applied. On success returns 0 and hands out
// malloc'ed arrays: corner coordinates (3 per corner) and corner counts per face. On failure
// returns 1 with the reason in `error`.
__attribute__((visibility("default"))) int massprops_assimp_read(const char* path, double** xyz,
                                                                 std::size_t* num_corners, int** face_sizes,
                                                                 std::size_t* num_faces, char* error,
                                                                 std::size_t error_size) {
  Assimp::Importer importer;
  // Bake node transforms into the vertices (glTF, COLLADA and 3MF place meshes through nodes);
  // keep polygons whole; drop points and lines, which bound no volume.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_PreTransformVertices | aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (scene == nullptr) {
    std::snprintf(error, error_size, "assimp could not read it: %s", importer.GetErrorString());
    return 1;
  }
  std::vector<double> corners;
  std::vector<int> sizes;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices < 3) continue;
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        const aiVector3D& v = mesh->mVertices[face.mIndices[k]];
        corners.insert(corners.end(), {static_cast<double>(v.x), static_cast<double>(v.y), static_cast<double>(v.z)});
      }
      sizes.push_back(static_cast<int>(face.mNumIndices));
    }
  }
  *num_corners = corners.size() / 3;
  *num_faces = sizes.size();
  *xyz = static_cast<double*>(std::malloc(std::max<std::size_t>(corners.size(), 1) * sizeof(double)));
  *face_sizes = static_cast<int*>(std::malloc(std::max<std::size_t>(sizes.size(), 1) * sizeof(int)));
  if (*xyz == nullptr || *face_sizes == nullptr) {
    std::free(*xyz);
    std::free(*face_sizes);
    std::snprintf(error, error_size, "out of memory");
    return 1;
  }
  std::memcpy(*xyz, corners.data(), corners.size() * sizeof(double));
  std::memcpy(*face_sizes, sizes.data(), sizes.size() * sizeof(int));
  return 0;
}

__attribute__((visibility("default"))) void massprops_assimp_free(void* p) { std::free(p); }

}  // extern "C"
