#pragma once
// Read-backs and one-off dispatches for tests, benchmarks and tools: they look inside the GI's GPU
// state synchronously (a submit and a fence each), which no frame should do. Not part of the public
// API: the dyngi_gi_testing library, linked by tests/ only.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "dyngi/engine/render/pipeline.h"
#include "dyngi/gi/gi_system.h"
#include "dyngi/gi/voxel.h"
#include "dyngi/gi/voxel_scene.h"
#include "techniques/many_lights/many_lights.h"
#include "techniques/temporal/temporal_indirect.h"
#include "techniques/temporal/vpl_paths.h"

namespace dyngi::gi {

// A technique's parts inside a GI system, when it runs that technique (nullptr otherwise): what tests
// inspect, kept out of GiSystem's public interface.
TemporalIndirect* temporalOf(GiSystem& gi);
VplPaths* pathsOf(GiSystem& gi);
ManyLights* manyLightsOf(GiSystem& gi);

// One voxelization fragment as the voxelizer wrote it (decoded).
struct VoxelFragment {
  glm::uvec3 cell{0};
  glm::vec4 albedo{0.0f};    // linear base colour x (1 - metallic), a 1
  glm::vec3 emission{0.0f};  // emitted radiance (8-bit mantissas, shared power-of-two scale)
  glm::vec3 normal{0.0f};    // the fragment's normal (snorm8): the face's, or the normal texture's
};

class VoxelProbe {
 public:
  explicit VoxelProbe(VoxelScene& voxels);
  std::vector<uint32_t> readbackNodes();
  std::vector<VoxelFragment> readbackFragments();  // every fragment written
  DenseVoxelGrid readbackFragmentGrid();           // every voxel some fragment marks
  // Every occupied leaf's voxel as its node cell (Morton code) says: where radiance injection puts it.
  DenseVoxelGrid readbackLeafCells();
  // The occupied leaves as the leaf list holds them (what VCT's passes over leaves walk): its entries
  // (node indices), and, against the nodes, how many of them are not an occupied node of the leaf level
  // (`stray`) and how many occupied leaf-level nodes it misses (`missed`). Its header's dispatch size
  // must cover its count (`dispatchCovers`).
  struct LeafListCheck {
    std::vector<uint32_t> entries;
    uint64_t occupied = 0, stray = 0, missed = 0, duplicates = 0, wrongCells = 0;  // wrongCells: an entry's cell is not its node's
    bool dispatchCovers = false, countFits = false;  // countFits: the header's count fits the buffer
  };
  LeafListCheck checkLeafList();
  // Every occupied leaf's voxel attributes as the passes over leaves read them (leaf_attributes.glsl,
  // decoded here the same way) against the fragments in its voxel, averaged here: the fragment count, the
  // mean albedo within 1 / 255 and the mean normal within 1 / 127 (means in bytes, the moving fragments'
  // added to the static ones' kept mean), for voxels of up to 255 fragments; and the leaf sums a build
  // must leave zero.
  struct LeafAttributesCheck {
    uint64_t leaves = 0, wrongCount = 0, wrongAlbedo = 0, wrongNormal = 0, sumsLeft = 0;
  };
  LeafAttributesCheck checkLeafAttributes();
  uint64_t attributeLeaves() const;  // leaf slots the attribute sums have room for
  uint64_t leafSlotBound() const;      // VoxelScene's bound on the leaf slots, from the voxel boxes
  uint64_t nodeGroupBound() const;     // ... and on the SVO's node groups
  uint64_t nodeGroupCapacity() const;  // node groups the SVO's pool holds now
  // Visibility of world-space segments through the SVO on the GPU (svo_march.comp); out[i] = 1 when
  // occluded. Returns the GPU time of the march dispatch in ms.
  double marchSegments(const std::vector<Segment>& segments, std::vector<uint8_t>& out, float epsVoxels = 1e-3f);
  // The same dispatch with the march compiled out (every result 0): what reading a segment and writing
  // a result costs on this device, the ceiling for any march's throughput (benchmarks only).
  double marchSegmentsWithoutMarch(const std::vector<Segment>& segments, std::vector<uint8_t>& out);
  // Wall time of the last march's submit-to-fence (what a CPU caller waits).
  double lastMarchWallMs() const { return lastMarchWallMs_; }

 private:
  // The SVO's leaf level: its node range, the nodes, and (withCells) every node's cell.
  struct LeafLevel {
    glm::uvec4 range{0u};
    std::vector<uint32_t> nodes, cells;
  };
  LeafLevel readbackLeafLevel(bool withCells);
  const render::Pipeline& marchPipeline(bool march);
  double dispatchMarch(const render::Pipeline& pipeline, const std::vector<Segment>& segments, std::vector<uint8_t>& out, float epsVoxels);
  VoxelScene& voxels_;
  render::Pipeline march_, marchOff_;
  double lastMarchWallMs_ = 0.0;
};

struct VplReadback {
  glm::vec3 position;
  int bounce;  // -1: invalid
  glm::vec3 normal;
  glm::vec3 flux;
};
// The many-lights technique's current VPLs.
// withProbes: also the bounce tail's probes (bounce index = the bounce count), which are never gathered.
std::vector<VplReadback> readbackVpls(ManyLights& manyLights, bool withProbes = false);

}  // namespace dyngi::gi
