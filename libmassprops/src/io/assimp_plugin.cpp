// The assimp plugin: a shared module loaded with dlopen the first time a file needs assimp, so
// that the common formats (OBJ, STL, PLY, OFF: readers of our own) start without loading assimp's
// ~10 MB (about 10 ms of relocations per process). The only translation unit that includes assimp.
// Its C interface is declared in assimp_loader.cpp.

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <assimp/config.h>
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
// malloc'ed arrays: corner coordinates (3 per corner), corner counts per face, the part (the node
// holding the mesh) of each face, and the parts' names, each ended by a NUL. On failure returns 1
// with the reason in `error`.
__attribute__((visibility("default"))) int massprops_assimp_read_parts(const char* path, double** xyz,
                                                                       std::size_t* num_corners, int** face_sizes,
                                                                       int** face_parts, std::size_t* num_faces,
                                                                       char** part_names, std::size_t* names_size,
                                                                       char* error, std::size_t error_size) {
  Assimp::Importer importer;
  // Node transforms are applied here, in double precision, rather than by assimp's
  // PreTransformVertices (single precision, and it keeps the winding of mirrored instances);
  // polygons stay whole; points and lines, which bound no volume, are dropped.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // Mass properties are reported in the file's own axes: COLLADA's Z_UP is not turned into Y-up.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const aiScene* scene = importer.ReadFile(path, aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    std::snprintf(error, error_size, "assimp could not read it: %s", importer.GetErrorString());
    return 1;
  }
  std::vector<double> corners;
  std::vector<int> sizes, parts;
  std::string names;  // NUL after each
  int num_parts = 0;
  // Depth-first over the node hierarchy with the accumulated transform (row-major 4x4, doubles).
  struct Item {
    const aiNode* node;
    double m[16];
  };
  std::vector<Item> stack;
  Item root{scene->mRootNode, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}};
  stack.push_back(root);
  while (!stack.empty()) {
    Item item = stack.back();
    stack.pop_back();
    const aiMatrix4x4& t = item.node->mTransformation;
    const double local[16] = {t.a1, t.a2, t.a3, t.a4, t.b1, t.b2, t.b3, t.b4,
                              t.c1, t.c2, t.c3, t.c4, t.d1, t.d2, t.d3, t.d4};
    double m[16];
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) {
        double sum = 0;
        for (int k = 0; k < 4; ++k) sum += item.m[4 * r + k] * local[4 * k + c];
        m[4 * r + c] = sum;
      }
    }
    // A transform with a negative determinant mirrors: faces keep their corners but must turn
    // the other way to face outward (as the glTF specification prescribes).
    const double det =
        m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) + m[2] * (m[4] * m[9] - m[5] * m[8]);
    if (item.node->mNumMeshes > 0) {
      // A part: the node, named as the file names it (else after its first mesh, else by number).
      std::string name = item.node->mName.C_Str();
      if (name.empty()) name = scene->mMeshes[item.node->mMeshes[0]]->mName.C_Str();
      if (name.empty()) name = "node " + std::to_string(num_parts + 1);
      names += name;
      names.push_back('\0');
      ++num_parts;
    }
    for (unsigned i = 0; i < item.node->mNumMeshes; ++i) {
      const aiMesh* mesh = scene->mMeshes[item.node->mMeshes[i]];
      for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
        const aiFace& face = mesh->mFaces[f];
        if (face.mNumIndices < 3) continue;
        for (unsigned k = 0; k < face.mNumIndices; ++k) {
          const unsigned corner = det < 0 ? face.mIndices[face.mNumIndices - 1 - k] : face.mIndices[k];
          const aiVector3D& v = mesh->mVertices[corner];
          const double x = v.x, y = v.y, z = v.z;
          corners.insert(corners.end(), {m[0] * x + m[1] * y + m[2] * z + m[3], m[4] * x + m[5] * y + m[6] * z + m[7],
                                         m[8] * x + m[9] * y + m[10] * z + m[11]});
        }
        sizes.push_back(static_cast<int>(face.mNumIndices));
        parts.push_back(num_parts - 1);
      }
    }
    for (unsigned c = item.node->mNumChildren; c-- > 0;) {  // so that the first child comes first
      Item child{item.node->mChildren[c], {}};
      std::memcpy(child.m, m, sizeof m);
      stack.push_back(child);
    }
  }
  *num_corners = corners.size() / 3;
  *num_faces = sizes.size();
  *xyz = static_cast<double*>(std::malloc(std::max<std::size_t>(corners.size(), 1) * sizeof(double)));
  *face_sizes = static_cast<int*>(std::malloc(std::max<std::size_t>(sizes.size(), 1) * sizeof(int)));
  *face_parts = static_cast<int*>(std::malloc(std::max<std::size_t>(parts.size(), 1) * sizeof(int)));
  *part_names = static_cast<char*>(std::malloc(std::max<std::size_t>(names.size(), 1)));
  *names_size = names.size();
  if (*xyz == nullptr || *face_sizes == nullptr || *face_parts == nullptr || *part_names == nullptr) {
    std::free(*xyz);
    std::free(*face_sizes);
    std::free(*face_parts);
    std::free(*part_names);
    std::snprintf(error, error_size, "out of memory");
    return 1;
  }
  std::memcpy(*xyz, corners.data(), corners.size() * sizeof(double));
  std::memcpy(*face_sizes, sizes.data(), sizes.size() * sizeof(int));
  std::memcpy(*face_parts, parts.data(), parts.size() * sizeof(int));
  std::memcpy(*part_names, names.data(), names.size());
  return 0;
}

__attribute__((visibility("default"))) void massprops_assimp_free(void* p) { std::free(p); }

}  // extern "C"
