#pragma once
// The engine's built-in components. Plain data: behaviour lives in systems.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "dyngi/engine/ecs/entity.h"

namespace dyngi::scene {

using ecs::Entity;

// Local transform relative to `parent` (null: relative to the world).
struct Transform {
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 scale{1.0f};
  Entity parent{};

  glm::mat4 matrix() const;
};

// True when every element is finite (no NaN, no infinity).
bool isFinite(const glm::mat4& m);

// The engine's coordinate range. Vertex positions, transform elements and world bounds beyond it are
// refused at import and ignored at run time (the entity keeps its last good transform, or is left out of
// the frame), so that bounds, extents and squared distances computed in float stay finite everywhere.
inline constexpr float kMaxCoordinate = 1e18f;
// Finite, and every element's magnitude at most kMaxCoordinate.
bool withinCoordinateRange(const glm::mat4& m);
bool withinCoordinateRange(const glm::vec3& p);

// Written only by the transform propagation system. Its change tick tells GI what moved.
struct WorldTransform {
  glm::mat4 matrix{1.0f};
};

// Human-readable name (from glTF or the code that built the entity).
struct Name {
  std::string value;
};

// Static objects promise never to move or deform after the first frame; GI caches what they produce
// (BVH at build quality, voxels once). Dynamic objects may move every frame.
struct StaticTag {};
struct DynamicTag {};

// Reference into the AssetStore's meshes; one mesh = one triangle list with one material.
using MeshId = uint32_t;
using TextureId = uint32_t;
inline constexpr uint32_t kNoTexture = 0xFFFFFFFFu;

struct MeshInstance {
  MeshId mesh = 0;
  bool castShadows = true;
};

// pbrMetallicRoughness subset. emissive is outgoing radiance (factor x KHR_materials_emissive_strength).
// KHR_texture_transform (engine/shaders/shared/uv_transform.h applies it): one per material, used by all
// of its textures.
struct TextureTransform {
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;  // radians, counter-clockwise in UV space
  glm::vec2 scale{1.0f};
  // The linear part's rows, (x, y) and (z, w): R(rotation) S(scale).
  glm::vec4 linear() const {
    const float c = std::cos(rotation), s = std::sin(rotation);
    return {scale.x * c, -scale.y * s, scale.x * s, scale.y * c};
  }
  bool operator==(const TextureTransform&) const = default;
};

struct Material {
  glm::vec4 baseColor{1.0f};
  TextureId baseColorTexture = kNoTexture;
  glm::vec3 emissive{0.0f};
  TextureId emissiveTexture = kNoTexture;
  float metallic = 0.0f;
  float roughness = 1.0f;
  // glTF's metallic-roughness texture (linear): roughness x G, metallic x B.
  TextureId metallicRoughnessTexture = kNoTexture;
  // glTF's occlusion texture (linear R): the share of the indirect light that reaches the surface,
  // 1 + strength (R - 1). Direct light is not affected (the shadow maps see the geometry), nor the path
  // tracer (it traces the occlusion the texture approximates).
  TextureId occlusionTexture = kNoTexture;
  float occlusionStrength = 1.0f;
  // glTF's normal texture (linear, tangent space, xy x normalScale), on meshes with tangents.
  TextureId normalTexture = kNoTexture;
  float normalScale = 1.0f;
  TextureTransform uvTransform;
  // glTF alphaMode MASK: where base colour alpha x the texture's alpha < alphaCutoff the surface is not
  // there (foliage, fences): cut from the G-buffer, the shadow maps, the voxels, the RSMs and the rays.
  bool alphaMask = false;
  float alphaCutoff = 0.5f;
  bool operator==(const Material&) const = default;
};

enum class LightType : uint32_t { Directional = 0, Point = 1, Spot = 2 };

// Light units follow glTF values used directly as linear radiometric quantities (no 683 lm/W):
// - point/spot: `intensity` is radiant intensity per steradian: irradiance I cos(theta) / d^2;
// - directional: `intensity` is irradiance on a surface facing the light;
// - spot falloff: clamp((cos a - cos outer) / (cos inner - cos outer), 0, 1)^2;
// - `range` > 0 multiplies by glTF's window clamp(1 - (d/range)^4, 0, 1)^2 / d^2 ... (inverse square
//   kept); range == 0 means infinite (pure inverse square).
// The light points down its local -Z axis, as in glTF.
struct Light {
  LightType type = LightType::Point;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  float range = 0.0f;
  float innerConeAngle = 0.0f;
  float outerConeAngle = 0.7853982f;
  bool castShadows = true;
  bool enabled = true;
};

// The ranges content is held to, by the importer (which refuses values outside them) and by run-time
// edits (panel, host API: clamped into them); docs/CONTENT.md.
constexpr float kMaxLightIntensity = 1e7f;  // point and spot: W/sr; directional: W/m^2
constexpr float kMaxEmission = 1e6f;        // emissive radiance, each channel

// `l` with each value brought into its range: colour in [0, 1e6], intensity in [0, kMaxLightIntensity],
// range >= 0, 0 <= inner < outer <= pi/2; a value that is not a number becomes its default.
inline Light inContentRange(Light l) {
  auto clampOr = [](float v, float lo, float hi, float fallback) { return v == v ? std::min(std::max(v, lo), hi) : fallback; };
  for (int c = 0; c < 3; ++c) l.color[c] = clampOr(l.color[c], 0.0f, kMaxEmission, 1.0f);
  l.intensity = clampOr(l.intensity, 0.0f, kMaxLightIntensity, 0.0f);
  l.range = clampOr(l.range, 0.0f, 3.0e38f, 0.0f);
  l.outerConeAngle = clampOr(l.outerConeAngle, 1e-3f, 1.5707963f, 0.7853982f);
  l.innerConeAngle = clampOr(l.innerConeAngle, 0.0f, l.outerConeAngle * 0.999f, 0.0f);
  return l;
}

// `m` with its factors in glTF's ranges ([0, 1]; emission in [0, kMaxEmission]).
inline Material inContentRange(Material m) {
  auto unit = [](float v, float fallback) { return v == v ? std::min(std::max(v, 0.0f), 1.0f) : fallback; };
  for (int c = 0; c < 4; ++c) m.baseColor[c] = unit(m.baseColor[c], 1.0f);
  for (int c = 0; c < 3; ++c) m.emissive[c] = m.emissive[c] == m.emissive[c] ? std::min(std::max(m.emissive[c], 0.0f), kMaxEmission) : 0.0f;
  m.metallic = unit(m.metallic, 0.0f);
  m.roughness = unit(m.roughness, 1.0f);
  m.occlusionStrength = unit(m.occlusionStrength, 1.0f);
  return m;
}

struct Camera {
  float yfov = 0.8f;     // radians
  float znear = 0.05f;
  float zfar = 100.0f;
  float aspect = 0.0f;   // 0: use the render target's aspect
};

// Marks the camera the renderer looks through (first glTF camera, or the sample's fly camera).
struct ActiveCamera {};

}  // namespace dyngi::scene
