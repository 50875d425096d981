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

GltfSpec skinnedBarSpec(const glm::vec3& base, const glm::vec3& baseColor) {
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

  return s;
}

SkinnedBar addSkinnedBar(ecs::World& world, scene::AssetStore& assets, const TempDir& dir, const glm::vec3& base,
                         const glm::vec3& baseColor) {
  const GltfSpec s = skinnedBarSpec(base, baseColor);
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

GltfSpec withSkinnedBar(GltfSpec scene, const glm::vec3& base, const glm::vec3& baseColor) {
  GltfSpec bar = skinnedBarSpec(base, baseColor);
  // Its normals written out (area-weighted vertex normals, the ones dyngi's importer makes when a file
  // has none), so a host that does not make normals reads the same surface.
  for (auto& mesh : bar.meshes)
    for (GltfPrimitiveSpec& p : mesh) {
      p.normals.assign(p.positions.size(), glm::vec3(0.0f));
      for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
        const uint32_t a = p.indices[t], b = p.indices[t + 1], c = p.indices[t + 2];
        const glm::vec3 n = glm::cross(p.positions[b] - p.positions[a], p.positions[c] - p.positions[a]);
        p.normals[a] += n, p.normals[b] += n, p.normals[c] += n;
      }
      for (glm::vec3& n : p.normals) n = glm::normalize(n);
    }
  const int meshOffset = int(scene.meshes.size()), nodeOffset = int(scene.nodes.size());
  const int skinOffset = int(scene.skins.size()), materialOffset = int(scene.materialsJson.size());
  for (auto& mesh : bar.meshes) {
    for (GltfPrimitiveSpec& p : mesh) p.material += materialOffset;
    scene.meshes.push_back(mesh);
  }
  scene.materialsJson.insert(scene.materialsJson.end(), bar.materialsJson.begin(), bar.materialsJson.end());
  for (GltfNodeSpec n : bar.nodes) {
    if (n.mesh >= 0) n.mesh += meshOffset;
    if (n.skin >= 0) n.skin += skinOffset;
    for (int& c : n.children) c += nodeOffset;
    scene.nodes.push_back(n);
  }
  for (GltfSkinSpec skin : bar.skins) {
    for (int& j : skin.joints) j += nodeOffset;
    scene.skins.push_back(skin);
  }
  for (GltfAnimationSpec a : bar.animations) {
    for (GltfChannelSpec& c : a.channels) c.node += nodeOffset;
    scene.animations.push_back(a);
  }
  if (!scene.sceneNodes.empty()) scene.sceneNodes.insert(scene.sceneNodes.end(), {nodeOffset, nodeOffset + 1});
  return scene;
}

void addAnimationAndSkinning(ecs::Scheduler& scheduler, scene::AssetStore& assets) {
  scheduler.add(ecs::Phase::Update, std::make_unique<scene::AnimationSystem>());
  scheduler.add(ecs::Phase::PostUpdate, std::make_unique<scene::TransformSystem>());
  scheduler.add(ecs::Phase::PostUpdate, std::make_unique<scene::SkinningSystem>(assets));
}

}  // namespace dyngi::test
