// glTF material textures in every consumer: the G-buffer (roughness, metallic, occlusion), the lighting
// (occlusion scales the indirect light only), the path tracer and the VPLs (the diffuse share follows
// the metallic texture).
#include <gtest/gtest.h>

#include <cstdio>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/quaternion.hpp>

#include "support/report.h"
#include "dyngi/engine/render/image_metrics.h"
#include "techniques/many_lights/many_lights.h"
#include "dyngi/gi/path_tracer.h"
#include "techniques/temporal/vpl_paths.h"
#include "render/gi_run.h"
#include "render/render_fixture.h"
#include "support/fence_scene.h"
#include "testing/gi_probes.h"

using namespace dyngi;
using namespace dyngi::test;

namespace {
constexpr float kMetallic = 0.8f, kRoughness = 0.5f;
constexpr uint8_t kLeftG = 64;  // the left half's roughness texel; its metallic texel is 0, the right half's are 255

// 8 x 8 linear texels: the left half (u < 0.5) G = 64, B = 0; the right half G = B = 255.
scene::TextureId halvesTexture(scene::AssetStore& assets) {
  scene::TextureData t;
  t.width = t.height = 8;
  t.srgb = false;
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 8; ++x) t.rgba8.insert(t.rgba8.end(), {0, uint8_t(x < 4 ? kLeftG : 255), uint8_t(x < 4 ? 0 : 255), 255});
  return assets.addTexture(t);
}

// A 2 m quad facing +z whose material takes its metallic and roughness from halvesTexture(), lit head-on
// by a directional light; the camera frames it.
void litQuad(ecs::World& w, scene::AssetStore& a) {
  const scene::Entity quad = w.create();
  w.add(quad, scene::Transform{});
  w.add(quad, scene::MeshInstance{a.addMesh(scene::makeQuad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0})), true});
  w.add(quad, scene::Material{.baseColor = glm::vec4(0.7f, 0.6f, 0.5f, 1.0f), .metallic = kMetallic, .roughness = kRoughness,
                              .metallicRoughnessTexture = halvesTexture(a)});
  const scene::Entity sun = w.create();
  scene::Transform st;
  st.translation = {0, 0, 3};
  w.add(sun, st);  // local -Z: towards the quad
  w.add(sun, scene::Light{.type = scene::LightType::Directional, .intensity = 2.0f});
}

// Pixels whose surface point lies in the quad's left or right half, away from the seam and the border.
std::vector<uint8_t> halfMask(const Frame& f, bool right) {
  std::vector<uint8_t> m(f.position.size(), 0);
  for (size_t i = 0; i < m.size(); ++i) {
    const glm::vec4& p = f.position[i];
    m[i] = p.w > 0.5f && std::abs(p.y) < 0.8f && (right ? p.x > 0.2f && p.x < 0.8f : p.x < -0.2f && p.x > -0.8f);
  }
  return m;
}
// The path tracer's direct light (no bounce) at the frame's sample positions, on an Embree scene synced
// to the world (`bvh`, left for the test's own rays).
render::ImageRgba directPathTraced(const Frame& f, gi::EmbreeScene& bvh, const ecs::World& w, const scene::AssetStore& assets) {
  bvh.sync(w, assets, 0);
  gi::PathTracerSettings pts;
  pts.spp = 4;
  pts.bounces = 0;
  pts.pixelJitter = false;
  return gi::pathTrace(f.snapshot, bvh, assets, f.width, f.height, pts);
}

// One many-lights frame of the world (64^3 voxels): what its voxelization and its RSM VPLs made of it.
struct ManyLightsRun {
  gi::VoxelScene voxels;
  gi::ManyLights ml;
  render::Renderer renderer;
  ManyLightsRun(render::VulkanContext& ctx, const ecs::World& w, const scene::AssetStore& a, uint32_t vplCount)
      : voxels(ctx, gi::VoxelSettings{.resolution = 64}), ml(ctx, voxels, gi::ManyLightsOptions{.vpl = {.vpls = vplCount}}), renderer(ctx) {
    renderer.addFeature(&voxels);
    renderer.addFeature(&ml);
    renderer.resize(32, 32);
    renderer.render(render::extractSnapshot(w, a, 0));
  }
  // The fragments' voxel centres (world) with their albedo.
  std::vector<std::pair<glm::vec3, glm::vec3>> voxelAlbedos() {
    std::vector<std::pair<glm::vec3, glm::vec3>> out;
    const gi::VoxelVolume& vol = voxels.volume();
    for (const gi::VoxelFragment& fr : gi::VoxelProbe(voxels).readbackFragments())
      out.emplace_back(vol.origin + (glm::vec3(fr.cell) + 0.5f) * vol.voxelSize, glm::vec3(fr.albedo));
    return out;
  }
};
}  // namespace

// Per texel: roughness x G and metallic x B in the G-buffer; the diffuse light (1 - metallic) in the
// raster frame equals the path tracer's (direct light only, its own SceneSurfaces reading the texture).
TEST_F(RenderTest, MetallicRoughnessTextureReachesTheGBufferTheLightingAndThePathTracer) {
  ecs::World w;
  scene::AssetStore assets;
  litQuad(w, assets);
  Frame f = render(w, assets, 96, 96);
  gi::EmbreeScene bvh;
  const render::ImageRgba ref = directPathTraced(f, bvh, w, assets);
  for (bool right : {false, true}) {
    const std::vector<uint8_t> mask = halfMask(f, right);
    size_t n = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
      if (!mask[i]) continue;
      ++n;
      const float roughness = kRoughness * (right ? 1.0f : kLeftG / 255.0f), metallic = right ? kMetallic : 0.0f;
      ASSERT_NEAR(f.normal[i].w, roughness, 2e-3f) << "pixel " << i;
      ASSERT_NEAR(f.albedo[i].a, metallic, 1.0f / 255.0f) << "pixel " << i;
    }
    ASSERT_GT(n, 500u);
    const double raster = luminance(render::meanOver(f.hdr, &mask)), path = luminance(render::meanOver(ref, &mask));
    // Lambert under the sun: E x base x (1 - metallic) / pi.
    const double expected = 2.0 * luminance(glm::dvec3(0.7, 0.6, 0.5)) * (1.0 - (right ? kMetallic : 0.0)) / 3.14159265358979;
    dyngi::test::report("%s half: raster %.4f  path tracer %.4f  analytic %.4f\n", right ? "metallic" : "rough", raster, path, expected);
    EXPECT_NEAR(raster / expected, 1.0, 0.01);
    EXPECT_NEAR(path / expected, 1.0, 0.01);
  }
}

// The VPLs see the diffuse share the texture gives: many lights' RSMs sample no VPL from the metallic
// half's weaker flux in its proportion, and the temporal paths' VPLs there reflect (1 - 0.8) x as much.
TEST_F(RenderTest, MetallicRoughnessTextureSetsTheVplsDiffuseShare) {
  ecs::World w;
  scene::AssetStore assets;
  litQuad(w, assets);
  render(w, assets, 8, 8);  // propagates the transforms
  // Many lights: the first bounce's VPLs per half, in proportion to the flux each half reflects.
  ManyLightsRun run(context(), w, assets, 2048);
  double left = 0, right = 0;
  for (const gi::VplReadback& v : gi::readbackVpls(run.ml))
    if (v.bounce == 0 && std::abs(v.position.x) > 0.25f && std::abs(v.position.x) < 0.8f && std::abs(v.position.y) < 0.8f)
      (v.position.x < 0 ? left : right) += luminance(glm::dvec3(v.flux));
  dyngi::test::report("many lights: VPL flux right / left %.3f (expected %.3f)\n", right / left, 1.0 - kMetallic);
  EXPECT_NEAR(right / left, 1.0 - kMetallic, 0.05);
  // The voxels' albedo: the diffuse share per texel too (what VCT injects and many lights' bounces reflect).
  size_t voxelsChecked = 0;
  for (const auto& [p, albedo] : run.voxelAlbedos()) {
    if (std::abs(p.x) < 0.25f || std::abs(p.x) > 0.8f || std::abs(p.y) > 0.8f) continue;
    EXPECT_NEAR(albedo.r, 0.7f * (p.x < 0 ? 1.0f : 1.0f - kMetallic), 2.0f / 255.0f) << "voxel at x " << p.x;
    ++voxelsChecked;
  }
  EXPECT_GT(voxelsChecked, 100u);
  // Temporal paths: each VPL's albedo is the texel's diffuse share.
  gi::EmbreeScene bvh;
  bvh.sync(w, assets, 0);
  const auto snap = render::extractSnapshot(w, assets, 0);
  gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 2000}, .reshootBudget = 100000});
  paths.update(snap, bvh, assets, {});
  size_t checked = 0;
  for (const gi::PathVpl& v : paths.vpls()) {
    // Away from the seam and the border, where the bilinear lookup (wrapping) blends the halves.
    if (!v.placed || std::abs(v.position.x) < 0.25f || std::abs(v.position.x) > 0.8f || std::abs(v.position.y) > 0.8f) continue;
    const float share = v.position.x < 0 ? 1.0f : 1.0f - kMetallic;
    EXPECT_NEAR(v.albedo.r, 0.7f * share, 1e-3f);
    ++checked;
  }
  EXPECT_GT(checked, 400u);  // the sun's beam covers the scene's bounding disc, wider than the quad
}

// The occlusion texture scales the indirect light (diffuse and specular), never the direct: the same GI
// run with and without it differs on the floor by exactly (1 - occlusion) x albedo x indirect.
TEST_F(RenderTest, OcclusionTextureScalesTheIndirectLightOnly) {
  constexpr uint8_t kR = 64;
  constexpr float kStrength = 0.5f;
  const float occlusion = 1.0f + kStrength * (kR / 255.0f - 1.0f);
  gi::GiSettings s;
  s.temporal.reshootBudget = 512;
  GiRun plain(context(), s), occluded(context(), s);
  scene::TextureData t;
  t.width = t.height = 4;
  t.srgb = false;
  for (int i = 0; i < 16; ++i) t.rgba8.insert(t.rgba8.end(), {kR, 0, 0, 255});
  scene::Material& m = occluded.world.write<scene::Material>(occluded.named("floor"));
  m.occlusionTexture = occluded.assets.addTexture(t);
  m.occlusionStrength = kStrength;
  plain.step(20), occluded.step(20);
  const Frame a = plain.readFrame(), b = occluded.readFrame();
  const render::ImageRgba indirect = plain.indirect(), albedo = plain.renderer->readback(render::TargetId::Albedo);
  size_t floor = 0, other = 0;
  double worst = 0;
  for (size_t i = 0; i < a.hdr.size(); ++i) {
    if (a.position[i].w < 0.5f) continue;
    const bool onFloor = std::abs(a.position[i].y) < 1e-3f && a.normal[i].y > 0.99f;
    for (int c = 0; c < 3; ++c) {
      const float diffuseIndirect = albedo[i][c] * (1.0f - albedo[i].a) * indirect[i][c];
      const float expected = onFloor ? a.hdr[i][c] - (1.0f - occlusion) * diffuseIndirect : a.hdr[i][c];
      worst = std::max(worst, double(std::abs(b.hdr[i][c] - expected) / std::max(a.hdr[i][c], 0.05f)));
    }
    (onFloor ? floor : other) += 1;
  }
  dyngi::test::report("occlusion %.4f: %zu floor and %zu other pixels, worst relative difference %.2e\n", occlusion, floor, other, worst);
  EXPECT_GT(floor, 1000u);
  EXPECT_LT(worst, 2e-3);
}

// KHR_texture_transform in every consumer: a base-colour texture red where u < 0.5 and green where
// u >= 0.5, on a quad whose v grows with y, under uv' = R(90 degrees) uv + (1, 0) = (1 - v, u): the colour
// then depends on y (green below, red above) instead of x. The G-buffer, the path tracer, many lights'
// RSM VPLs and the temporal paths' VPLs all see it turned.
TEST_F(RenderTest, TextureTransformTurnsTheTextureInEveryConsumer) {
  ecs::World w;
  scene::AssetStore assets;
  litQuad(w, assets);
  scene::TextureData t;
  t.width = t.height = 8;
  t.srgb = false;
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 8; ++x) t.rgba8.insert(t.rgba8.end(), {uint8_t(x < 4 ? 255 : 0), uint8_t(x < 4 ? 0 : 255), 0, 255});
  w.each<scene::Material>([&](scene::Entity e, const scene::Material&) {
    scene::Material& m = w.write<scene::Material>(e);
    m = scene::Material{.baseColorTexture = assets.addTexture(t), .uvTransform = {.offset = {1.0f, 0.0f}, .rotation = 1.5707963f}};
  });
  Frame f = render(w, assets, 64, 64);
  gi::EmbreeScene bvh;
  const render::ImageRgba ref = directPathTraced(f, bvh, w, assets);
  // Redness (r / (r + g)) expected where the surface point is: 1 above (y > 0), 0 below.
  auto expectTurned = [](const char* who, const glm::vec3& p, const glm::vec3& colour) {
    if (std::abs(p.x) > 0.8f || std::abs(p.y) > 0.8f || std::abs(p.y) < 0.25f) return 0;  // off the seam and the wrapping border
    const float redness = colour.r / std::max(colour.r + colour.g, 1e-6f);
    EXPECT_NEAR(redness, p.y > 0 ? 1.0f : 0.0f, 0.02f) << who << " at (" << p.x << ", " << p.y << ")";
    return 1;
  };
  int n = 0;
  for (size_t i = 0; i < f.position.size(); ++i)
    if (f.position[i].w > 0.5f) {
      n += expectTurned("G-buffer albedo", glm::vec3(f.position[i]), glm::vec3(f.albedo[i]));
      expectTurned("path tracer", glm::vec3(f.position[i]), glm::vec3(ref[i]));
    }
  EXPECT_GT(n, 500);
  ManyLightsRun run(context(), w, assets, 1024);
  int vpls = 0;
  for (const gi::VplReadback& v : gi::readbackVpls(run.ml)) vpls += v.bounce == 0 ? expectTurned("RSM VPL", v.position, v.flux) : 0;
  EXPECT_GT(vpls, 100);
  int fragments = 0;
  for (const auto& [p, albedo] : run.voxelAlbedos()) fragments += expectTurned("voxel fragment", p, albedo);
  EXPECT_GT(fragments, 100);
  gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 2000}, .reshootBudget = 100000});
  paths.update(render::extractSnapshot(w, assets, 0), bvh, assets, {});
  int pathVpls = 0;
  for (const gi::PathVpl& v : paths.vpls()) pathVpls += v.placed ? expectTurned("path VPL", v.position, v.albedo) : 0;
  EXPECT_GT(pathVpls, 100);
}


// alphaMode MASK in every consumer: the G-buffer sees the floor through the cut half, the shadow map
// lets the sun through it, the path tracer (Embree's filter) agrees pixel by pixel, and neither the
// voxels, many lights' RSM VPLs nor the temporal paths' VPLs lie on the cut half.
TEST_F(RenderTest, AlphaMaskCutsTheSurfaceInEveryConsumer) {
  ecs::World w;
  scene::AssetStore assets;
  floorUnderAFence(w, assets);
  constexpr uint32_t kSize = 96;
  Frame f = render(w, assets, kSize, kSize);
  gi::EmbreeScene bvh;
  const render::ImageRgba ref = directPathTraced(f, bvh, w, assets);
  dumpTestImage("alpha_mask_raster", f.hdr, kSize, kSize);
  dumpTestImage("alpha_mask_path", ref, kSize, kSize);
  size_t fencePixels = 0, litFloor[3] = {0, 0, 0}, floorPixels[3] = {0, 0, 0}, disagree = 0, covered = 0;
  for (size_t i = 0; i < f.position.size(); ++i) {
    if (f.position[i].w < 0.5f) continue;
    ++covered;
    const glm::vec3 p(f.position[i]);
    if (std::abs(p.y - kFenceHeight) < 1e-3f) {
      ++fencePixels;
      EXPECT_GT(p.x, -0.05f) << "the G-buffer shows the fence's cut half";
    } else if (std::abs(p.y) < 1e-3f) {
      const int under = int(underTheFence(p));
      ++floorPixels[under];
      litFloor[under] += f.hdr[i].r > 0.1f;
    }
    // The path tracer (primary rays and shadow rays through Embree's alpha filter) sees the same.
    disagree += std::abs(luminance(glm::dvec3(f.hdr[i])) - luminance(glm::dvec3(ref[i]))) > 0.05;
  }
  dyngi::test::report("fence %zu px; floor under the hole %zu (lit %zu), under the solid half %zu (lit %zu), open %zu (lit %zu); "
              "raster and path tracer disagree on %zu of %zu px\n",
              fencePixels, floorPixels[0], litFloor[0], floorPixels[1], litFloor[1], floorPixels[2], litFloor[2], disagree, covered);
  EXPECT_GT(fencePixels, 300u);
  EXPECT_GT(floorPixels[0], 40u);
  EXPECT_GT(floorPixels[1], 100u);
  EXPECT_GE(litFloor[0], floorPixels[0] * 95 / 100) << "the sun passes the cut half";
  EXPECT_LE(litFloor[1], floorPixels[1] * 5 / 100) << "the solid half casts its shadow";
  EXPECT_LE(disagree, covered / 50) << "edges only";

  // The GI's views of the scene: voxels, RSM VPLs, path VPLs.
  ManyLightsRun run(context(), w, assets, 2048);
  auto onCutHalf = [](const glm::vec3& p, float tolerance) {
    return std::abs(p.y - kFenceHeight) < tolerance && p.x < -tolerance && std::abs(p.z) < 1.0f;
  };
  const float voxelSize = run.voxels.volume().voxelSize;
  size_t fenceFragments = 0;
  for (const auto& [c, albedo] : run.voxelAlbedos()) {
    EXPECT_FALSE(onCutHalf(c, voxelSize)) << "a voxel on the cut half at x " << c.x;
    fenceFragments += std::abs(c.y - kFenceHeight) < voxelSize;
  }
  EXPECT_GT(fenceFragments, 50u) << "the solid half is voxelized";
  size_t rsmOnFence = 0, rsmUnderSolid = 0;
  for (const gi::VplReadback& v : gi::readbackVpls(run.ml)) {
    if (v.bounce != 0) continue;
    EXPECT_FALSE(onCutHalf(v.position, 1e-2f)) << "an RSM VPL on the cut half";
    rsmOnFence += std::abs(v.position.y - kFenceHeight) < 1e-2f;
    rsmUnderSolid += std::abs(v.position.y) < 1e-2f && underTheFence(v.position) == Under::Solid;
  }
  EXPECT_GT(rsmOnFence, 50u);
  EXPECT_EQ(rsmUnderSolid, 0u) << "the RSM sees the fence's solid half, not the floor under it";
  gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 3000}, .reshootBudget = 100000});
  paths.update(render::extractSnapshot(w, assets, 0), bvh, assets, {});
  size_t pathsThroughHole = 0;
  for (const gi::PathVpl& v : paths.vpls()) {
    if (!v.placed) continue;
    EXPECT_FALSE(onCutHalf(v.position, 1e-3f)) << "a path VPL on the cut half";
    pathsThroughHole += std::abs(v.position.y) < 1e-3f && underTheFence(v.position) == Under::Hole;
    EXPECT_FALSE(std::abs(v.position.y) < 1e-3f && underTheFence(v.position) == Under::Solid) << "a path VPL in the solid half's shadow";
  }
  EXPECT_GT(pathsThroughHole, 20u);
}

// A normal texture in every consumer: the quad's left half (u < 0.5) has its normals turned 45 degrees
// towards +x (its tangent), the right half is flat; under a sun from +x+z the left half receives
// E cos 0 and the right E cos 45, as the analytic case says, in the raster frame and the path tracer
// alike; the RSM VPLs, the voxels and the temporal paths' VPLs carry the texture's normals.
TEST_F(RenderTest, NormalTextureTurnsTheShadingNormalInEveryConsumer) {
  ecs::World w;
  scene::AssetStore assets;
  scene::TextureData t;
  t.width = t.height = 8;
  t.srgb = false;
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 8; ++x) t.rgba8.insert(t.rgba8.end(), {uint8_t(x < 4 ? 218 : 128), 128, uint8_t(x < 4 ? 218 : 255), 255});
  scene::MeshData mesh = scene::makeQuad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0});
  mesh.computeTangents();
  const scene::Entity quad = w.create();
  w.add(quad, scene::Transform{});
  w.add(quad, scene::MeshInstance{assets.addMesh(std::move(mesh)), true});
  w.add(quad, scene::Material{.baseColor = glm::vec4(0.7f, 0.6f, 0.5f, 1.0f), .normalTexture = assets.addTexture(t)});
  const glm::vec3 toSun = glm::normalize(glm::vec3(1.0f, 0.0f, 1.0f));
  const scene::Entity sun = w.create();
  scene::Transform st;
  st.rotation = glm::quatLookAtRH(-toSun, glm::vec3(0, 1, 0));
  w.add(sun, st);
  w.add(sun, scene::Light{.type = scene::LightType::Directional, .intensity = 2.0f});
  Frame f = render(w, assets, 96, 96);
  gi::EmbreeScene bvh;
  const render::ImageRgba ref = directPathTraced(f, bvh, w, assets);
  const auto texelNormal = [](float r, float g, float b) { return glm::normalize(glm::vec3(r, g, b) / 255.0f * 2.0f - 1.0f); };
  for (bool right : {false, true}) {
    const glm::vec3 expectedNormal = right ? texelNormal(128, 128, 255) : texelNormal(218, 128, 218);
    const std::vector<uint8_t> mask = halfMask(f, right);
    size_t n = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
      if (!mask[i]) continue;
      ++n;
      ASSERT_LT(glm::length(glm::vec3(f.normal[i]) - expectedNormal), 0.01f) << "pixel " << i;
    }
    ASSERT_GT(n, 500u);
    const double raster = luminance(render::meanOver(f.hdr, &mask)), path = luminance(render::meanOver(ref, &mask));
    const double expected = 2.0 * luminance(glm::dvec3(0.7, 0.6, 0.5)) * glm::dot(expectedNormal, toSun) / 3.14159265358979;
    dyngi::test::report("%s half: raster %.4f  path tracer %.4f  analytic %.4f\n", right ? "flat" : "turned", raster, path, expected);
    EXPECT_NEAR(raster / expected, 1.0, 0.01);
    EXPECT_NEAR(path / expected, 1.0, 0.01);
  }

  // The GI's views of the quad carry the same normals: the RSM VPLs (their bounce leaves along it), the
  // voxels (averaged from their fragments) and the temporal paths' VPLs (SceneSurfaces).
  const auto expectedAt = [&](const glm::vec3& p) { return p.x > 0 ? texelNormal(128, 128, 255) : texelNormal(218, 128, 218); };
  // Away from the seam and the border, where the bilinear lookup (wrapping) blends the halves.
  const auto inHalf = [](const glm::vec3& p) { return std::abs(p.x) > 0.25f && std::abs(p.x) < 0.8f && std::abs(p.y) < 0.8f; };
  ManyLightsRun run(context(), w, assets, 2048);
  size_t rsmChecked = 0, voxelsChecked = 0, pathsChecked = 0;
  for (const gi::VplReadback& v : gi::readbackVpls(run.ml)) {
    if (v.bounce != 0 || !inHalf(v.position)) continue;
    ++rsmChecked;
    EXPECT_LT(glm::length(v.normal - expectedAt(v.position)), 0.01f) << "RSM VPL at x " << v.position.x;
  }
  const float voxelSize = run.voxels.volume().voxelSize;
  for (const gi::VoxelFragment& fr : gi::VoxelProbe(run.voxels).readbackFragments()) {
    const glm::vec3 c = run.voxels.volume().origin + (glm::vec3(fr.cell) + 0.5f) * voxelSize;
    if (!inHalf(c)) continue;
    ++voxelsChecked;
    EXPECT_LT(glm::length(fr.normal - expectedAt(c)), 0.02f) << "voxel fragment at x " << c.x;  // snorm8
  }
  gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 2000}, .reshootBudget = 100000});
  paths.update(render::extractSnapshot(w, assets, 0), bvh, assets, {});
  for (const gi::PathVpl& v : paths.vpls()) {
    if (!v.placed || !inHalf(v.position)) continue;
    ++pathsChecked;
    EXPECT_LT(glm::length(v.normal - expectedAt(v.position)), 0.01f) << "path VPL at x " << v.position.x;
  }
  dyngi::test::report("normals checked: %zu RSM VPLs, %zu voxel fragments, %zu path VPLs\n", rsmChecked, voxelsChecked, pathsChecked);
  EXPECT_GT(rsmChecked, 200u);
  EXPECT_GT(voxelsChecked, 100u);
  EXPECT_GT(pathsChecked, 200u);
}
