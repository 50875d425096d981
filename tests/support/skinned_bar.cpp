#include "support/skinned_bar.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "dyngi/engine/scene/animation.h"
#include "dyngi/engine/scene/components.h"
#include "dyngi/engine/scene/gltf_import.h"
#include "dyngi/engine/scene/transform_system.h"
#include "support/gltf_writer.h"

namespace dyngi::test {

SkinnedBar addSkinnedBar(ecs::World& world, scene::AssetStore& assets, const TempDir& dir, const glm::vec3& base,
                         const glm::vec3& baseColor) {
  constexpr int kRings = 13;  // 12 segments of 0.1
  constexpr float kHalf = 0.08f, kHeight = 1.2f, kJoint = 0.6f;
  const glm::vec2 corners[4] = {{-kHalf, -kHalf}, {kHalf, -kHalf}, {kHalf, kHalf}, {-kHalf, kHalf}};
  GltfPrimitiveSpec bar;
  for (int r = 0; r < kRings; ++r) {
    const float y = kHeight * float(r) / float(kRings - 1);
    // Lower half: root joint; upper half: the bending joint; the ring at the joint: half and half.
    const float w1 = y < kJoint - 1e-4f ? 0.0f : y > kJoint + 1e-4f ? 1.0f : 0.5f;
    for (const glm::vec2& c : corners) {
      bar.positions.push_back(base + glm::vec3(c.x, y, c.y));
      bar.joints.push_back({0, 1, 0, 0});
      bar.weights.push_back({1.0f - w1, w1, 0, 0});
    }
  }
  for (int r = 0; r + 1 < kRings; ++r)
    for (uint32_t k = 0; k < 4; ++k) {  // four side quads, counter-clockwise seen from outside
      uint32_t a = uint32_t(r) * 4 + k, b = uint32_t(r) * 4 + (k + 1) % 4, c = b + 4, d = a + 4;
      bar.indices.insert(bar.indices.end(), {a, c, b, a, d, c});
    }
  for (uint32_t cap : {0u, uint32_t(kRings - 1) * 4}) {  // bottom and top caps
    bool top = cap > 0;
    bar.indices.insert(bar.indices.end(), top ? std::initializer_list<uint32_t>{cap, cap + 3, cap + 2, cap, cap + 2, cap + 1}
                                              : std::initializer_list<uint32_t>{cap, cap + 1, cap + 2, cap, cap + 2, cap + 3});
  }
  bar.material = 0;
  GltfSpec s;
  s.meshes = {{bar}};
  s.materialsJson = {"{\"pbrMetallicRoughness\":{\"baseColorFactor\":[" + std::to_string(baseColor.r) + "," +
                     std::to_string(baseColor.g) + "," + std::to_string(baseColor.b) + ",1],\"metallicFactor\":0}}"};
  const std::string baseJson = "[" + std::to_string(base.x) + "," + std::to_string(base.y) + "," + std::to_string(base.z) + "]";
  s.nodes = {{.name = "skinned_bar", .mesh = 0, .skin = 0},
             {.name = "bar_root_joint", .children = {2}, .transformJson = "\"translation\":" + baseJson},
             {.name = "bar_bend_joint", .transformJson = "\"translation\":[0," + std::to_string(kJoint) + ",0]"}};
  s.skins = {{.joints = {1, 2},
              .inverseBind = {glm::translate(glm::mat4(1.0f), -base), glm::translate(glm::mat4(1.0f), -(base + glm::vec3(0, kJoint, 0)))}}};
  GltfChannelSpec bend{.node = 2, .path = "rotation"};
  for (int k = 0; k <= 4; ++k) {
    float t = float(k) / 4.0f;
    glm::quat q = glm::angleAxis(t * glm::radians(90.0f), glm::vec3(0, 0, 1));
    bend.times.push_back(t);
    bend.values.push_back({q.x, q.y, q.z, q.w});
  }
  s.animations = {{.name = "bend", .channels = {bend}}};

  scene::ImportOptions io;
  io.markStatic = false;
  io.clip = "bend";
  scene::ImportReport report;
  std::string err = scene::importGltf(dir.write("skinned_bar.gltf", writeGltf(s)), world, assets, &report, io);
  SkinnedBar out;
  out.error = !err.empty() ? err : report.skinnedMeshes != 1 ? "the bar did not import as one skinned mesh" : "";
  out.animator = report.animator;
  world.each<scene::SkinnedMesh>([&](ecs::Entity e, const scene::SkinnedMesh&) { out.mesh = e; });
  return out;
}

void addAnimationAndSkinning(ecs::Scheduler& scheduler, scene::AssetStore& assets) {
  scheduler.add(ecs::Phase::Update, std::make_unique<scene::AnimationSystem>());
  scheduler.add(ecs::Phase::PostUpdate, std::make_unique<scene::TransformSystem>());
  scheduler.add(ecs::Phase::PostUpdate, std::make_unique<scene::SkinningSystem>(assets));
}

}  // namespace dyngi::test
