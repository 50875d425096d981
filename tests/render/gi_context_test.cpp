// The host API (gi::GiContext): a device the host made, its scene fed through calls, its G-buffer read
// through GBufferDesc. The truth is the ECS path on dyngi's own renderer: fed the same scene through the
// calls and that renderer's G-buffer images as a host's, the host API must give the same indirect light.
#include <gtest/gtest.h>

#include <climits>
#include <malloc.h>
#include <string>

#include "dyngi/engine/render/image_metrics.h"
#include "dyngi/engine/render/resources.h"
#include "dyngi/gi/gi_context.h"
#include "render/gi_run.h"
#include "render/render_fixture.h"
#include "support/report.h"

using namespace dyngi;
using namespace dyngi::test;

namespace {

render::ExternalDevice externalOf(render::VulkanContext& ctx) {
  render::ExternalDevice d;
  d.instance = ctx.instance();
  d.physicalDevice = ctx.physicalDevice();
  d.device = ctx.device();
  d.queueFamily = ctx.queueFamily();
  d.queue = ctx.queue();
  d.enabledFeatures = ctx.enabledFeatures();
  return d;
}

// The world's meshes, materials, instances and lights, through the calls (in the world's order).
struct Mirror {
  std::unordered_map<ecs::Entity, gi::InstanceHandle> instances;
  std::unordered_map<ecs::Entity, gi::LightHandle> lights;
};

gi::LightDesc lightDesc(const render::LightItem& l) {
  gi::LightDesc d;
  d.type = l.light.type == scene::LightType::Directional ? gi::LightDesc::Type::Directional
           : l.light.type == scene::LightType::Spot      ? gi::LightDesc::Type::Spot
                                                          : gi::LightDesc::Type::Point;
  d.color = l.light.color;
  d.intensity = l.light.intensity;
  d.position = l.position;
  d.direction = l.direction;
  d.range = l.light.range;
  d.innerConeAngle = l.light.innerConeAngle;
  d.outerConeAngle = l.light.outerConeAngle;
  d.enabled = l.light.enabled;
  return d;
}

gi::MaterialDesc materialDesc(const scene::Material& m) {
  gi::MaterialDesc d;
  d.baseColor = m.baseColor;
  d.emissive = m.emissive;
  d.metallic = m.metallic;
  d.roughness = m.roughness;
  return d;
}

Mirror mirror(gi::GiContext& host, const ecs::World& world, const scene::AssetStore& assets) {
  Mirror out;
  std::unordered_map<scene::MeshId, gi::MeshHandle> meshes;
  const render::RenderSnapshot s = render::extractSnapshot(world, assets, 0);
  for (const render::DrawItem& d : s.draws) {
    if (!meshes.count(d.mesh)) {
      const scene::MeshData& m = assets.mesh(d.mesh);
      meshes[d.mesh] = host.addMesh({m.positions, m.normals, m.uvs, m.indices, m.name});
    }
    const gi::MaterialHandle material = host.addMaterial(materialDesc(s.materialOf(d)));
    out.instances[d.entity] = host.addInstance({meshes[d.mesh], material, d.model, !world.has<scene::StaticTag>(d.entity)});
  }
  for (const render::LightItem& l : s.lights) out.lights[l.entity] = host.addLight(lightDesc(l));
  return out;
}

// One host frame on the ECS run's G-buffer, recorded and submitted (and waited for) by the test.
void recordHostFrame(render::VulkanContext& ctx, gi::GiContext& host, GiRun& run, render::Image& output) {
  render::Renderer& r = *run.renderer;
  const render::RenderSnapshot s = render::extractSnapshot(run.world, run.assets, run.frame);
  gi::FrameDesc f;
  f.width = r.width();
  f.height = r.height();
  f.camera.view = s.camera.view;
  f.camera.projection = s.camera.projection(float(f.width) / float(f.height));
  f.time = double(run.frame) / 60.0;
  gi::GBufferDesc& g = f.gbuffer;
  g.depth = r.targetView(render::TargetId::Depth);
  g.normal = r.targetView(render::TargetId::Normal);      // world xyz, roughness in alpha
  g.baseColor = r.targetView(render::TargetId::Albedo);   // metallic in alpha
  g.roughness = g.normal;
  g.metallic = g.baseColor;
  g.emissive = r.targetView(render::TargetId::Emissive);
  f.outputs.indirect = output.view();
  f.outputs.indirectFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
  ctx.immediate([&](VkCommandBuffer cmd) {
    r.targetImage(render::TargetId::Depth)
        .transition(cmd, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    for (render::TargetId id : {render::TargetId::Normal, render::TargetId::Albedo, render::TargetId::Emissive})
      r.targetImage(id).transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                   VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    output.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    host.recordFrame(cmd, f);
  });
}

render::Image outputImage(render::VulkanContext& ctx, uint32_t w, uint32_t h) {
  render::ImageDesc d;
  d.width = w;
  d.height = h;
  d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  d.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  d.name = "host indirect";
  return render::Image(ctx, d);
}

gi::GiSettings settingsOf(const char* technique) {
  gi::GiSettings s;
  s.technique = technique;
  return s;
}

}  // namespace

// Every technique: the host API fed dyngi's own G-buffer and the same scene gives the ECS path's indirect
// light, frame after frame, through the same changes made on both sides (the world's components on one,
// the calls on the other): a box moving, the light moving, a material edited, an instance removed.
TEST_F(RenderTest, HostApiGivesTheEcsPathsIndirectLightOnTheSameGBuffer) {
  constexpr uint32_t kSize = 64;
  for (const char* technique : {"temporal", "many-lights", "vct"}) {
    SCOPED_TRACE(technique);
    const gi::GiSettings settings = settingsOf(technique);
    GiRun run(context(), settings, "cornell", kSize, kSize);
    gi::GiContext host(externalOf(context()), settings);
    Mirror m = mirror(host, run.world, run.assets);
    render::Image output = outputImage(context(), kSize, kSize);
    const ecs::Entity box = run.named("short_box"), tall = run.named("tall_box");
    ecs::Entity light{};
    run.world.each<scene::Light>([&](ecs::Entity e, const scene::Light&) { light = e; });
    ASSERT_FALSE(box.isNull() || tall.isNull() || light.isNull());
    double worst = 0;
    for (int frame = 0; frame < 12; ++frame) {
      if (frame >= 3 && frame < 6) {  // the box slides
        scene::Transform t = run.world.get<scene::Transform>(box);
        t.translation.x += 0.05f;
        run.world.write<scene::Transform>(box) = t;
      }
      if (frame == 6) {  // the light moves
        scene::Transform t = run.world.get<scene::Transform>(light);
        t.translation.z += 0.3f;
        run.world.write<scene::Transform>(light) = t;
      }
      if (frame == 8) run.world.write<scene::Material>(tall).baseColor = glm::vec4(0.9f, 0.2f, 0.1f, 1.0f);  // re-coloured
      if (frame == 10) run.world.destroy(tall);
      const scene::Material tallMaterial = frame == 8 ? run.world.get<scene::Material>(tall) : scene::Material{};
      run.step();
      if (frame >= 3 && frame < 6) host.setTransform(m.instances.at(box), run.world.get<scene::WorldTransform>(box).matrix);
      if (frame == 6)
        for (const render::LightItem& l : render::extractSnapshot(run.world, run.assets, run.frame).lights)
          if (l.entity == light) host.updateLight(m.lights.at(light), lightDesc(l));
      if (frame == 8) host.setMaterial(m.instances.at(tall), host.addMaterial(materialDesc(tallMaterial)));
      if (frame == 10) host.removeInstance(m.instances.at(tall));
      recordHostFrame(context(), host, run, output);
      const std::vector<glm::vec4> ecs = run.indirect(), viaHost = render::readbackImage(context(), output);
      const double rel = render::relativeMse(viaHost, ecs);
      worst = std::max(worst, rel);
      report("%s frame %d: host API against the ECS path relMSE %.2e, means %.4f %.4f\n", technique, frame, rel,
             render::meanOver(viaHost).g, render::meanOver(ecs).g);
    }
    EXPECT_LT(worst, 1e-6) << "the host API's indirect light is the ECS path's (depth reconstruction aside)";
    EXPECT_GT(render::meanOver(run.indirect()).g, 0.01) << "there is indirect light to compare";
  }
}

// A device made without what dyngi needs is refused in one line naming it; a host's device with the
// requirements merged in takes 100 GI contexts made and destroyed (12 under ASan, whose leak check
// stands in for the size one), with no validation error and the heap in use flat.
TEST_F(RenderTest, HostDeviceRequirementsAndTeardown) {
  render::ExternalDevice d = externalOf(context());
  render::ExternalDevice without = d;
  without.enabledFeatures.geometryShader = VK_FALSE;
  try {
    gi::GiContext refused(without, settingsOf("vct"));
    ADD_FAILURE() << "a device without geometryShader was taken";
  } catch (const std::exception& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("geometryShader"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  EXPECT_EQ(gi::GiContext::requirements().missing(d.physicalDevice), "") << "the test's device has what dyngi needs";
  // The heap in use (every arena, and mmap'd blocks) rather than resident memory, which moves by tens of
  // MiB with the allocator's trimming and the machine's load; the least over ten contexts, since the
  // driver frees some blocks of a destroyed context a moment later. A leak raises that floor.
  auto heapKiB = [] {
    const struct mallinfo2 m = mallinfo2();
    return long((m.uordblks + m.hblkhd) / 1024);
  };
#ifdef DYNGI_TEST_SANITIZED
  constexpr int contexts = 12;  // LeakSanitizer reports any leak at exit; the heap is its own under ASan
#else
  constexpr int contexts = 100;
#endif
  long firstTen = LONG_MAX, lastTen = LONG_MAX;
  for (int i = 0; i < contexts; ++i) {
    { gi::GiContext host(d, settingsOf(i % 2 ? "vct" : "temporal")); }
    if (i >= 10 && i < 20) firstTen = std::min(firstTen, heapKiB());
    if (i >= contexts - 10) lastTen = std::min(lastTen, heapKiB());
  }
  report("heap in use after contexts 10-19 %ld KiB, after the last ten of %d %ld KiB\n", firstTen, contexts, lastTen);
#ifndef DYNGI_TEST_SANITIZED
  // The validation layer keeps about 35 KiB of each context's command buffers (without it the heap is
  // flat): 3 MiB of the 80 contexts between.
  EXPECT_LT(lastTen - firstTen, 6 * 1024) << "80 more contexts made and destroyed grew the heap by over 6 MiB";
#endif
  EXPECT_EQ(context().validationErrorCount(), 0u);
}
