#include "visgrab/render/mesh_loader.hpp"

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "rw/geometry/detail/mesh_checks.hpp"
#include "visgrab/render/png_io.hpp"

namespace visgrab::render {

namespace {

class MeshReader {
 public:
  MeshReader(const std::filesystem::path& path, const aiScene& scene)
      : path_(path), scene_(scene) {}

  void readNode(const aiNode& node, const aiMatrix4x4& parent,
                std::vector<visual::VisualMesh>& out) {
    const aiMatrix4x4 transform = parent * node.mTransformation;
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
      const aiMesh& mesh = *scene_.mMeshes[node.mMeshes[i]];
      if ((mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0 || mesh.mNumFaces == 0) continue;
      out.push_back(convert(mesh, transform));
    }
    for (unsigned i = 0; i < node.mNumChildren; ++i) readNode(*node.mChildren[i], transform, out);
  }

 private:
  visual::VisualMesh convert(const aiMesh& mesh, const aiMatrix4x4& transform) {
    visual::VisualMesh out;
    aiMatrix3x3 normalTransform(transform);
    normalTransform.Inverse().Transpose();
    out.positions.reserve(mesh.mNumVertices);
    out.normals.reserve(mesh.mNumVertices);
    const bool hasUvs = mesh.HasTextureCoords(0);
    for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
      const aiVector3D p = transform * mesh.mVertices[i];
      out.positions.emplace_back(p.x, p.y, p.z);
      aiVector3D n = mesh.HasNormals() ? normalTransform * mesh.mNormals[i] : aiVector3D(0, 0, 1);
      const float length = n.Length();
      if (length > 0.0f) n /= length;
      out.normals.emplace_back(n.x, n.y, n.z);
      if (hasUvs) {
        const aiVector3D& uv = mesh.mTextureCoords[0][i];
        out.uvs.emplace_back(uv.x, 1.0f - uv.y);
      }
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;
      out.triangles.push_back({face.mIndices[0], face.mIndices[1], face.mIndices[2]});
    }
    if (mesh.mMaterialIndex < scene_.mNumMaterials) {
      readMaterial(*scene_.mMaterials[mesh.mMaterialIndex], out);
    }
    if (out.texture && out.uvs.empty()) {
      throw std::runtime_error(path_.string() + ": mesh '" + mesh.mName.C_Str() +
                               "' has a texture but no texture coordinates");
    }
    return out;
  }

  void readMaterial(const aiMaterial& material, visual::VisualMesh& out) {
    aiColor3D diffuse(0.8f, 0.8f, 0.8f);
    if (material.Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) == AI_SUCCESS) {
      out.colour = {std::clamp(diffuse.r, 0.0f, 1.0f), std::clamp(diffuse.g, 0.0f, 1.0f),
                    std::clamp(diffuse.b, 0.0f, 1.0f)};
    }
    aiColor3D specular(0.0f, 0.0f, 0.0f);
    if (material.Get(AI_MATKEY_COLOR_SPECULAR, specular) == AI_SUCCESS) {
      out.specular = std::clamp((specular.r + specular.g + specular.b) / 3.0f, 0.0f, 1.0f);
    }
    aiString file;
    if (material.GetTextureCount(aiTextureType_DIFFUSE) == 0 ||
        material.GetTexture(aiTextureType_DIFFUSE, 0, &file) != AI_SUCCESS) {
      return;
    }
    const std::string name = file.C_Str();
    if (!name.empty() && name[0] == '*') {
      throw std::runtime_error(path_.string() + ": embedded texture '" + name +
                               "' is not supported");
    }
    std::string normalised = name;
    std::replace(normalised.begin(), normalised.end(), '\\', '/');
    const std::filesystem::path texturePath =
        (path_.parent_path() / std::filesystem::path(normalised)).lexically_normal();
    if (const auto found = textures_.find(texturePath.string()); found != textures_.end()) {
      out.texture = found->second;
      return;
    }
    if (!std::filesystem::is_regular_file(texturePath)) {
      throw std::runtime_error(path_.string() + ": texture file " + texturePath.string() +
                               " (named '" + name + "') does not exist");
    }
    std::shared_ptr<const visual::RgbImage> image;
    try {
      image = std::make_shared<const visual::RgbImage>(readImage(texturePath));
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(path_.string() + ": texture: " + e.what());
    }
    textures_.emplace(texturePath.string(), image);
    out.texture = image;
  }

  std::filesystem::path path_;
  const aiScene& scene_;
  std::map<std::string, std::shared_ptr<const visual::RgbImage>> textures_;
};

}  // namespace

std::vector<visual::VisualMesh> loadVisualMeshes(const std::filesystem::path& path) {
  if (!std::filesystem::is_regular_file(path)) {
    throw std::runtime_error(path.string() + ": mesh file does not exist");
  }
  // The checks loadMesh makes before assimp: STL structure; PLY and AC3D read in full by our own
  // readers (assimp loops or allocates without bound on some malformed ones). A file that passes
  // is then read by assimp for its materials, textures and smooth normals.
  rw::geometry::detail::checkBeforeAssimp(path);
  Assimp::Importer importer;
  // Points and lines are split off by SortByPType and then ignored.
  const aiScene* scene =
      importer.ReadFile(path.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                           aiProcess_GenSmoothNormals | aiProcess_SortByPType |
                                           aiProcess_ValidateDataStructure);
  if (scene == nullptr || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0 ||
      scene->mRootNode == nullptr) {
    throw std::runtime_error(path.string() +
                             ": cannot read the mesh: " + importer.GetErrorString());
  }
  std::vector<visual::VisualMesh> meshes;
  MeshReader reader(path, *scene);
  reader.readNode(*scene->mRootNode, aiMatrix4x4(), meshes);
  if (meshes.empty()) throw std::runtime_error(path.string() + ": no triangle meshes in the file");
  return meshes;
}

}  // namespace visgrab::render
