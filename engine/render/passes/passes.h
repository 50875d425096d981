#pragma once
// The engine's built-in passes, one class each. Every pass has a name (its timestamp, debug label and
// key in stats), a Settings struct with defaults, and execute(FrameContext&).
#include <functional>
#include <optional>
#include <unordered_map>
#include <vector>

#include "dyngi/engine/render/frame_context.h"
#include "dyngi/engine/render/pipeline.h"

namespace dyngi::render {

// Builds the light list and renders one layer per spot/directional light and six per point light into
// a 2D-array shadow map. Each layer is drawn into a depth layer (the depth test) and an r32f layer that
// holds the same biased depth (shadow.frag), the lookup image the lighting pass reads with imageLoad:
// lavapipe loads a storage image in about half the time of a sampler fetch, and a depth format cannot
// be a storage image. A layer is kept from the last frame when its light's view and every shadow caster
// (mesh, version, transform) are unchanged: a still scene renders no shadows at all. Under a still
// light with casters moving, a layer is a cached layer holding the static casters with the moving ones
// drawn on top; each frame only the part the moving casters covered and now cover is restored.
class ShadowPass {
 public:
  static constexpr const char* kName = "shadow";
  struct Settings {
    uint32_t mapSize = 1024;
    uint32_t maxLayers = 24;
    float depthBiasConstant = 1.25f;
    float depthBiasSlope = 1.75f;
    float normalOffsetTexels = 1.5f;
  };
  ShadowPass(VulkanContext& ctx, const Settings& settings);
  // CPU side: fills the light and matrix buffers for this snapshot.
  void prepare(const RenderSnapshot& snapshot);
  void execute(FrameContext& frame);

  const Buffer& lights() const { return lights_; }
  const Buffer& matrices() const { return matrices_; }
  // The lookup image: r32f 2D array, each texel the biased depth of the nearest caster (1: none), in
  // GENERAL layout after execute(). A point compares lit when its light-space depth is <= the texel.
  Image& shadowMap() { return layers_.lookup; }
  uint32_t lightCount() const { return lightCount_; }
  uint32_t layersRenderedLastFrame() const { return layersRendered_; }

 private:
  VulkanContext& ctx_;
  Settings settings_;
  Pipeline pipeline_, maskedPipeline_;  // opaque casters; alpha-masked casters (their base colour's alpha cuts them)
  // A layered shadow map: the depth layers its draws test against, and the r32f lookup layers.
  struct Layers {
    Image depth, lookup;
    uint32_t count() const { return lookup.valid() ? lookup.desc().layers : 0; }
  };
  Layers makeLayers(uint32_t count, const char* name) const;
  void prepareForDrawing(VkCommandBuffer cmd, Layers& layers) const;
  Layers layers_;
  Buffer lights_;
  Buffer matrices_;
  uint32_t lightCount_ = 0;
  std::vector<glm::mat4> layerMatrices_;
  // What the shadow map holds: each layer's view, and the casters drawn into it.
  // 24 bytes a caster, its matrix as a 64-bit hash of its bits (a scene of 200,000 instances keeps
  // several lists of them; two matrices with one hash are a 2^-64 chance).
  struct Caster {
    scene::Entity entity;
    scene::MeshId mesh;
    uint32_t version;
    uint64_t modelHash;
    bool operator==(const Caster&) const = default;
  };
  std::vector<glm::mat4> renderedMatrices_;
  std::vector<Caster> renderedCasters_;
  bool rendered_ = false;
  uint32_t layersRendered_ = 0;
  // Static casters (unchanged for kSettleFrames frames) of a still light are drawn once into a cached
  // layer; while only moving casters change, a layer is that copy plus the moving casters.
  static constexpr uint64_t kSettleFrames = 60;
  uint64_t frameCounter_ = 0;
  std::unordered_map<scene::Entity, uint64_t> casterChangedAt_;  // frame its key last changed (0: never)
  Layers staticCache_;                       // one layer per shadow layer in use, made on first need
  std::vector<glm::mat4> cacheMatrices_;     // the view each cached layer was drawn with
  std::vector<std::vector<Caster>> cacheCasters_;  // the static casters drawn into it
  // Per layer built from the cache: the texel rectangle its moving casters were drawn in last frame
  // (none: the layer is not the cache plus moving casters, copy it whole). Only that rectangle and
  // this frame's are copied back from the cache before the moving casters are drawn again.
  std::vector<std::optional<VkRect2D>> movingRects_;
  std::optional<VkRect2D> movingFootprint(const glm::mat4& viewProj, const FrameContext& frame, const std::vector<size_t>& draws) const;
  void drawCasters(VkCommandBuffer cmd, const Layers& target, uint32_t layer, const glm::mat4& viewProj, const FrameContext& frame,
                   const std::vector<size_t>& draws, bool clear);
  // This frame's casters: every one (draw indices), the static and the moving ones, the static keys.
  struct CasterSets {
    std::vector<Caster> casters, staticCasters;
    std::vector<size_t> all, statics, moving;
  };
  // The layers drawn whole, those built from the cache plus the moving casters, and those whose cached
  // layer must be drawn again first.
  struct LayerPlan {
    std::vector<uint32_t> direct, fromCache, cacheRebuild;
  };
  CasterSets gatherCasters(const FrameContext& frame);
  LayerPlan planLayers(const CasterSets& sets) const;
  void rebuildStaticCache(FrameContext& frame, const CasterSets& sets, LayerPlan& plan);
  void restoreFromCache(FrameContext& frame, const CasterSets& sets, const LayerPlan& plan);
  bool warnedCapacity_ = false;
};

class GBufferPass {
 public:
  static constexpr const char* kName = "gbuffer";
  using TextureLookup = std::function<VkImageView(scene::TextureId)>;
  explicit GBufferPass(VulkanContext& ctx);
  void execute(FrameContext& frame, const TextureLookup& textures);

 private:
  VulkanContext& ctx_;
  // One pipeline per material kind (base-colour texture or not, emissive texture or not), made on first
  // use: lavapipe runs both sides of a branch, so an untextured material would pay for the lookups.
  Pipeline pipelines_[64];  // by the material's texture bits (DYNGI_MATERIAL_*)
  Pipeline& pipelineFor(uint32_t textureBits);
};

// The frame's radiance into targets.hdr: emission + shadowed direct light + albedo x targets.indirect
// (when `hasIndirect`).
class LightingPass {
 public:
  static constexpr const char* kName = "lighting";
  explicit LightingPass(VulkanContext& ctx);
  void execute(FrameContext& frame, ShadowPass& shadows, bool hasIndirect, SpecularSource specular);

 private:
  VulkanContext& ctx_;
  // By SpecularSource: without the indirect specular term, with it from targets.specular, with it from
  // targets.indirect (a specialization constant: lavapipe would pay for the branches in every pixel of
  // every frame that has none).
  Pipeline pipeline_[3];
};

class TonemapPass {
 public:
  static constexpr const char* kName = "tonemap";
  explicit TonemapPass(VulkanContext& ctx);
  void execute(FrameContext& frame);

 private:
  VulkanContext& ctx_;
  Pipeline pipeline_;
};

}  // namespace dyngi::render
