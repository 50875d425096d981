// The GPU voxel scene against CPU oracles: exact triangle/box voxelization, the dense grid, a 3D-DDA,
// the SVO's C++ twin and the Embree BVH.
#include <gtest/gtest.h>

#include <functional>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/component_wise.hpp>
#include <random>

#include "support/report.h"
#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/engine/render/image_metrics.h"
#include "dyngi/engine/scene/scripted_motion.h"
#include "dyngi/engine/scene/transform_system.h"
#include "dyngi/gi/bvh.h"
#include "dyngi/gi/voxel_scene.h"
#include "testing/gi_probes.h"
#include "render/render_fixture.h"
#include "scenes/builtin_scenes.h"
#include "dyngi/engine/scene/animation.h"
#include "support/skinned_bar.h"

using namespace dyngi;
using namespace dyngi::test;

namespace {

std::vector<glm::vec3> voxelSpaceTriangles(const render::RenderSnapshot& s, const gi::VoxelVolume& v) {
  std::vector<glm::vec3> out;
  for (const auto& d : s.draws) {
    const auto& m = s.assets->mesh(d.mesh);
    for (uint32_t i : m.indices) out.push_back(v.toVoxel(glm::vec3(d.model * glm::vec4(m.positions[i], 1.0f))));
  }
  return out;
}

struct GridDiff {
  size_t missing = 0, extra = 0, reference = 0;
};
GridDiff diff(const gi::DenseVoxelGrid& got, const gi::DenseVoxelGrid& ref) {
  GridDiff d;
  uint32_t r = ref.resolution();
  for (uint32_t z = 0; z < r; ++z)
    for (uint32_t y = 0; y < r; ++y)
      for (uint32_t x = 0; x < r; ++x) {
        bool a = got.get(x, y, z), b = ref.get(x, y, z);
        d.reference += b;
        d.missing += b && !a;
        d.extra += a && !b;
      }
  return d;
}

class VoxelTest : public RenderTest {
 protected:
  // Renders `frames` frames of `scene` with a voxel scene plugged in.
  void run(const std::string& sceneName, uint32_t res, int frames) {
    sample::buildBuiltinScene(sceneName, world, assets);
    attachVoxels(res, 64, /*scriptedMotion=*/true);
    for (int f = 0; f < frames; ++f) step();
  }
  // A voxel scene at `res` in a renderer of size x size, with the systems that feed it.
  void attachVoxels(uint32_t res, uint32_t size, bool scriptedMotion = false) {
    voxels = std::make_unique<gi::VoxelScene>(context(), gi::VoxelSettings{.resolution = res});
    renderer = std::make_unique<render::Renderer>(context());
    renderer->addFeature(voxels.get());
    renderer->resize(size, size);
    if (scriptedMotion) scheduler.add(ecs::Phase::Update, std::make_unique<scene::ScriptedMotionSystem>());
    scheduler.add(ecs::Phase::PostUpdate, std::make_unique<scene::TransformSystem>());
    scheduler.add(ecs::Phase::PostUpdate, std::make_unique<gi::VoxelSyncSystem>(*voxels, assets));
  }
  ecs::Entity addMeshEntity(scene::MeshId mesh, const scene::Transform& t) {
    ecs::Entity e = world.create();
    world.add(e, t);
    world.add(e, scene::WorldTransform{t.matrix()});
    world.add(e, scene::MeshInstance{mesh, true});
    world.add(e, scene::Material{.baseColor = glm::vec4(0.6f)});
    return e;
  }
  void step() {
    scheduler.runFrame(world, ecs::FrameTime{0.2, 0.2 * double(frame), frame});
    snapshot = render::extractSnapshot(world, assets, frame);
    renderer->render(snapshot);
    ++frame;
  }
  // The SVO's leaves as they are now, and as a new voxel scene over the same snapshot and volume
  // builds them from scratch.
  gi::DenseVoxelGrid leaves() { return gi::SvoCpu(gi::VoxelProbe(*voxels).readbackNodes(), voxels->volume().resolution).leaves(); }
  gi::DenseVoxelGrid scratchLeaves() {
    gi::VoxelScene fresh(context(), gi::VoxelSettings{.resolution = voxels->volume().resolution});
    fresh.setVolume(voxels->volume());
    render::Renderer r2(context());
    r2.addFeature(&fresh);
    r2.resize(16, 16);
    r2.render(snapshot);
    return gi::SvoCpu(gi::VoxelProbe(fresh).readbackNodes(), fresh.volume().resolution).leaves();
  }
  ecs::World world;
  scene::AssetStore assets;
  ecs::Scheduler scheduler;
  std::unique_ptr<gi::VoxelScene> voxels;
  std::unique_ptr<render::Renderer> renderer;
  render::RenderSnapshot snapshot;
  uint64_t frame = 0;
};

}  // namespace

TEST_F(VoxelTest, VoxelizationCoversExactOverlapAndSvoLeavesEqualIt) {
  run("cornell", 128, 1);
  const auto& st = voxels->stats();
  EXPECT_EQ(st.entitiesVoxelized, 7u);
  EXPECT_EQ(st.overflowedEntities, 0u);
  EXPECT_FALSE(st.poolOverflow);
  gi::DenseVoxelGrid gpu = gi::VoxelProbe(*voxels).readbackFragmentGrid();
  gi::DenseVoxelGrid brute = gi::voxelizeBruteForce(voxelSpaceTriangles(snapshot, voxels->volume()), 128);
  GridDiff d = diff(gpu, brute);
  dyngi::test::report("voxelization 128^3: %zu voxels by exact overlap, GPU missed %zu, extra %zu\n", d.reference, d.missing, d.extra);
  EXPECT_GT(d.reference, 50000u);
  EXPECT_EQ(d.missing, 0u) << "no occupied voxel missed";
  EXPECT_LE(d.extra, d.reference / 100) << "extras (touching within 1e-4 voxel) stay rare";

  gi::SvoCpu svo(gi::VoxelProbe(*voxels).readbackNodes(), 128);
  GridDiff l = diff(svo.leaves(), gpu);
  EXPECT_EQ(l.missing + l.extra, 0u) << "the SVO's leaves are exactly the voxelized set";
  EXPECT_EQ(st.leaves, gpu.count());
  dyngi::test::report("svo: %llu nodes, %llu bytes, %llu leaves\n", (unsigned long long)st.nodes, (unsigned long long)st.svoBytes,
              (unsigned long long)st.leaves);
}

TEST_F(VoxelTest, SmallTrianglesTakeTheComputeVoxelizerAndWriteTheRasterPathsFragments) {
  // 400 boxes about a voxel wide, turned every way, in plain, emissive and textured materials, over a
  // floor whose triangles span the volume: the boxes take the compute voxelizer, the floor the raster
  // one. The same snapshot voxelized with the raster path alone (a second voxel scene over the same
  // volume) gives the same fragments, and both cover the exact overlap.
  scene::TextureData texture;
  texture.width = texture.height = 4;
  for (int i = 0; i < 16; ++i) texture.rgba8.insert(texture.rgba8.end(), {uint8_t(40 * (i % 4) + 60), uint8_t(30 * (i / 4) + 90), 200, 255});
  const scene::TextureId checker = assets.addTexture(texture);
  const scene::MeshId floor = assets.addMesh(scene::makeQuad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}));
  const scene::MeshId box = assets.addMesh(scene::makeBox(glm::vec3(0.008f)));
  addMeshEntity(floor, scene::Transform{});
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  for (int i = 0; i < 400; ++i) {
    scene::Transform t{.translation = glm::vec3(2.0f * U(rng) - 1.0f, 0.02f + 1.5f * U(rng), 2.0f * U(rng) - 1.0f)};
    t.rotation = glm::normalize(glm::quat(U(rng) - 0.5f, U(rng) - 0.5f, U(rng) - 0.5f, U(rng) - 0.5f));
    const ecs::Entity e = addMeshEntity(box, t);
    scene::Material& m = world.write<scene::Material>(e);
    m.baseColor = glm::vec4(U(rng), U(rng), U(rng), 1.0f);
    if (i % 3 == 1) m.emissive = glm::vec3(4.0f * U(rng), U(rng), 0.5f);
    if (i % 3 == 2) m.baseColorTexture = checker, m.metallic = 0.5f * U(rng);
  }
  attachVoxels(64, 32);
  step();
  EXPECT_EQ(voxels->stats().drawsComputeVoxelized, 400u);
  EXPECT_EQ(voxels->stats().entitiesVoxelized, 401u);

  auto sorted = [](std::vector<gi::VoxelFragment> f) {
    auto key = [](const gi::VoxelFragment& a) {
      return std::make_tuple(a.cell.x, a.cell.y, a.cell.z, a.albedo.r, a.albedo.g, a.albedo.b, a.emission.r, a.emission.g, a.emission.b, a.normal.x,
                             a.normal.y, a.normal.z);
    };
    std::sort(f.begin(), f.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
    return f;
  };
  const std::vector<gi::VoxelFragment> both = sorted(gi::VoxelProbe(*voxels).readbackFragments());
  // The same snapshot voxelized by a second voxel scene over the same volume, set up by `configure`:
  // its fragments, sorted, and how many draws took the compute voxelizer.
  auto voxelizeAgain = [&](const std::function<void(gi::VoxelScene&)>& configure) {
    gi::VoxelScene again(context(), gi::VoxelSettings{.resolution = 64});
    configure(again);
    again.setVolume(voxels->volume());
    render::Renderer second(context());
    second.addFeature(&again);
    second.resize(16, 16);
    second.render(snapshot);
    return std::make_pair(sorted(gi::VoxelProbe(again).readbackFragments()), again.stats().drawsComputeVoxelized);
  };
  const auto [rasterOnly, rasterComputeDraws] = voxelizeAgain([](gi::VoxelScene& v) { v.setComputeVoxelization(false); });
  EXPECT_EQ(rasterComputeDraws, 0u);
  ASSERT_EQ(both.size(), rasterOnly.size());
  size_t differ = 0;
  for (size_t i = 0; i < both.size(); ++i) {
    const gi::VoxelFragment &a = both[i], &b = rasterOnly[i];
    differ += a.cell != b.cell || glm::any(glm::greaterThan(glm::abs(a.albedo - b.albedo), glm::vec4(1.5f / 255))) ||
              glm::any(glm::greaterThan(glm::abs(a.emission - b.emission), glm::vec3(0.02f) * (b.emission + 1.0f))) ||
              glm::any(glm::greaterThan(glm::abs(a.normal - b.normal), glm::vec3(1.5f / 127)));
  }
  dyngi::test::report("small triangles: %zu fragments by both voxelizers, %zu by the raster one alone, %zu differ\n", both.size(), rasterOnly.size(),
                      differ);
  EXPECT_GT(both.size(), 10000u);
  EXPECT_EQ(differ, 0u);
  gi::DenseVoxelGrid brute = gi::voxelizeBruteForce(voxelSpaceTriangles(snapshot, voxels->volume()), 64);
  GridDiff d = diff(gi::VoxelProbe(*voxels).readbackFragmentGrid(), brute);
  EXPECT_EQ(d.missing, 0u);
  EXPECT_LE(d.extra, d.reference / 100);

  // A device allowing 3 x 4 workgroups a dispatch: the batches split into many 2-D dispatches, and the
  // fragments stay the same.
  const auto [splitFragments, splitComputeDraws] = voxelizeAgain([](gi::VoxelScene& v) { v.setComputeDispatchLimit({3, 4}); });
  EXPECT_EQ(splitComputeDraws, 400u);
  ASSERT_EQ(splitFragments.size(), both.size());
  size_t splitDiffer = 0;
  for (size_t i = 0; i < both.size(); ++i) splitDiffer += splitFragments[i].cell != both[i].cell || splitFragments[i].albedo != both[i].albedo;
  EXPECT_EQ(splitDiffer, 0u);
}

TEST(VoxelizeDispatch, EveryInstanceAndTriangleIsCoveredOnceWithinTheDeviceLimits) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 2000; ++trial) {
    const uint32_t instances = uint32_t(1 + rng() % 5000), triangles = uint32_t(1 + rng() % (trial % 3 == 0 ? 4000 : 40));
    const glm::uvec2 limit(uint32_t(1 + rng() % (trial % 2 ? 70000 : 9)), uint32_t(1 + rng() % 9));
    const auto parts = gi::VoxelScene::splitComputeVoxelize(instances, triangles, limit);
    if (uint64_t(triangles) > uint64_t(limit.x) * limit.y * 64) continue;  // voxelizesByCompute sends such meshes to the raster path
    uint32_t next = 0;
    for (const auto& p : parts) {
      ASSERT_EQ(p.firstInstance, next);
      ASSERT_GT(p.instanceCount, 0u);
      next += p.instanceCount;
      ASSERT_LE(p.groups.x, limit.x);
      ASSERT_LE(p.groups.y, limit.y);
      const uint64_t invocations = uint64_t(p.groups.x) * p.groups.y * 64, needed = uint64_t(p.instanceCount) * triangles;
      ASSERT_GE(invocations, needed) << "every triangle has an invocation";
      ASSERT_LT(invocations, needed + 64 * (uint64_t(p.groups.x) + 1)) << "at most a row of groups to spare";
    }
    ASSERT_EQ(next, instances);
  }
  EXPECT_TRUE(gi::VoxelScene::splitComputeVoxelize(0, 12, {65535, 65535}).empty());
  EXPECT_EQ(gi::VoxelScene::splitComputeVoxelize(200000, 2, {65535, 65535}).size(), 1u) << "one dispatch where the device allows it";
}

TEST_F(VoxelTest, SvoMarchEqualsDenseDdaAndGpuEqualsCppTwin) {
  run("cornell", 64, 1);
  gi::DenseVoxelGrid grid = gi::VoxelProbe(*voxels).readbackFragmentGrid();
  gi::SvoCpu svo(gi::VoxelProbe(*voxels).readbackNodes(), 64);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-4.0, 68.0);  // some segments start or end outside the volume
  const int n = 100000;
  std::vector<gi::Segment> worldSegs(n);
  std::vector<uint8_t> cpu(n);
  int disagreeDda = 0, occluded = 0;
  for (int i = 0; i < n; ++i) {
    glm::dvec3 a(U(rng), U(rng), U(rng)), b(U(rng), U(rng), U(rng));
    bool s = svo.occluded(a, b, 1e-3);
    bool d = grid.occluded(a, b, 1e-3);
    disagreeDda += s != d;
    occluded += s;
    cpu[size_t(i)] = s;
    worldSegs[size_t(i)] = {voxels->volume().toWorld(glm::vec3(a)), voxels->volume().toWorld(glm::vec3(b))};
  }
  EXPECT_EQ(disagreeDda, 0) << "C++ SVO-restart march vs dense 3D-DDA";
  EXPECT_GT(occluded, n / 10);
  EXPECT_LT(occluded, n * 9 / 10);

  std::vector<uint8_t> gpu;
  gi::VoxelProbe probe(*voxels);
  double ms = probe.marchSegments(worldSegs, gpu);
  int disagreeGpu = 0;
  for (int i = 0; i < n; ++i) disagreeGpu += gpu[size_t(i)] != cpu[size_t(i)];
  dyngi::test::report("GPU march: %d segments in %.2f ms (timestamps), %.2f ms (submit to fence), %d disagreements with the C++ twin\n", n, ms,
              probe.lastMarchWallMs(), disagreeGpu);
  EXPECT_LE(disagreeGpu, n / 1000);

  // The twin built on the CPU from the dense grid means the same thing.
  gi::SvoCpu rebuilt = gi::SvoCpu::fromDense(grid);
  for (int i = 0; i < 2000; ++i) {
    glm::dvec3 a(U(rng), U(rng), U(rng)), b(U(rng), U(rng), U(rng));
    ASSERT_EQ(rebuilt.occluded(a, b, 1e-3), svo.occluded(a, b, 1e-3));
  }
}

TEST_F(VoxelTest, AgreesWithEmbreeAwayFromSurfaces) {
  run("cornell", 128, 1);
  gi::DenseVoxelGrid grid = gi::VoxelProbe(*voxels).readbackFragmentGrid();
  gi::EmbreeScene bvh;
  bvh.sync(world, assets, 0);
  const gi::VoxelVolume& v = voxels->volume();
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  std::vector<gi::Segment> segs;
  // Ends inside the room, more than two voxels from any surface.
  while (segs.size() < 20000) {
    glm::vec3 a(U(rng) * 2 - 1, U(rng) * 2, U(rng) * 2 - 1), b(U(rng) * 2 - 1, U(rng) * 2, U(rng) * 2 - 1);
    glm::ivec3 va(glm::floor(v.toVoxel(a))), vb(glm::floor(v.toVoxel(b)));
    if (grid.distanceToOccupied(va, 2) <= 2 || grid.distanceToOccupied(vb, 2) <= 2) continue;
    segs.push_back({a, b});
  }
  std::vector<uint8_t> svo;
  gi::VoxelProbe(*voxels).marchSegments(segs, svo);
  int agree = 0, svoOnly = 0, embreeOnly = 0;
  for (size_t i = 0; i < segs.size(); ++i) {
    bool e = bvh.occluded(segs[i]);
    bool s = svo[i] != 0;
    agree += e == s;
    svoOnly += s && !e;
    embreeOnly += e && !s;
  }
  double rate = double(agree) / double(segs.size());
  dyngi::test::report("SVO vs Embree: %.3f%% agree; %d blocked only by voxels (grazing: voxels are fatter than triangles), "
              "%d blocked only by triangles\n", 100.0 * rate, svoOnly, embreeOnly);
  EXPECT_GE(rate, 0.98);
  EXPECT_EQ(embreeOnly, 0) << "voxelization is conservative: a triangle in the way always occupies a voxel";
}

// The leaf list (what VCT's passes over leaves walk) is exactly the leaf level's occupied nodes, each once.
static void expectLeafListIsTheOccupiedLeaves(gi::VoxelScene& voxels, const std::string& when) {
  const gi::VoxelProbe::LeafListCheck c = gi::VoxelProbe(voxels).checkLeafList();
  ASSERT_TRUE(c.countFits) << when;
  EXPECT_GT(c.occupied, 1000u) << when;
  EXPECT_EQ(c.entries.size(), c.occupied) << when;
  EXPECT_EQ(c.stray, 0u) << when << ": entries that are not occupied leaves";
  EXPECT_EQ(c.missed, 0u) << when << ": occupied leaves missing from the list";
  EXPECT_EQ(c.duplicates, 0u) << when;
  EXPECT_EQ(c.wrongCells, 0u) << when << ": entries whose cell is not their node's";
  EXPECT_EQ(c.occupied, voxels.stats().leaves) << when;
  EXPECT_TRUE(c.dispatchCovers) << when << ": the header's dispatch covers the list";
}

// Every occupied leaf's attribute sums (what radiance injection lights) are those of the fragments in its
// voxel, summed on the CPU; in a build that overflowed the node pool too, for the leaves it has.
static void expectLeafAttributesSumTheirFragments(gi::VoxelScene& voxels, const std::string& when) {
  const gi::VoxelProbe::LeafAttributesCheck c = gi::VoxelProbe(voxels).checkLeafAttributes();
  dyngi::test::report("%s: %llu leaves, attributes wrong: count %llu, albedo %llu, normal %llu; leaf sum words left %llu\n", when.c_str(),
              (unsigned long long)c.leaves, (unsigned long long)c.wrongCount, (unsigned long long)c.wrongAlbedo, (unsigned long long)c.wrongNormal,
              (unsigned long long)c.sumsLeft);
  EXPECT_GT(c.leaves, 1000u) << when;
  EXPECT_EQ(c.wrongCount + c.wrongAlbedo + c.wrongNormal, 0u) << when;
  EXPECT_EQ(c.sumsLeft, 0u) << when << ": the leaf sums must be zero for the next build";
}

TEST_F(VoxelTest, MovingObjectsReVoxelizeOnlyThemselvesAndMatchARebuild) {
  run("cornell-dynamic", 64, 2);
  for (int f = 0; f < 3; ++f) {
    step();
    EXPECT_EQ(voxels->stats().entitiesVoxelized, 2u) << "only the two moving boxes";
    EXPECT_TRUE(voxels->stats().rebuilt);
  }
  GridDiff d = diff(leaves(), scratchLeaves());
  EXPECT_EQ(d.missing + d.extra, 0u) << "voxels the boxes left are gone, new ones are there";
  expectLeafListIsTheOccupiedLeaves(*voxels, "after the boxes moved");
  expectLeafAttributesSumTheirFragments(*voxels, "after the boxes moved");
  // And nothing moves: nothing is re-voxelized, the SVO is kept.
  auto& motion = world;  // stop the scripted motion
  std::vector<ecs::Entity> movers;
  motion.each<scene::ScriptedMotion>([&](ecs::Entity e, const scene::ScriptedMotion&) { movers.push_back(e); });
  for (ecs::Entity e : movers) motion.remove<scene::ScriptedMotion>(e);
  step();
  step();
  EXPECT_EQ(voxels->stats().entitiesVoxelized, 0u);
  EXPECT_FALSE(voxels->stats().rebuilt);
}

// Every voxel that empties in a frame lies in one of that frame's stale boxes (what VCT clears instead of
// its whole volumes): boxes moving, then one removed. The first frame is stale everywhere.
TEST_F(VoxelTest, StaleBoxesHoldEveryVoxelThatEmptied) {
  run("cornell-dynamic", 64, 1);
  EXPECT_TRUE(voxels->staleEverywhere()) << "the first frame voxelizes everything";
  step();
  auto inAStaleBox = [&](uint32_t x, uint32_t y, uint32_t z) {
    for (const gi::VoxelBox& b : voxels->staleBoxes())
      if (glm::all(glm::greaterThanEqual(glm::uvec3(x, y, z), b.min)) && glm::all(glm::lessThanEqual(glm::uvec3(x, y, z), b.max))) return true;
    return false;
  };
  for (int f = 0; f < 4; ++f) {
    const gi::DenseVoxelGrid before = leaves();
    if (f == 3) {  // the tall box goes
      ecs::Entity tall{};
      world.each<scene::Name>([&](ecs::Entity e, const scene::Name& n) {
        if (n.value == "tall_box") tall = e;
      });
      ASSERT_TRUE(world.alive(tall));
      world.destroy(tall);
    }
    step();
    EXPECT_FALSE(voxels->staleEverywhere());
    const gi::DenseVoxelGrid after = leaves();
    uint64_t emptied = 0, outside = 0, boxVoxels = 0;
    for (uint32_t z = 0; z < 64; ++z)
      for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x)
          if (before.get(x, y, z) && !after.get(x, y, z)) ++emptied, outside += !inAStaleBox(x, y, z);
    for (const gi::VoxelBox& b : voxels->staleBoxes()) boxVoxels += b.voxels();
    dyngi::test::report("frame %llu: %llu voxels emptied, %llu outside the %zu stale boxes (%llu voxels)\n", (unsigned long long)frame,
                (unsigned long long)emptied, (unsigned long long)outside, voxels->staleBoxes().size(), (unsigned long long)boxVoxels);
    EXPECT_GT(emptied, 0u) << "frame " << frame << ": the test means voxels to empty";
    EXPECT_EQ(outside, 0u) << "frame " << frame;
    EXPECT_LT(boxVoxels, 64u * 64u * 64u / 4u) << "the boxes are the movers' (a sixth of the volume), not the volume";
  }
}

// The build keeps the occupancy of entities that have not moved lately and marks only the moving ones'
// fragments on top; their attributes too are kept per voxel and only the moving ones' summed. An entity
// of the kept occupancy that starts moving, one that stops and settles, one that moves again: the SVO
// must equal a from-scratch build every time, the attributes must average the fragments in each voxel,
// and a build with one mover must read that mover's fragments only.
TEST_F(VoxelTest, KeptStaticOccupancyFollowsEntitiesThatStartAndStopMoving) {
  sample::buildBuiltinScene("cornell", world, assets);
  attachVoxels(64, 16);
  step();
  const uint32_t everyone = voxels->stats().staticEntities;
  ASSERT_GT(everyone, 2u);
  ecs::Entity shortBox{}, tallBox{};
  world.each<scene::Name>([&](ecs::Entity e, const scene::Name& n) {
    if (n.value == "short_box") shortBox = e;
    if (n.value == "tall_box") tallBox = e;
  });
  ASSERT_TRUE(world.alive(shortBox) && world.alive(tallBox));
  auto expectScratch = [&](const char* what) {
    GridDiff d = diff(leaves(), scratchLeaves());
    EXPECT_EQ(d.missing + d.extra, 0u) << what;
    expectLeafAttributesSumTheirFragments(*voxels, what);
  };
  auto nudge = [&](ecs::Entity e, float dx) {
    world.write<scene::Transform>(e).translation.x += dx;
    step();
  };
  // The short box leaves the kept occupancy (rebuilt without it), then only its fragments are marked.
  nudge(shortBox, 0.05f);
  expectScratch("short box starts moving");
  EXPECT_EQ(voxels->stats().staticEntities, everyone - 1);
  nudge(shortBox, 0.05f);
  expectScratch("short box keeps moving");
  const uint64_t moverSlots = voxels->stats().slotsMarked;
  EXPECT_GT(moverSlots, 0u);
  EXPECT_LT(moverSlots * 4, voxels->stats().fragmentCapacity) << "a build with one mover marks the mover only";
  // It settles; nothing is rebuilt while nothing moves. The tall box's first motion rebuilds the kept
  // occupancy, now with the short box in it and without the tall box.
  for (int f = 0; f < 61; ++f) step();
  nudge(tallBox, -0.05f);
  expectScratch("tall box starts moving, short box settled");
  EXPECT_EQ(voxels->stats().staticEntities, everyone - 1);
  nudge(shortBox, -0.1f);
  expectScratch("short box moves again");
  EXPECT_EQ(voxels->stats().staticEntities, everyone - 2);
}

// Fine meshes: the per-entity range estimate takes a small triangle's bounding box, so the first frame
// holds little more than it writes. Removed entities leave holes; once the ranges hold more than twice
// what they need they are compacted to what they hold (static entities exactly, moving ones with their
// slack): the SVO must equal a from-scratch build, and later motion must still match one.
TEST_F(VoxelTest, FragmentRangesAreCompactedWithoutLosingVoxels) {
  sample::buildBuiltinScene("cornell", world, assets);
  scene::MeshId sphere = assets.addMesh(scene::makeSphere(0.2f, 96, 48));
  std::vector<ecs::Entity> spheres;
  for (int i = 0; i < 3; ++i) {
    scene::Transform t;
    t.translation = {-0.5f + 0.5f * float(i), 1.0f, 0.2f};
    spheres.push_back(addMeshEntity(sphere, t));
  }
  attachVoxels(128, 32);
  step();
  const uint64_t firstCapacity = voxels->stats().fragmentCapacity, fragments = voxels->stats().fragments;
  EXPECT_LE(firstCapacity, 2 * fragments) << "the first frame's ranges: small triangles bounded by their boxes";
  // The room's walls, floor and ceiling go (the boxes and spheres stay): the next frame empties their
  // ranges, the one after compacts.
  std::vector<ecs::Entity> room;
  world.each<scene::Name>([&](ecs::Entity e, const scene::Name& n) {
    if (world.has<scene::MeshInstance>(e) && n.value != "short_box" && n.value != "tall_box") room.push_back(e);
  });
  ASSERT_FALSE(room.empty());
  for (ecs::Entity e : room) world.destroy(e);
  step();
  step();
  const uint64_t compactCapacity = voxels->stats().fragmentCapacity;
  dyngi::test::report("fragments %llu: slots %llu -> %llu after compaction (%llu fragments); total %.1f MB\n", (unsigned long long)fragments,
                      (unsigned long long)firstCapacity, (unsigned long long)compactCapacity, (unsigned long long)voxels->stats().fragments,
                      double(voxels->stats().totalBytes) / (1 << 20));
  EXPECT_LT(compactCapacity * 2, firstCapacity);
  EXPECT_LE(voxels->stats().fragments, compactCapacity);
  GridDiff same = diff(leaves(), scratchLeaves());
  EXPECT_EQ(same.missing + same.extra, 0u);
  // What is allocated follows what is held: fragments (the record, leaf attributes), the SVO's nodes
  // with their cells and the occupancy pyramid, within a factor of 3, besides the static attributes'
  // fixed 16 bytes a voxel and the smallest fragment store.
  const gi::VoxelStats& st = voxels->stats();
  const uint64_t pyramidBytes = ((((uint64_t(1) << 24) - 1) / 7) + 31) / 32 * 4;  // levels 0..7 of 128^3
  const uint64_t staticAttributeBytes = (uint64_t(1) << 21) * 16;               // 128^3 voxels
  const uint64_t smallestStore = gi::FragmentRanges::kMinCompactSlots * (16 + 2 * 32);
  EXPECT_EQ(voxels->voxelAttributes().desc().width, 128u);
  EXPECT_LT(st.totalBytes - staticAttributeBytes, smallestStore + 3 * (st.fragments * (16 + 32) + 2 * st.svoBytes + pyramidBytes));
  // One sphere starts moving (its exact-size range is too small for a new pose: it gets a new one).
  for (int f = 0; f < 4; ++f) {
    world.write<scene::Transform>(spheres[1]).rotation = glm::angleAxis(0.4f * float(f + 1), glm::vec3(0.3f, 1.0f, 0.2f));
    world.write<scene::Transform>(spheres[1]).translation.x += 0.05f;
    step();
    EXPECT_EQ(voxels->stats().overflowedEntities, 0u);
    GridDiff d = diff(leaves(), scratchLeaves());
    EXPECT_EQ(d.missing + d.extra, 0u) << "frame " << f;
  }
}

// A moving mesh's range is sized from its last count; one scaled up 5x in one frame (25x the surface)
// must get a range grown with it, not overflow and lose voxels for a frame.
TEST_F(VoxelTest, MeshScaledUpInOneFrameKeepsAllItsVoxels) {
  sample::buildBuiltinScene("cornell", world, assets);
  attachVoxels(128, 32);
  step();
  const uint64_t walls = voxels->stats().fragments;
  scene::Transform t;
  t.translation = {0.0f, 1.0f, 0.0f};
  t.scale = glm::vec3(0.5f);
  ecs::Entity sphere = addMeshEntity(assets.addMesh(scene::makeSphere(0.2f, 48, 24)), t);
  for (int f = 0; f < 3; ++f) {  // moving: its range follows its count
    world.write<scene::Transform>(sphere).translation.x += 0.02f;
    step();
  }
  const uint64_t before = voxels->stats().fragments - walls;
  world.write<scene::Transform>(sphere).scale = glm::vec3(2.5f);
  step();
  const uint64_t after = voxels->stats().fragments - walls;
  dyngi::test::report("sphere scaled 5x: %llu -> %llu fragments, %u entities overflowed\n", (unsigned long long)before,
              (unsigned long long)after, voxels->stats().overflowedEntities);
  EXPECT_GT(after, 2 * before + 64) << "more than a moving range's slack: sized from the old count it overflows";
  EXPECT_EQ(voxels->stats().overflowedEntities, 0u);
  GridDiff d = diff(leaves(), scratchLeaves());
  EXPECT_EQ(d.missing + d.extra, 0u) << "no voxel lost in the frame it grew";
}

// A debug view draws over hdr after lighting and before tone mapping: the display image is the
// tone-mapped debug view, not the lit frame (and the frame stays clean under validation).
TEST_F(VoxelTest, DebugViewIsWhatTheDisplayImageShows) {
  run("cornell", 64, 1);
  render::RendererSettings rs;
  const std::vector<uint8_t> lit = renderer->readbackLdr();
  voxels->setDebugView(gi::VoxelDebugView::Voxels);
  step();
  const std::vector<uint8_t> shown = renderer->readbackLdr();
  const std::vector<uint8_t> expected = render::tonemapToSrgb8(renderer->readback(render::TargetId::Hdr), rs.exposure, rs.toneMapper);
  int worst = 0;
  size_t differing = 0;
  for (size_t i = 0; i < shown.size(); ++i) {
    worst = std::max(worst, std::abs(int(shown[i]) - int(expected[i])));
    differing += std::abs(int(shown[i]) - int(lit[i])) > 8;
  }
  EXPECT_LE(worst, 1) << "the display image is the tone-mapped debug view";
  EXPECT_GT(differing, shown.size() / 10) << "the debug view looks unlike the lit frame";
}

// A cap on the voxelization per frame (what a GI budget sets) spreads a big change over frames: with a
// cap of one entity, every mesh of the room moved at once is re-voxelized one a frame, the longest
// waiting first (a box that keeps moving does not hold the others back), and once all have had their
// turn the SVO equals a build from scratch.
TEST_F(VoxelTest, AVoxelizationCapSpreadsABigMoveOverFrames) {
  sample::buildBuiltinScene("cornell", world, assets);
  attachVoxels(128, 64);
  step();
  step();
  std::vector<ecs::Entity> meshes;
  world.each<scene::MeshInstance>([&](ecs::Entity e, const scene::MeshInstance&) { meshes.push_back(e); });
  ASSERT_GE(meshes.size(), 5u);
  voxels->setVoxelizeCap(1);  // fragments: always below one entity's estimate, so one entity a frame
  for (ecs::Entity e : meshes) world.write<scene::Transform>(e).translation.y += 0.02f;
  ecs::Entity shortBox{};
  world.each<scene::Name>([&](ecs::Entity e, const scene::Name& n) {
    if (n.value == "short_box") shortBox = e;
  });
  std::vector<uint32_t> voxelized, deferred;
  for (size_t f = 0; f < meshes.size() + 2; ++f) {
    if (f > 0) world.write<scene::Transform>(shortBox).translation.x += 0.01f;  // moves every frame
    step();
    voxelized.push_back(voxels->stats().entitiesVoxelized);
    deferred.push_back(voxels->stats().entitiesDeferred);
  }
  std::string trace;
  for (size_t f = 0; f < deferred.size(); ++f) {
    char step[32];
    std::snprintf(step, sizeof step, " %u/%u", voxelized[f], deferred[f]);
    trace += step;
  }
  dyngi::test::report("%zu meshes moved at once, a cap of one a frame (voxelized/deferred per frame):%s\n", meshes.size(), trace.c_str());
  EXPECT_EQ(deferred.front(), meshes.size() - 1);
  for (size_t f = 0; f < deferred.size(); ++f) {
    EXPECT_EQ(voxelized[f], 1u) << "frame " << f;
    if (f > 0 && deferred[f - 1] > 1) {
      EXPECT_EQ(deferred[f], deferred[f - 1] - 1) << "frame " << f << ": the moving box waits its turn";
    }
  }
  EXPECT_LE(deferred.back(), 1u) << "only the moving box's latest move may still wait";
  voxels->setVoxelizeCap(0);
  step();
  EXPECT_EQ(voxels->stats().entitiesDeferred, 0u);
  const GridDiff d = diff(leaves(), scratchLeaves());
  EXPECT_EQ(d.missing + d.extra, 0u) << "every spread re-voxelization landed";
}

// A volume with every voxel occupied needs the full tree: the pool, bounded by the full tree's groups
// rather than the setting's limit, holds it without overflow (one group fewer would overflow).
TEST_F(VoxelTest, AFullVolumeFitsTheNodePoolAFullTreeNeeds) {
  constexpr uint32_t kRes = 16;
  // A sheet through the middle of every layer of voxels, each a little wider than the volume.
  scene::MeshId sheet = assets.addMesh(scene::makeQuad({-0.1f, -0.1f, 0.0f}, {1.2f, 0.0f, 0.0f}, {0.0f, 1.2f, 0.0f}));
  for (uint32_t z = 0; z < kRes; ++z) {
    scene::Transform t;
    t.translation = {0.0f, 0.0f, (float(z) + 0.5f) / float(kRes)};
    addMeshEntity(sheet, t);
  }
  attachVoxels(kRes, 16);
  voxels->setVolume(gi::VoxelVolume{.origin = glm::vec3(0.0f), .voxelSize = 1.0f / float(kRes), .resolution = kRes});
  step();
  const auto& st = voxels->stats();
  uint64_t fullTree = 1;  // the root's group, then one per node of levels 0..depth-1
  for (uint64_t n = 1; n < kRes * kRes * kRes; n *= 8) fullTree += n;
  dyngi::test::report("full %u^3 volume: %llu leaves, %llu nodes (full tree %llu groups), overflow %d\n", kRes,
                      (unsigned long long)st.leaves, (unsigned long long)st.nodes, (unsigned long long)fullTree, int(st.poolOverflow));
  EXPECT_EQ(st.leaves, uint64_t(kRes) * kRes * kRes);
  EXPECT_FALSE(st.poolOverflow);
  EXPECT_EQ(st.nodes, 8 * fullTree);
  EXPECT_EQ(diff(leaves(), gi::voxelizeBruteForce(voxelSpaceTriangles(snapshot, voxels->volume()), kRes)).missing, 0u);
}

// The first build's node pool is fitted to the bound the voxel boxes give (half over it); when the scene
// then needs more, the build that overflows is conservative (no voxel missing) and the pool grows so the
// next one is exact.
TEST_F(VoxelTest, NodePoolGrowsWhenTheSceneNeedsMore) {
  run("cornell", 128, 2);
  const uint64_t smallPool = voxels->stats().totalBytes;
  gi::VoxelProbe probe(*voxels);
  EXPECT_GE(probe.nodeGroupBound(), voxels->stats().nodes / 8) << "the bound holds";
  EXPECT_LE(probe.nodeGroupCapacity(), probe.nodeGroupBound() * 3 / 2) << "the first pool is fitted, not the full tree";
  // Thirty slanted sheets across the room: far more occupied voxels than the box had.
  scene::MeshId sheet = assets.addMesh(scene::makeQuad({-0.95f, 0.0f, -0.95f}, {1.9f, 0.0f, 0.0f}, {0.0f, 0.15f, 1.9f}));
  for (int i = 0; i < 30; ++i) {
    ecs::Entity e = world.create();
    scene::Transform t;
    t.translation = {0.0f, 0.1f + 0.055f * float(i), 0.0f};
    world.add(e, t);
    world.add(e, scene::WorldTransform{t.matrix()});
    world.add(e, scene::MeshInstance{sheet, true});
    world.add(e, scene::Material{.baseColor = glm::vec4(0.6f)});
  }
  step();
  gi::DenseVoxelGrid exact = gi::voxelizeBruteForce(voxelSpaceTriangles(snapshot, voxels->volume()), 128);
  GridDiff first = diff(leaves(), exact);
  dyngi::test::report("pool %.2f MB after the first build; sheets added: overflow %d, %zu missing, %zu extra\n",
              double(smallPool) / (1 << 20), int(voxels->stats().poolOverflow), first.missing, first.extra);
  EXPECT_TRUE(voxels->stats().poolOverflow) << "the test means to overflow the shrunken pool";
  EXPECT_EQ(first.missing, 0u) << "an overflowing build is conservative";
  expectLeafAttributesSumTheirFragments(*voxels, "the build that overflowed");
  step();
  EXPECT_FALSE(voxels->stats().poolOverflow);
  // Exact again: the same leaves as a from-scratch build with a pool big enough from the start.
  GridDiff second = diff(leaves(), scratchLeaves());
  EXPECT_EQ(second.missing + second.extra, 0u);
  EXPECT_EQ(diff(leaves(), exact).missing, 0u);
  expectLeafAttributesSumTheirFragments(*voxels, "the build after");
}

// Many small instances: more fragments than the first storage holds, so it grows in the first frame,
// the leaf attributes and the first node pool sized by the bounds the voxel boxes give instead of two
// slots a fragment and the full tree. The bounds hold (the SVO fits them: no overflow), every leaf's
// attributes match its fragments (truth: the fragments averaged on the CPU), the leaves are the cells
// with fragments, and the next frame finds nothing to grow.
TEST_F(VoxelTest, ManySmallInstancesGetLeafAttributesSizedByTheirBoxes) {
  const scene::MeshId box = assets.addMesh(scene::makeBox(glm::vec3(0.01f)));
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  for (int i = 0; i < 6000; ++i) addMeshEntity(box, scene::Transform{.translation = glm::vec3(U(rng), 0.25f * U(rng), U(rng))});
  attachVoxels(64, 16);
  step();
  const gi::VoxelStats& s = voxels->stats();
  gi::VoxelProbe probe(*voxels);
  ASSERT_GT(s.fragmentCapacity, 1u << 16) << "the storage grew in the first frame";
  EXPECT_GE(probe.leafSlotBound(), s.leafSlots);
  EXPECT_GE(probe.nodeGroupBound(), s.nodes / 8);
  EXPECT_FALSE(s.poolOverflow);
  EXPECT_LE(probe.nodeGroupCapacity(), 2 * probe.nodeGroupBound()) << "the bound, not the full tree";
  EXPECT_GE(probe.attributeLeaves(), s.leafSlots) << "every leaf slot has its sums";
  EXPECT_LT(probe.attributeLeaves(), std::min<uint64_t>(2 * s.fragmentCapacity, 1u << 20) / 2) << "the bound, not two slots a fragment";
  // Their ranges are small and neighbours: chunks of several ranges mark them.
  const GridDiff cells = diff(probe.readbackLeafCells(), probe.readbackFragmentGrid());
  EXPECT_EQ(cells.missing + cells.extra, 0u) << "the leaves are the voxelized cells";
  const gi::VoxelProbe::LeafAttributesCheck check = probe.checkLeafAttributes();
  EXPECT_GT(check.leaves, 3000u);
  EXPECT_EQ(check.wrongCount + check.wrongAlbedo + check.wrongNormal, 0u);
  step();
  EXPECT_FALSE(voxels->stats().rebuilt) << "nothing moved and nothing grew: the SVO stands";
}

// The node pool shrinks to what the SVO uses after a build that needs far less, while the SVO itself
// stands until something changes. Its node cells (where radiance injection puts each leaf, where the VCT
// atlas puts each node's texel) must come along, in a still scene as many frames later as it likes.
TEST_F(VoxelTest, ShrunkNodePoolKeepsTheLeavesWhereTheyAre) {
  run("cornell", 64, 1);
  // All but the short box removed: the SVO needs a fraction of the pool, which shrinks after the build.
  const uint64_t poolBefore = gi::VoxelProbe(*voxels).nodeGroupCapacity();
  std::vector<ecs::Entity> others;
  world.each<scene::Name>([&](ecs::Entity e, const scene::Name& n) {
    if (n.value != "short_box" && world.has<scene::MeshInstance>(e)) others.push_back(e);
  });
  for (ecs::Entity e : others) world.destroy(e);
  step();
  ASSERT_LT(gi::VoxelProbe(*voxels).nodeGroupCapacity(), poolBefore / 2) << "the test means to shrink the pool";
  const gi::DenseVoxelGrid fragments = gi::VoxelProbe(*voxels).readbackFragmentGrid();
  for (int still = 0; still < 2; ++still) {
    GridDiff d = diff(gi::VoxelProbe(*voxels).readbackLeafCells(), fragments);
    EXPECT_GT(d.reference, 1000u);
    EXPECT_EQ(d.missing + d.extra, 0u) << "frame " << frame << ": leaf cells against the voxelized set";
    expectLeafListIsTheOccupiedLeaves(*voxels, "after the pool shrank, frame " + std::to_string(frame));
    step();
    EXPECT_FALSE(voxels->stats().rebuilt) << "nothing moved: the SVO stands";
  }
}

TEST_F(VoxelTest, ObjectLeavingTheVolumeIsClippedNotFatal) {
  run("cornell", 64, 1);
  ecs::Entity box{};
  world.each<scene::Name>([&](ecs::Entity e, const scene::Name& n) {
    if (n.value == "short_box") box = e;
  });
  // Half in, half out through the right wall, then far away.
  for (glm::vec3 at : {glm::vec3(1.05f, 0.3f, 0.0f), glm::vec3(40.0f, 0.3f, 0.0f)}) {
    world.write<scene::Transform>(box).translation = at;
    step();
    gi::DenseVoxelGrid gpu = gi::VoxelProbe(*voxels).readbackFragmentGrid();
    gi::DenseVoxelGrid brute = gi::voxelizeBruteForce(voxelSpaceTriangles(snapshot, voxels->volume()), 64);
    GridDiff d = diff(gpu, brute);
    EXPECT_EQ(d.missing, 0u) << "inside the volume nothing is lost";
    EXPECT_LE(d.extra, d.reference / 100);
    GridDiff l = diff(leaves(), gpu);
    EXPECT_EQ(l.missing + l.extra, 0u);
  }
}

// Materials are pipeline variants (texture lookups compiled in only when a texture is bound): a textured
// base colour and a textured emission reach the G-buffer and the voxel fragments, an untextured
// material keeps its factor. Truth: the textures are one solid colour, so any lookup returns it.
TEST_F(VoxelTest, TexturedAndUntexturedMaterialsReachGBufferAndVoxels) {
  auto solid = [&](uint8_t r, uint8_t g, uint8_t b) {
    scene::TextureData t;
    t.width = t.height = 4;
    t.srgb = true;
    for (int i = 0; i < 16; ++i) t.rgba8.insert(t.rgba8.end(), {r, g, b, 255});
    return assets.addTexture(t);
  };
  auto srgbToLinear = [](float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); };
  const scene::MeshId box = assets.addMesh(scene::makeBox(glm::vec3(0.4f)));
  struct Case {
    float x;
    scene::Material material;
    glm::vec3 albedo, emission;  // expected
  };
  const glm::vec3 tex1(srgbToLinear(200 / 255.0f), srgbToLinear(100 / 255.0f), srgbToLinear(50 / 255.0f));
  const glm::vec3 tex2(1.0f, srgbToLinear(128 / 255.0f), 0.0f);
  std::vector<Case> cases = {
      {-1.0f, scene::Material{.baseColor = glm::vec4(0.2f, 0.5f, 0.8f, 1.0f)}, glm::vec3(0.2f, 0.5f, 0.8f), glm::vec3(0.0f)},
      {0.0f, scene::Material{.baseColor = glm::vec4(0.5f, 1.0f, 1.0f, 1.0f), .baseColorTexture = solid(200, 100, 50)},
       glm::vec3(0.5f, 1.0f, 1.0f) * tex1, glm::vec3(0.0f)},
      {1.0f, scene::Material{.baseColor = glm::vec4(0.3f, 0.3f, 0.3f, 1.0f), .emissive = glm::vec3(2.0f), .emissiveTexture = solid(255, 128, 0)},
       glm::vec3(0.3f), 2.0f * tex2},
  };
  for (const Case& c : cases) {
    ecs::Entity e = addMeshEntity(box, scene::Transform{.translation = glm::vec3(c.x, 0.0f, 0.0f)});
    world.write<scene::Material>(e) = c.material;
  }
  ecs::Entity cam = world.create();
  scene::Transform ct{.translation = glm::vec3(0.0f, 0.0f, 3.0f)};
  world.add(cam, ct);
  world.add(cam, scene::WorldTransform{ct.matrix()});
  world.add(cam, scene::Camera{});
  world.add(cam, scene::ActiveCamera{});
  attachVoxels(64, 96);
  step();
  const std::vector<glm::vec4> position = renderer->readback(render::TargetId::Position);
  const std::vector<glm::vec4> albedo = renderer->readback(render::TargetId::Albedo);
  const std::vector<glm::vec4> emissive = renderer->readback(render::TargetId::Emissive);
  const std::vector<gi::VoxelFragment> fragments = gi::VoxelProbe(*voxels).readbackFragments();
  for (const Case& c : cases) {
    SCOPED_TRACE("box at x = " + std::to_string(c.x));
    // G-buffer: every pixel whose surface lies on this box.
    int pixels = 0;
    glm::vec3 worstAlbedo(0.0f), worstEmission(0.0f);
    for (size_t i = 0; i < position.size(); ++i) {
      if (position[i].w == 0.0f || std::abs(position[i].x - c.x) > 0.41f) continue;
      ++pixels;
      worstAlbedo = glm::max(worstAlbedo, glm::abs(glm::vec3(albedo[i]) - c.albedo));
      worstEmission = glm::max(worstEmission, glm::abs(glm::vec3(emissive[i]) - c.emission));
    }
    EXPECT_GT(pixels, 100);
    EXPECT_LT(glm::compMax(worstAlbedo), 2.5f / 255.0f) << "G-buffer albedo (8-bit)";
    EXPECT_LT(glm::compMax(worstEmission), 0.01f) << "G-buffer emission (half float)";
    // Voxel fragments whose cell centre lies in this box's slab of x.
    int voxelCount = 0;
    glm::vec3 worstVoxelAlbedo(0.0f), worstVoxelEmission(0.0f);
    for (const gi::VoxelFragment& f : fragments) {
      glm::vec3 centre = voxels->volume().origin + (glm::vec3(f.cell) + 0.5f) * voxels->volume().voxelSize;
      if (std::abs(centre.x - c.x) > 0.45f) continue;
      ++voxelCount;
      worstVoxelAlbedo = glm::max(worstVoxelAlbedo, glm::abs(glm::vec3(f.albedo) - c.albedo));
      worstVoxelEmission = glm::max(worstVoxelEmission, glm::abs(f.emission - c.emission) / glm::max(c.emission, glm::vec3(1.0f)));
    }
    EXPECT_GT(voxelCount, 100);
    EXPECT_LT(glm::compMax(worstVoxelAlbedo), 2.5f / 255.0f) << "voxel albedo (8-bit)";
    EXPECT_LT(glm::compMax(worstVoxelEmission), 0.01f) << "voxel emission (8-bit mantissas)";
  }
}

TEST_F(VoxelTest, SkinnedBarReVoxelizesAsItBendsAndMatchesExactOverlap) {
  // A skinned mesh made in code: each frame of its deformation re-voxelizes the bar alone, and the
  // voxels equal the exact triangle/box overlap of the deformed triangles and a from-scratch build.
  sample::buildBuiltinScene("cornell", world, assets);
  TempDir dir;
  SkinnedBar bar = addSkinnedBar(world, assets, dir, {0.4f, 0.0f, 0.0f});
  ASSERT_EQ(bar.error, "");
  voxels = std::make_unique<gi::VoxelScene>(context(), gi::VoxelSettings{.resolution = 64});
  renderer = std::make_unique<render::Renderer>(context());
  renderer->addFeature(voxels.get());
  renderer->resize(32, 32);
  addAnimationAndSkinning(scheduler, assets);
  scheduler.add(ecs::Phase::PostUpdate, std::make_unique<gi::VoxelSyncSystem>(*voxels, assets));
  step();  // t = 0: everything voxelized once
  for (int f = 1; f <= 5; ++f) {  // 0.2 s a step: the bar bends from 0 to 90 degrees
    step();
    EXPECT_EQ(voxels->stats().entitiesVoxelized, 1u) << "only the bar, frame " << f;
    gi::DenseVoxelGrid gpu = gi::VoxelProbe(*voxels).readbackFragmentGrid();
    GridDiff d = diff(gpu, gi::voxelizeBruteForce(voxelSpaceTriangles(snapshot, voxels->volume()), 64));
    EXPECT_EQ(d.missing, 0u) << "frame " << f;
    EXPECT_LE(d.extra, d.reference / 100) << "frame " << f;
    GridDiff l = diff(leaves(), scratchLeaves());
    EXPECT_EQ(l.missing + l.extra, 0u) << "frame " << f << ": the SVO equals a rebuild";
  }
}

// In a scene wider than the reach (the 400 m street) the volume covers the camera's surroundings: voxels
// of a street's detail instead of 3.4 m ones, nothing reserved for the geometry outside, and a camera
// that moves into another cell of the volume's grid moves the volume, voxelized afresh there as a new
// voxel scene at that place would be, the same voxels where the two overlap; back in the first cell, the
// first voxels again.
TEST_F(VoxelTest, TheVolumeFollowsTheCameraInAWideWorld) {
  run("street", 128, 1);
  const gi::VoxelStats& st = voxels->stats();
  ASSERT_TRUE(st.windowed);
  const gi::VoxelVolume first = voxels->volume();
  const float reach = gi::VoxelSettings{}.reach, side = first.voxelSize * float(first.resolution);
  auto holdsCamera = [&](const gi::VoxelVolume& v) {
    const glm::vec3 p = v.toVoxel(snapshot.camera.position);
    return glm::all(glm::greaterThan(p, glm::vec3(0.0f))) && glm::all(glm::lessThan(p, glm::vec3(float(v.resolution))));
  };
  EXPECT_TRUE(holdsCamera(first));
  EXPECT_LT(side, 2.0f * reach) << "the cube around the focus sphere of the reach";
  EXPECT_LT(first.voxelSize, 1.0f);
  const gi::DenseVoxelGrid firstLeaves = leaves();
  GridDiff d = diff(firstLeaves, scratchLeaves());
  dyngi::test::report("street, volume around the camera: %.1f m a side, %.2f m voxels, %zu leaves, %llu fragments in %llu slots\n", side,
                      first.voxelSize, d.reference, (unsigned long long)st.fragments, (unsigned long long)st.fragmentCapacity);
  EXPECT_GT(d.reference, 1000u);
  EXPECT_EQ(d.missing + d.extra, 0u) << "as a voxel scene over that volume builds it";
  EXPECT_LT(st.fragmentCapacity, 4 * st.fragments) << "the geometry outside the volume reserves nothing";

  ecs::Entity camera{};
  world.each<scene::ActiveCamera>([&](ecs::Entity e, const scene::ActiveCamera&) { camera = e; });
  const float cell = gi::VoxelScene::kWindowStep * reach;  // the cells the volume moves by (8 m)
  world.write<scene::Transform>(camera).translation.x += 5.0f * cell;
  step();
  const gi::VoxelVolume moved = voxels->volume();
  EXPECT_EQ(st.volumeMoves, 1u);
  const float shift = (moved.origin.x - first.origin.x) / first.voxelSize;
  EXPECT_NEAR(shift * first.voxelSize, 5.0f * cell, first.voxelSize);
  EXPECT_NEAR(shift, std::round(shift), 1e-3f) << "both volumes on one grid of voxels";
  EXPECT_EQ(moved.origin.y, first.origin.y);
  EXPECT_TRUE(holdsCamera(moved));
  const gi::DenseVoxelGrid movedLeaves = leaves();
  d = diff(movedLeaves, scratchLeaves());
  EXPECT_EQ(d.missing + d.extra, 0u) << "the moved volume, voxelized afresh";
  // Where the two volumes overlap (a voxel of their sides left out: clipping), the same voxels.
  const int k = int(std::lround(shift)), res = int(first.resolution);
  size_t overlap = 0, differ = 0;
  for (int z = 1; z < res - 1; ++z)
    for (int y = 1; y < res - 1; ++y)
      for (int x = 1; x + k < res - 1; ++x) {
        overlap += movedLeaves.get(x, y, z);
        differ += movedLeaves.get(x, y, z) != firstLeaves.get(x + k, y, z);
      }
  dyngi::test::report("moved %d voxels along the street: %zu leaves where the volumes overlap, %zu differ\n", k, overlap, differ);
  EXPECT_GT(overlap, 1000u);
  EXPECT_EQ(differ, 0u) << "a move changes nothing where the volumes overlap";
  EXPECT_EQ(st.overflowedEntities, 0u);

  world.write<scene::Transform>(camera).translation.x -= 5.0f * cell;
  step();
  EXPECT_EQ(st.volumeMoves, 2u);
  EXPECT_EQ(voxels->volume().origin, first.origin);
  d = diff(leaves(), firstLeaves);
  EXPECT_EQ(d.missing + d.extra, 0u) << "back in the first cell: the first voxels";
}

