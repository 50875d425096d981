// The voxel scene's fragment-range allocator on the CPU: ranges never overlap, counters are unique and
// reused, a range is kept while it holds what its entity writes, compaction keeps every fragment, the
// estimate bounds what a triangle writes.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>

#include "dyngi/gi/fragment_ranges.h"
#include "dyngi/gi/voxel.h"

using dyngi::ecs::Entity;
using namespace dyngi::gi;

namespace {
Entity entity(uint32_t i) { return Entity{i, 0}; }

// Invariants any state must keep: ranges inside [0, highWater), pairwise disjoint, counters unique.
void expectConsistent(const FragmentRanges& ranges) {
  std::vector<std::pair<uint64_t, uint64_t>> spans;
  std::map<uint32_t, int> counters;
  for (const auto& [e, r] : ranges.all()) {
    EXPECT_LE(r.first + r.capacity, ranges.highWater());
    spans.push_back({r.first, r.first + r.capacity});
    EXPECT_EQ(++counters[r.counter], 1) << "counter " << r.counter << " shared";
    EXPECT_LT(r.counter, ranges.counterCount());
  }
  std::sort(spans.begin(), spans.end());
  for (size_t i = 1; i < spans.size(); ++i) EXPECT_LE(spans[i - 1].second, spans[i].first) << "ranges overlap";
}

// Plans and commits one frame's voxelizations, then "reads back" counts as the voxelizer would write.
void voxelize(FragmentRanges& ranges, const std::map<Entity, uint64_t>& estimates, const std::map<Entity, uint32_t>& counts, uint64_t frame,
              std::vector<FragmentRange>* emptied = nullptr) {
  uint64_t highWater = ranges.highWater();
  std::vector<FragmentRange> toEmpty;
  std::vector<std::pair<Entity, FragmentRange>> planned;
  for (const auto& [e, estimate] : estimates) planned.push_back({e, ranges.plan(e, estimate, highWater, toEmpty)});
  for (const auto& [e, r] : planned) ranges.commit(e, r, frame);
  ranges.setHighWater(highWater);
  for (const auto& [e, n] : counts) ranges.at(e).lastCount = n;
  if (emptied) *emptied = toEmpty;
}
}  // namespace

TEST(FragmentRanges, ARangeIsKeptWhileItHoldsWhatItsEntityWritesAndMovedWhenItOverflows) {
  FragmentRanges ranges;
  voxelize(ranges, {{entity(1), 1000}, {entity(2), 500}}, {{entity(1), 300}, {entity(2), 100}}, 1);
  expectConsistent(ranges);
  EXPECT_EQ(ranges.at(entity(1)).capacity, 1000u) << "first time: the estimate";
  const FragmentRange before = ranges.at(entity(1));
  // Moved: same estimate, known count 300 fits with headroom: kept in place.
  std::vector<FragmentRange> emptied;
  voxelize(ranges, {{entity(1), 1000}}, {{entity(1), 320}}, 2, &emptied);
  EXPECT_EQ(ranges.at(entity(1)).first, before.first);
  EXPECT_TRUE(emptied.empty());
  // It wrote more than its range holds: a fresh, larger range at the end; the old one is emptied.
  voxelize(ranges, {{entity(1), 1000}}, {{entity(1), 5000}}, 3);
  voxelize(ranges, {{entity(1), 1000}}, {}, 4, &emptied);
  EXPECT_GE(ranges.at(entity(1)).capacity, 5000u * 5 / 4);
  ASSERT_EQ(emptied.size(), 1u);
  EXPECT_EQ(emptied[0].first, before.first);
  EXPECT_EQ(ranges.at(entity(1)).counter, before.counter) << "the entity keeps its counter";
  expectConsistent(ranges);
}

TEST(FragmentRanges, CountersOfRemovedEntitiesAreReused) {
  FragmentRanges ranges;
  voxelize(ranges, {{entity(1), 100}, {entity(2), 100}, {entity(3), 100}}, {}, 1);
  const uint32_t freed = ranges.at(entity(2)).counter;
  ASSERT_TRUE(ranges.remove(entity(2)));
  EXPECT_FALSE(ranges.remove(entity(2))) << "once";
  voxelize(ranges, {{entity(4), 100}}, {}, 2);
  EXPECT_EQ(ranges.at(entity(4)).counter, freed);
  EXPECT_EQ(ranges.counterCount(), 3u);
  expectConsistent(ranges);
}

TEST(FragmentRanges, CompactionKeepsEveryFragmentAndStaticEntitiesShrinkToTheirCount) {
  FragmentRanges ranges;
  std::map<Entity, uint64_t> estimates;
  std::map<Entity, uint32_t> counts;
  for (uint32_t i = 1; i <= 40; ++i) estimates[entity(i)] = 4000, counts[entity(i)] = 500 + i;
  voxelize(ranges, estimates, counts, 1);
  // Entity 7 moves (voxelized again): it keeps slack.
  voxelize(ranges, {{entity(7), 4000}}, {{entity(7), 600}}, 2);
  ASSERT_TRUE(ranges.wantsCompaction()) << ranges.highWater() << " slots for ~21k fragments";
  std::map<Entity, FragmentRange> before(ranges.all().begin(), ranges.all().end());
  const std::vector<SlotCopy> copies = ranges.compact();
  expectConsistent(ranges);
  EXPECT_FALSE(ranges.wantsCompaction());
  // Every entity's written fragments are copied from where they were to the start of its new range.
  for (const auto& [e, r] : ranges.all()) {
    const FragmentRange& old = before.at(e);
    auto c = std::find_if(copies.begin(), copies.end(), [&](const SlotCopy& s) { return s.from == old.first; });
    ASSERT_NE(c, copies.end());
    EXPECT_EQ(c->to, r.first);
    EXPECT_EQ(c->count, std::min<uint64_t>(old.lastCount, old.capacity));
    if (e == entity(7)) EXPECT_EQ(r.capacity, FragmentRanges::movingCapacity(old));
    else EXPECT_EQ(r.capacity, old.lastCount);
  }
  EXPECT_EQ(ranges.storedFragments(), std::accumulate(counts.begin(), counts.end(), uint64_t(0),
                                                      [](uint64_t s, const auto& kv) { return s + kv.second; }) -
                                          counts[entity(7)] + 600);
}

TEST(FragmentRanges, RandomOperationsKeepTheRangesDisjoint) {
  FragmentRanges ranges;
  std::mt19937 rng(5);
  for (uint64_t frame = 1; frame < 300; ++frame) {
    std::map<Entity, uint64_t> estimates;
    std::map<Entity, uint32_t> counts;
    for (int k = 0; k < 4; ++k) {
      Entity e = entity(uint32_t(1 + rng() % 30));
      estimates[e] = 64 + rng() % 5000;
      counts[e] = uint32_t(rng() % 6000);  // sometimes more than the range holds
    }
    voxelize(ranges, estimates, counts, frame);
    if (rng() % 5 == 0) ranges.remove(entity(uint32_t(1 + rng() % 30)));
    if (ranges.wantsCompaction()) ranges.compact();
    expectConsistent(ranges);
  }
}

// A triangle writes one fragment into each voxel it overlaps (contact included, as the voxelizer's
// epsilon counts it): the estimate must bound that count for any triangle, and for one under a voxel
// it must stay near it (its bounding box's voxels, no per-range slack), or many small instances each
// reserve far more than they write.
TEST(FragmentRanges, TheEstimateBoundsEachTrianglesVoxelsAndStaysNearItForSmallOnes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> where(4.0f, 12.0f), unit(-1.0f, 1.0f);
  for (float size : {0.05f, 0.3f, 0.9f, 2.5f, 9.0f}) {
    for (int trial = 0; trial < 40; ++trial) {
      const glm::vec3 a(where(rng), where(rng), where(rng));
      dyngi::scene::MeshData mesh;
      mesh.positions = {a, a + size * glm::vec3(unit(rng), unit(rng), unit(rng)), a + size * glm::vec3(unit(rng), unit(rng), unit(rng))};
      mesh.indices = {0, 1, 2};
      if (trial % 8 == 0) mesh.positions[0].y = mesh.positions[1].y = mesh.positions[2].y = 7.0f;  // in a voxel face: touches two layers
      const glm::dvec3 p0(mesh.positions[0]), p1(mesh.positions[1]), p2(mesh.positions[2]);
      const glm::ivec3 lo = glm::ivec3(glm::floor(glm::min(p0, glm::min(p1, p2)))) - 1, hi = glm::ivec3(glm::floor(glm::max(p0, glm::max(p1, p2)))) + 1;
      uint64_t overlapped = 0;
      for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
          for (int x = lo.x; x <= hi.x; ++x)
            overlapped += triangleOverlapsBox(glm::dvec3(x, y, z) + 0.5, glm::dvec3(0.5 + 1e-4), p0, p1, p2) ? 1 : 0;
      const FragmentRanges::Estimate both = FragmentRanges::estimate(mesh, glm::mat4(1.0f));
      const uint64_t estimate = both.fragments;
      EXPECT_GE(estimate, overlapped) << "size " << size << ", trial " << trial;
      const glm::dvec3 extent = glm::max(p0, glm::max(p1, p2)) - glm::min(p0, glm::min(p1, p2));
      EXPECT_NEAR(both.widestTriangle, std::max({extent.x, extent.y, extent.z}), 1e-5) << "the widest side decides the voxelizer";
      if (size <= 0.3f) {  // the vertices within 0.6 voxels of each other on every axis
        EXPECT_LE(estimate, 8u) << "size " << size << ": a triangle under a voxel spans 8 voxels at most";
      }
    }
  }
}

// A mesh whose triangle has a non-finite vertex never counts as small (the raster path clips it).
TEST(FragmentRanges, ANonFiniteTriangleIsNeverTheWidestSmallOne) {
  dyngi::scene::MeshData mesh;
  mesh.positions = {{1, 1, 1}, {1.5f, 1, 1}, {1, std::nanf(""), 1}, {1, 1.2f, 1}};
  mesh.indices = {0, 1, 3, 0, 1, 2};
  EXPECT_TRUE(std::isinf(FragmentRanges::estimate(mesh, glm::mat4(1.0f)).widestTriangle));
  mesh.indices = {0, 1, 3};
  EXPECT_FLOAT_EQ(FragmentRanges::estimate(mesh, glm::mat4(1.0f)).widestTriangle, 0.5f);
}
