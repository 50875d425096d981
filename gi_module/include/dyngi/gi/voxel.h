#pragma once
// The voxel scene on the CPU side: the volume's placement, a dense occupancy grid with a 3D-DDA march,
// the sparse voxel octree's C++ twin (same node layout and SVO-restart march as the GLSL), and an exact
// triangle/box brute-force voxelizer. Tests use these as oracles; CPU code can march the GPU's SVO
// after reading it back.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "dyngi/engine/scene/assets.h"

namespace dyngi::gi {

// A cube of resolution^3 voxels. voxel = (world - origin) / voxelSize.
struct VoxelVolume {
  glm::vec3 origin{0.0f};
  float voxelSize = 1.0f;
  uint32_t resolution = 128;

  // Smallest cube holding `bounds` grown by `padding` (relative) on every side.
  static VoxelVolume around(const scene::Aabb& bounds, uint32_t resolution, float padding = 0.05f);
  glm::vec3 toVoxel(const glm::vec3& world) const { return (world - origin) / voxelSize; }
  glm::vec3 toWorld(const glm::vec3& voxel) const { return origin + voxel * voxelSize; }
  glm::mat4 worldToVoxelMatrix() const;
  uint32_t depth() const;  // log2(resolution)
};

// Exact overlap of a triangle with an axis-aligned box (separating axis theorem).
bool triangleOverlapsBox(const glm::dvec3& center, const glm::dvec3& halfSize, const glm::dvec3& a, const glm::dvec3& b,
                         const glm::dvec3& c);

class DenseVoxelGrid {
 public:
  explicit DenseVoxelGrid(uint32_t resolution = 0) : res_(resolution), bits_(size_t(resolution) * resolution * resolution, 0) {}
  uint32_t resolution() const { return res_; }
  bool get(uint32_t x, uint32_t y, uint32_t z) const { return bits_[index(x, y, z)] != 0; }
  void set(uint32_t x, uint32_t y, uint32_t z) { bits_[index(x, y, z)] = 1; }
  size_t count() const;
  // 3D-DDA (Amanatides & Woo) over the segment a -> b in voxel units, shrunk by eps at both ends.
  bool occluded(const glm::dvec3& a, const glm::dvec3& b, double eps) const;
  // Distance in voxels from voxel v to the nearest occupied voxel, capped at `cap` (Chebyshev metric).
  uint32_t distanceToOccupied(const glm::ivec3& v, uint32_t cap) const;

 private:
  size_t index(uint32_t x, uint32_t y, uint32_t z) const { return (size_t(z) * res_ + y) * res_ + x; }
  uint32_t res_;
  std::vector<uint8_t> bits_;
};

// Every voxel a triangle overlaps (triangles given in voxel units).
DenseVoxelGrid voxelizeBruteForce(const std::vector<glm::vec3>& voxelSpaceTriangles, uint32_t resolution);

// The SVO's C++ twin. Node words as on the GPU (see shaders/shared/gi_gpu_types.h).
class SvoCpu {
 public:
  SvoCpu() = default;
  SvoCpu(std::vector<uint32_t> nodes, uint32_t resolution);
  // Builds the same structure from a dense grid (level by level, children of a node stored together).
  static SvoCpu fromDense(const DenseVoxelGrid& grid);

  bool occluded(const glm::dvec3& a, const glm::dvec3& b, double eps, uint32_t* steps = nullptr) const;
  DenseVoxelGrid leaves() const;  // occupied leaves as a dense grid
  size_t nodeCount() const { return nodes_.size(); }
  uint32_t resolution() const { return res_; }

 private:
  std::vector<uint32_t> nodes_;
  uint32_t res_ = 0, depth_ = 0;
};

}  // namespace dyngi::gi
