// assimp reads the scene; its post-processing bakes every node's transform into the vertices
// (PreTransformVertices) and splits polygons into triangles. Points and lines are not surfaces:
// assimp removes them (SortByPType); a file of nothing else then has no faces, an error.
#include "roving/formats/assimp_reader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include <assimp/Importer.hpp>

#include "roving/core/error.h"
#include "roving/formats/file_bytes.h"

namespace roving {

LoadedMesh read_with_assimp(const std::string& path) {
  { const FileBytes bytes(path, "a glTF or 3MF mesh"); }  // the shared checks: missing, a directory, empty
  Assimp::Importer importer;
  // Nothing but geometry: no normals, materials, animations or cameras are made or kept.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                                          aiComponent_COLORS | aiComponent_TEXCOORDS |
                                                          aiComponent_ANIMATIONS | aiComponent_LIGHTS |
                                                          aiComponent_CAMERAS | aiComponent_MATERIALS);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const std::string format = path.substr(path.rfind('.') + 1);
  // By path, not from memory: a .gltf names its buffers as files beside it.
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_RemoveComponent | aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_PreTransformVertices);
  if (!scene && std::string(importer.GetErrorString()).find("No meshes remaining") != std::string::npos) {
    throw Error(fmt::format("{}: no faces found (its meshes hold only points or lines); expected a triangle mesh", path));
  }
  if (!scene || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    throw Error(fmt::format("{}: cannot read it as .{} ({})", path, format, importer.GetErrorString()));
  }
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  LoadedMesh loaded;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    const std::size_t base = positions.size();
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      positions.emplace_back(mesh.mVertices[v].x, mesh.mVertices[v].y, mesh.mVertices[v].z);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // left by a mesh of mixed primitives
      Triangle t;
      for (int c = 0; c < 3; ++c) {
        if (face.mIndices[c] >= mesh.mNumVertices) {
          throw Error(fmt::format("{}: mesh {} face {} refers to vertex {}; expected an index in [0, {})", path, m, f,
                                  face.mIndices[c], mesh.mNumVertices));
        }
        t[c] = static_cast<int>(base + face.mIndices[c]);
      }
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
        ++loaded.dropped_repeated_vertex_faces;
        continue;
      }
      triangles.push_back(t);
    }
  }
  loaded.path = path;
  loaded.mesh = TriangleMesh(std::move(positions), std::move(triangles), path);  // checks finite coordinates
  return loaded;
}

}  // namespace roving
