// dyngi_bench: speed figures that the tests deliberately do not assert.
// Run: build/bin/dyngi_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <filesystem>
#include <glm/gtc/quaternion.hpp>
#include <atomic>
#include <chrono>
#include <cmath>
#include <random>

#include "dyngi/engine/scene/animation.h"
#include "dyngi/engine/scene/gltf_import.h"
#include "dyngi/engine/scene/transform_system.h"
#include "dyngi/gi/bvh.h"
#include "dyngi/gi/bvh_sync.h"
#include "dyngi/gi/job_pool.h"
#include "dyngi/gi/path_tracer.h"
#include "dyngi/gi/voxel_scene.h"
#include "testing/gi_probes.h"
#include "dyngi/engine/render/renderer.h"
#include "dyngi/engine/scene/scripted_motion.h"
#include "scenes/builtin_scenes.h"

using namespace dyngi;
using namespace dyngi::scene;

namespace {

// The walking fox: animation + skinning run untimed; the BVH update is what is measured.
void foxBvh(benchmark::State& state, bool rebuild) {
  std::string path = std::string(DYNGI_SHARED_SCENES) + "/Fox.glb";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("../shared/scenes/Fox.glb not found");
    return;
  }
  ecs::World w;
  AssetStore assets;
  ImportOptions io;
  io.clip = "Walk";
  importGltf(path, w, assets, nullptr, io);
  ecs::Scheduler anim;
  anim.add(ecs::Phase::Update, std::make_unique<AnimationSystem>());
  anim.add(ecs::Phase::PostUpdate, std::make_unique<TransformSystem>());
  anim.add(ecs::Phase::PostUpdate, std::make_unique<SkinningSystem>(assets));
  gi::EmbreeScene bvh;
  anim.runFrame(w, {});
  bvh.sync(w, assets, 0);
  ecs::Tick last = w.tick();
  uint64_t frame = 1;
  size_t tris = 0;
  w.each<MeshInstance>([&](Entity, const MeshInstance& mi) { tris += assets.mesh(mi.mesh).triangleCount(); });
  for (auto _ : state) {
    state.PauseTiming();
    anim.runFrame(w, ecs::FrameTime{1.0 / 60, double(frame) / 60, frame});
    ++frame;
    state.ResumeTiming();
    if (rebuild) bvh.rebuild(w, assets);
    else bvh.sync(w, assets, last);
    last = w.tick();
  }
  state.counters["triangles"] = double(tris);
  state.counters["meshes_refit"] = double(bvh.stats().meshesRefit);
}
void BM_BvhFoxWalk_Refit(benchmark::State& s) { foxBvh(s, false); }
void BM_BvhFoxWalk_Rebuild(benchmark::State& s) { foxBvh(s, true); }
BENCHMARK(BM_BvhFoxWalk_Refit)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BvhFoxWalk_Rebuild)->Unit(benchmark::kMillisecond);

// 100 moving instances of a 2k-triangle sphere: instance-transform updates vs rebuilding everything.
void movingInstances(benchmark::State& state, bool rebuild) {
  ecs::World w;
  AssetStore assets;
  MeshId sphere = assets.addMesh(makeSphere(0.1f, 40, 25));
  std::vector<Entity> es;
  for (int i = 0; i < 100; ++i) {
    Entity e = w.create();
    Transform t;
    t.translation = glm::vec3(float(i % 10), float(i / 10), 0.0f) * 0.3f;
    w.add(e, t);
    w.add(e, WorldTransform{t.matrix()});
    w.add(e, MeshInstance{sphere, true});
    es.push_back(e);
  }
  gi::EmbreeScene bvh;
  bvh.sync(w, assets, 0);
  ecs::Tick last = w.tick();
  float phase = 0;
  for (auto _ : state) {
    state.PauseTiming();
    w.advanceTick();
    phase += 0.01f;
    for (size_t i = 0; i < es.size(); ++i) {
      glm::mat4& m = w.write<WorldTransform>(es[i]).matrix;
      m[3].z = 0.2f * std::sin(phase + float(i));
    }
    state.ResumeTiming();
    if (rebuild) bvh.rebuild(w, assets);
    else bvh.sync(w, assets, last);
    last = w.tick();
  }
  state.counters["instances_updated"] = double(bvh.stats().instancesUpdated);
  state.counters["triangles"] = double(100 * assets.mesh(sphere).triangleCount());
}
void BM_Bvh100MovingInstances_Update(benchmark::State& s) { movingInstances(s, false); }
void BM_Bvh100MovingInstances_Rebuild(benchmark::State& s) { movingInstances(s, true); }
BENCHMARK(BM_Bvh100MovingInstances_Update)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Bvh100MovingInstances_Rebuild)->Unit(benchmark::kMillisecond);

struct CornellFixture {
  ecs::World w;
  AssetStore assets;
  gi::EmbreeScene bvh;
  CornellFixture() {
    sample::buildBuiltinScene("cornell", w, assets);
    bvh.sync(w, assets, 0);
  }
  // Segments between random points in the room: long rays, about half occluded.
  std::vector<gi::Segment> segments(size_t n) const {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> U(0.02f, 0.98f);
    std::vector<gi::Segment> s(n);
    for (auto& seg : s) {
      seg.from = {U(rng) * 2 - 1, U(rng) * 2, U(rng) * 2 - 1};
      seg.to = {U(rng) * 2 - 1, U(rng) * 2, U(rng) * 2 - 1};
    }
    return s;
  }
};

// Embree occlusion on one core (the benchmark thread); multiply by cores for the machine's rate.
void BM_EmbreeOcclusion_Single(benchmark::State& state) {
  CornellFixture f;
  auto segs = f.segments(1 << 16);
  size_t blocked = 0;
  for (auto _ : state)
    for (const auto& s : segs) blocked += f.bvh.occluded(s);
  benchmark::DoNotOptimize(blocked);
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(segs.size()));
}
void BM_EmbreeOcclusion_Packet8(benchmark::State& state) {
  CornellFixture f;
  auto segs = f.segments(1 << 16);
  std::vector<uint8_t> out(segs.size());
  for (auto _ : state) f.bvh.occluded(segs.data(), segs.size(), out.data(), 1e-4f, gi::EmbreeScene::BatchMode::Packet8);
  benchmark::DoNotOptimize(out.data());
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(segs.size()));
}
void BM_EmbreeOcclusion_Stream(benchmark::State& state) {
  CornellFixture f;
  auto segs = f.segments(1 << 16);
  std::vector<uint8_t> out(segs.size());
  for (auto _ : state) f.bvh.occluded(segs.data(), segs.size(), out.data(), 1e-4f, gi::EmbreeScene::BatchMode::Stream);
  benchmark::DoNotOptimize(out.data());
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(segs.size()));
}
BENCHMARK(BM_EmbreeOcclusion_Stream)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EmbreeOcclusion_Single)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EmbreeOcclusion_Packet8)->Unit(benchmark::kMillisecond);

// Path tracer throughput (all hardware threads), Cornell box, one indirect bounce.
void BM_PathTracer(benchmark::State& state) {
  CornellFixture f;
  ecs::Scheduler s;
  s.add(ecs::Phase::PostUpdate, std::make_unique<TransformSystem>());
  s.runFrame(f.w, {});
  auto snap = render::extractSnapshot(f.w, f.assets, 0);
  gi::PathTracerSettings pts;
  pts.spp = 4;
  pts.bounces = uint32_t(state.range(0));
  gi::PathTracerStats st;
  for (auto _ : state) benchmark::DoNotOptimize(gi::pathTrace(snap, f.bvh, f.assets, 128, 128, pts, &st));
  state.SetItemsProcessed(int64_t(state.iterations()) * 128 * 128 * 4);
}
BENCHMARK(BM_PathTracer)->Arg(0)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();

// ---- voxel scene -------------------------------------------------------------------------------

render::VulkanContext& vulkan() {
  static render::VulkanContext ctx(render::ContextOptions{.quiet = true});
  return ctx;
}

// The Cornell box plus four 37k-triangle spheres (about 150k dynamic triangles).
struct HeavyCornell {
  ecs::World w;
  AssetStore assets;
  std::vector<Entity> spheres;
  HeavyCornell() {
    sample::buildBuiltinScene("cornell", w, assets);
    MeshId sphere = assets.addMesh(makeSphere(0.18f, 192, 96));
    for (int i = 0; i < 4; ++i) {
      Entity e = w.create();
      Transform t;
      t.translation = {-0.5f + 0.33f * float(i), 1.3f, 0.3f};
      w.add(e, t);
      w.add(e, WorldTransform{t.matrix()});
      w.add(e, MeshInstance{sphere, true});
      w.add(e, Material{.baseColor = glm::vec4(0.7f)});
      w.add(e, DynamicTag{});
      spheres.push_back(e);
    }
  }
  size_t dynamicTriangles() const { return 4 * assets.mesh(MeshId(assets.meshCount() - 1)).triangleCount(); }
};

// Voxelize + SVO build per frame, wall time (lavapipe's timestamps do not bracket compute work reliably).
// Full: everything re-voxelized each frame. Incremental: one sphere moves per frame; the rest is cached.
void voxelBench(benchmark::State& state, bool full) {
  HeavyCornell scene;
  uint32_t res = uint32_t(state.range(0));
  gi::VoxelScene voxels(vulkan(), gi::VoxelSettings{.resolution = res, .maxNodeGroups = 1u << 21});
  render::Renderer renderer(vulkan(), render::RendererSettings{.gpuTimestamps = false, .featuresOnly = true});
  renderer.addFeature(&voxels);
  renderer.resize(8, 8);
  ecs::Scheduler s;
  s.add(ecs::Phase::PostUpdate, std::make_unique<TransformSystem>());
  s.add(ecs::Phase::PostUpdate, std::make_unique<gi::VoxelSyncSystem>(voxels, scene.assets));
  uint64_t frame = 0;
  auto step = [&] {
    if (full) voxels.markAllDirty();
    else scene.w.write<Transform>(scene.spheres[frame % 4]).translation.y = 1.3f + 0.1f * std::sin(float(frame));
    s.runFrame(scene.w, ecs::FrameTime{1.0 / 60, double(frame) / 60, frame});
    auto snap = render::extractSnapshot(scene.w, scene.assets, frame);
    auto t0 = std::chrono::steady_clock::now();
    renderer.render(snap);
    ++frame;
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  // Warm-up: pipelines compiled, buffers sized, every sphere moved once (a static mesh that starts
  // moving gets a range with slack once; the steady state is what is timed).
  for (int i = 0; i < 6; ++i) step();
  for (auto _ : state) state.SetIterationTime(step());
  const gi::VoxelStats& st = voxels.stats();
  state.counters["dynamic_triangles"] = double(scene.dynamicTriangles());
  state.counters["entities_voxelized"] = double(st.entitiesVoxelized);
  state.counters["fragments"] = double(st.fragments);
  state.counters["svo_nodes"] = double(st.nodes);
  state.counters["svo_MB"] = double(st.svoBytes) / (1 << 20);
  state.counters["total_MB"] = double(st.totalBytes) / (1 << 20);
}
void BM_VoxelizeBuild_Full(benchmark::State& s) { voxelBench(s, true); }
void BM_VoxelizeBuild_Incremental(benchmark::State& s) { voxelBench(s, false); }
BENCHMARK(BM_VoxelizeBuild_Full)->Arg(128)->Arg(256)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(10);
BENCHMARK(BM_VoxelizeBuild_Incremental)->Arg(128)->Arg(256)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(10);

// VPL-to-surface segments in the heavy Cornell box: 256 "VPLs" where the spot's rays land, 4096 points
// the camera sees; both ends lifted 1.5 voxels off their surface (so neither starts inside its own voxel).
struct VisibilitySet {
  HeavyCornell scene;
  gi::EmbreeScene bvh;
  std::unique_ptr<gi::VoxelScene> voxels;
  std::unique_ptr<render::Renderer> renderer;
  std::vector<gi::Segment> segments;
  VisibilitySet() {
    ecs::Scheduler s;
    s.add(ecs::Phase::PostUpdate, std::make_unique<TransformSystem>());
    s.runFrame(scene.w, {});
    bvh.sync(scene.w, scene.assets, 0);
    voxels = std::make_unique<gi::VoxelScene>(vulkan(), gi::VoxelSettings{.resolution = 128, .maxNodeGroups = 1u << 21});
    renderer = std::make_unique<render::Renderer>(vulkan(), render::RendererSettings{.gpuTimestamps = false, .featuresOnly = true});
    renderer->addFeature(voxels.get());
    renderer->resize(8, 8);
    auto snap = render::extractSnapshot(scene.w, scene.assets, 0);
    renderer->render(snap);
    float lift = 1.5f * voxels->volume().voxelSize;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    auto surfacePoint = [&](glm::vec3 o, glm::vec3 d, glm::vec3& p) {
      gi::RayHit h = bvh.intersect(o, d, 1e-4f, 100.0f);
      if (!h.hit) return false;
      p = o + d * h.t;
      // Lift against the incoming direction (towards the side that was seen).
      p -= d * lift * 1.2f;
      return true;
    };
    std::vector<glm::vec3> vpls, points;
    while (vpls.size() < 256) {
      float phi = 6.2831853f * U(rng), ct = 1.0f - U(rng) * (1.0f - std::cos(0.7f));
      float st = std::sqrt(1 - ct * ct);
      glm::vec3 p;
      if (surfacePoint({0, 1.9f, 0}, {st * std::cos(phi), -ct, st * std::sin(phi)}, p)) vpls.push_back(p);
    }
    while (points.size() < 4096) {
      glm::vec3 target(U(rng) * 2 - 1, U(rng) * 2, -1.0f);
      glm::vec3 p;
      if (surfacePoint({0, 1, 3.9f}, glm::normalize(target - glm::vec3(0, 1, 3.9f)), p)) points.push_back(p);
    }
    for (auto& v : vpls)
      for (auto& p : points) segments.push_back({v, p});
  }
};
VisibilitySet& visibilitySet() {
  static VisibilitySet set;
  return set;
}

void BM_SvoVisibility(benchmark::State& state) {
  VisibilitySet& v = visibilitySet();
  std::vector<uint8_t> out;
  size_t blocked = 0;
  gi::VoxelProbe probe(*v.voxels);
  for (auto _ : state) {
    probe.marchSegments(v.segments, out);
    state.SetIterationTime(probe.lastMarchWallMs() * 1e-3);
  }
  for (uint8_t b : out) blocked += b;
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(v.segments.size()));
  state.counters["occluded_fraction"] = double(blocked) / double(v.segments.size());
}
BENCHMARK(BM_SvoVisibility)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(5);

// The same dispatch with the march compiled out: reading a segment and writing its result, nothing
// else. No march on this device can be faster: the ceiling next to BM_SvoVisibility.
void BM_SvoVisibility_DispatchOnly(benchmark::State& state) {
  VisibilitySet& v = visibilitySet();
  std::vector<uint8_t> out;
  gi::VoxelProbe probe(*v.voxels);
  for (auto _ : state) {
    probe.marchSegmentsWithoutMarch(v.segments, out);
    state.SetIterationTime(probe.lastMarchWallMs() * 1e-3);
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(v.segments.size()));
}
BENCHMARK(BM_SvoVisibility_DispatchOnly)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(5);

// The SVO-restart march's C++ twin (double precision) on all cores, over the GPU-built SVO read back:
// the same algorithm as native CPU code, for comparison with Embree's BVH on the same cores.
void BM_SvoVisibility_CpuTwin(benchmark::State& state) {
  VisibilitySet& v = visibilitySet();
  static gi::SvoCpu svo(gi::VoxelProbe(*v.voxels).readbackNodes(), v.voxels->volume().resolution);
  const gi::VoxelVolume& vol = v.voxels->volume();
  std::vector<uint8_t> out(v.segments.size());
  std::atomic<uint64_t> restarts{0};
  for (auto _ : state) {
    gi::parallelFor(0, v.segments.size(), 4096, [&](size_t b, size_t e) {
      uint64_t sum = 0;
      for (size_t i = b; i < e; ++i) {
        glm::dvec3 a = (glm::dvec3(v.segments[i].from) - glm::dvec3(vol.origin)) / double(vol.voxelSize);
        glm::dvec3 c = (glm::dvec3(v.segments[i].to) - glm::dvec3(vol.origin)) / double(vol.voxelSize);
        uint32_t steps = 0;
        out[i] = svo.occluded(a, c, 1e-3, &steps) ? 1 : 0;
        sum += steps;
      }
      restarts += sum;
    });
  }
  size_t blocked = 0;
  for (uint8_t b : out) blocked += b;
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(v.segments.size()));
  state.counters["occluded_fraction"] = double(blocked) / double(v.segments.size());
  state.counters["restarts_per_segment"] = double(restarts) / double(state.iterations() * v.segments.size());
}
BENCHMARK(BM_SvoVisibility_CpuTwin)->UseRealTime()->Unit(benchmark::kMillisecond)->Iterations(3);

// The same segments through Embree on all cores (streams).
void BM_EmbreeOcclusion(benchmark::State& state) {
  VisibilitySet& v = visibilitySet();
  std::vector<uint8_t> out(v.segments.size());
  for (auto _ : state)
    gi::parallelFor(0, v.segments.size(), 4096, [&](size_t b, size_t e) { v.bvh.occluded(v.segments.data() + b, e - b, out.data() + b); });
  size_t blocked = 0;
  for (uint8_t b : out) blocked += b;
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(v.segments.size()));
  state.counters["occluded_fraction"] = double(blocked) / double(v.segments.size());
}
BENCHMARK(BM_EmbreeOcclusion)->UseRealTime()->Unit(benchmark::kMillisecond)->Iterations(5);

}  // namespace

BENCHMARK_MAIN();
