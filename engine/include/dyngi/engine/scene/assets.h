#pragma once
// CPU-side mesh and texture data shared by the rasterizer and (later) the BVH and voxelizer.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "dyngi/engine/scene/components.h"

namespace dyngi::scene {

struct Aabb {
  glm::vec3 min{1e30f};
  glm::vec3 max{-1e30f};
  bool valid() const { return min.x <= max.x && min.y <= max.y && min.z <= max.z; }
  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void extend(const Aabb& b) {
    if (b.valid()) { extend(b.min); extend(b.max); }
  }
  glm::vec3 center() const { return 0.5f * (min + max); }
  glm::vec3 extent() const { return max - min; }
  Aabb transformed(const glm::mat4& m) const;
};

struct MeshData {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;  // empty when the mesh has none
  // Per vertex: xyz the tangent (the direction u grows), w the bitangent's sign (glTF TANGENT); empty
  // when the mesh has none (a normal texture then has no frame and is not used).
  std::vector<glm::vec4> tangents;
  std::vector<uint32_t> indices;
  // Skinning attributes (JOINTS_0 / WEIGHTS_0), empty for rigid meshes. Joint indices refer to the
  // skin's joint list.
  std::vector<glm::uvec4> joints;
  std::vector<glm::vec4> weights;
  Aabb bounds;
  uint32_t version = 0;  // bumped when the vertices change (deforming meshes)
  // Every position finite and within the coordinate range (set by computeBounds). A mesh that is not
  // (NaN data from a host, a skin pulled to infinity) is left out of frames, the BVH and the voxels.
  bool usable = true;

  size_t triangleCount() const { return indices.size() / 3; }
  void computeBounds();
  // Tangents from the positions, normals and uvs (per-triangle frames summed at the vertices, then
  // made orthogonal to the normal); nothing without uvs.
  void computeTangents();
  // Area-weighted vertex normals; used when the source has none.
  void generateNormals();
};

struct TextureData {
  std::string name;
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba8;  // width*height*4
  bool srgb = true;
};

// The texture at uv, bilinear with wrap like the rasterizer's sampler: rgb linear (sRGB decoded when
// the texture is sRGB), alpha linear. An empty texture reads as white. The CPU's one texture lookup
// (the path tracer, the VPL shooter, the ray queries' alpha cut).
glm::vec4 sampleTexture(const TextureData& texture, glm::vec2 uv);

class AssetStore {
 public:
  MeshId addMesh(MeshData mesh);
  TextureId addTexture(TextureData texture);
  const MeshData& mesh(MeshId id) const { return meshes_.at(id); }
  MeshData& meshForWrite(MeshId id) {
    auto& m = meshes_.at(id);
    ++m.version;
    return m;
  }
  const TextureData& texture(TextureId id) const { return textures_.at(id); }
  size_t meshCount() const { return meshes_.size(); }
  size_t textureCount() const { return textures_.size(); }

 private:
  std::vector<MeshData> meshes_;
  std::vector<TextureData> textures_;
};

// Helpers for building scenes in code.
MeshData makeBox(const glm::vec3& halfExtent);                 // outward normals, 24 vertices
MeshData makeQuad(const glm::vec3& corner, const glm::vec3& edgeU, const glm::vec3& edgeV);  // normal = U x V
MeshData makeSphere(float radius, int segments, int rings);

}  // namespace dyngi::scene
