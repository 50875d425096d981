// dyngi_bench: speed figures that the tests deliberately do not assert.
// Run: build/bin/dyngi_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <filesystem>
#include <glm/gtc/quaternion.hpp>
#include <random>

#include "dyngi/engine/scene/animation.h"
#include "dyngi/engine/scene/gltf_import.h"
#include "dyngi/engine/scene/transform_system.h"
#include "dyngi/gi/bvh.h"
#include "dyngi/gi/bvh_sync.h"
#include "dyngi/gi/path_tracer.h"
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

}  // namespace

BENCHMARK_MAIN();
