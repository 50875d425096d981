#pragma once
// glTF animation playback (node TRS channels with step, linear and cubic-spline interpolation) and
// skinning. Skinned vertices are produced once per frame on the CPU into a mesh of the AssetStore,
// whose version bump tells every consumer (rasterizer upload, BVH refit, voxelizer) that it deformed:
// one source of truth for the deformed geometry.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/engine/scene/assets.h"
#include "dyngi/engine/scene/components.h"

namespace dyngi::scene {

enum class AnimationPath { Translation, Rotation, Scale };
enum class Interpolation { Step, Linear, CubicSpline };

struct AnimationChannel {
  uint32_t node = 0;  // index into Animator::nodes
  AnimationPath path = AnimationPath::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;        // strictly increasing key times (seconds)
  // Key values as vec4 (xyz for translation/scale, xyzw quaternion for rotation). Cubic splines store
  // three per key: in-tangent, value, out-tangent (glTF order).
  std::vector<glm::vec4> values;
};

struct AnimationClip {
  std::string name;
  float duration = 0.0f;
  std::vector<AnimationChannel> channels;
};

// Plays one clip on a set of node entities.
struct Animator {
  std::vector<Entity> nodes;
  std::vector<AnimationClip> clips;
  int active = 0;
  float time = 0.0f;
  float speed = 1.0f;
  bool loop = true;
  bool playing = true;

  int findClip(const std::string& name) const;
};

// The value of `channel` at time t (clamped to the key range).
glm::vec4 sampleChannel(const AnimationChannel& channel, float t);

// Skinned mesh: the instance draws `deformed`, rewritten each frame from `bindPose` and the joints.
struct SkinnedMesh {
  MeshId bindPose = 0;
  MeshId deformed = 0;
  std::vector<Entity> joints;
  std::vector<glm::mat4> inverseBind;
};

class AnimationSystem final : public ecs::System {
 public:
  const char* name() const override { return "animation"; }
  void run(ecs::World& world, const ecs::SystemContext& ctx) override;
};

// Runs after transform propagation. Re-skins a mesh only when one of its joints (or the mesh node)
// moved since the last run.
class SkinningSystem final : public ecs::System {
 public:
  explicit SkinningSystem(AssetStore& assets) : assets_(assets) {}
  const char* name() const override { return "skinning"; }
  void run(ecs::World& world, const ecs::SystemContext& ctx) override;
  size_t meshesSkinnedLastRun() const { return skinnedLastRun_; }

 private:
  AssetStore& assets_;
  size_t skinnedLastRun_ = 0;
};

// CPU skinning of one mesh (also used by tests as the reference).
void skinMesh(const MeshData& bindPose, const std::vector<glm::mat4>& jointMatrices, MeshData& out);

}  // namespace dyngi::scene
