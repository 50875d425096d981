#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>
#include <unordered_map>

#include "dyngi/engine/ecs/entity_map.h"
#include "dyngi/engine/ecs/world.h"

using namespace dyngi::ecs;

namespace {
struct Position { float x = 0; };
struct Velocity { float v = 0; };
struct Tag {};
}  // namespace

TEST(Entity, StaleHandleIsDetectedAndNeverAliased) {
  World w;
  Entity a = w.create();
  w.add(a, Position{1});
  w.destroy(a);
  Entity b = w.create();  // reuses a's slot
  EXPECT_EQ(a.index, b.index);
  EXPECT_NE(a.generation, b.generation);
  EXPECT_FALSE(w.alive(a));
  EXPECT_TRUE(w.alive(b));
  EXPECT_EQ(w.tryGet<Position>(a), nullptr);
  w.add(b, Position{2});
  EXPECT_EQ(w.tryGet<Position>(a), nullptr) << "stale handle must not see the new entity's component";
  EXPECT_THROW(w.write<Position>(a), std::out_of_range);
  EXPECT_THROW(w.add(a, Velocity{}), std::out_of_range);
  EXPECT_THROW(w.destroy(a), std::out_of_range);
  EXPECT_THROW((void)w.get<Position>(kNullEntity), std::out_of_range);
}

TEST(Entity, DestroyRemovesAllComponents) {
  World w;
  Entity e = w.create();
  w.add(e, Position{1});
  w.add(e, Velocity{2});
  w.add(e, Tag{});
  w.destroy(e);
  EXPECT_EQ(w.count<Position>(), 0u);
  EXPECT_EQ(w.count<Velocity>(), 0u);
  EXPECT_EQ(w.count<Tag>(), 0u);
  EXPECT_EQ(w.aliveCount(), 0u);
}

TEST(View, VisitsExactlyEntitiesWithAllComponents) {
  World w;
  std::set<uint32_t> both;
  for (int i = 0; i < 100; ++i) {
    Entity e = w.create();
    if (i % 2 == 0) w.add(e, Position{float(i)});
    if (i % 3 == 0) w.add(e, Velocity{float(i)});
    if (i % 6 == 0) both.insert(e.index);
  }
  std::set<uint32_t> seen;
  w.each<Position, Velocity>([&](Entity e, const Position& p, const Velocity& v) {
    EXPECT_EQ(p.x, v.v);
    seen.insert(e.index);
  });
  EXPECT_EQ(seen, both);
  int none = 0;
  w.each<Position, Tag>([&](Entity, const Position&, const Tag&) { ++none; });
  EXPECT_EQ(none, 0);
}

TEST(View, StructuralChangeDuringIterationThrowsAndCommandsDefer) {
  World w;
  std::vector<Entity> es;
  for (int i = 0; i < 10; ++i) {
    es.push_back(w.create());
    w.add(es.back(), Position{float(i)});
  }
  EXPECT_THROW(w.each<Position>([&](Entity e, const Position&) { w.destroy(e); }), std::logic_error);
  EXPECT_FALSE(w.iterating()) << "the guard must unwind on exceptions";
  int visited = 0;
  w.each<Position>([&](Entity e, const Position& p) {
    ++visited;
    if (int(p.x) % 2 == 0) w.commands().destroy(e);
    else w.commands().add(e, Velocity{p.x});
    Entity spawned = w.create();  // creation is allowed during iteration
    w.commands().add(spawned, Tag{});
  });
  EXPECT_EQ(visited, 10);
  EXPECT_EQ(w.count<Position>(), 10u) << "nothing applied before flush";
  w.flushCommands();
  EXPECT_EQ(w.count<Position>(), 5u);
  EXPECT_EQ(w.count<Velocity>(), 5u);
  EXPECT_EQ(w.count<Tag>(), 10u);
}

TEST(ChangeDetection, ReportsWritesAfterTickOnceEach) {
  World w;
  std::vector<Entity> es;
  for (int i = 0; i < 50; ++i) {
    es.push_back(w.create());
    w.add(es.back(), Position{0});
  }
  Tick t0 = w.tick();
  w.advanceTick();
  w.write<Position>(es[3]).x = 1;
  w.write<Position>(es[3]).x = 2;  // same tick: reported once
  w.set(es[7], Position{5});
  auto changed = w.changedSince<Position>(t0);
  ASSERT_EQ(changed.size(), 2u);
  EXPECT_EQ(changed[0], es[3]);
  EXPECT_EQ(changed[1], es[7]);
  // Reading is not writing.
  Tick t1 = w.tick();
  w.advanceTick();
  (void)w.get<Position>(es[9]);
  w.each<Position>([](Entity, const Position&) {});
  EXPECT_TRUE(w.changedSince<Position>(t1).empty());
  // A rewrite in a later tick moves the entity to the later tick only.
  w.write<Position>(es[3]).x = 3;
  auto later = w.changedSince<Position>(t1);
  ASSERT_EQ(later.size(), 1u);
  EXPECT_EQ(later[0], es[3]);
}

TEST(ChangeDetection, RemovedAndDestroyedAreReportedAndNotAsChanged) {
  World w;
  Entity a = w.create(), b = w.create();
  w.add(a, Position{});
  w.add(b, Position{});
  Tick t = w.tick();
  w.advanceTick();
  w.write<Position>(a);
  w.destroy(a);
  w.remove<Position>(b);
  EXPECT_TRUE(w.changedSince<Position>(t).empty());
  auto removed = w.removedSince<Position>(t);
  EXPECT_EQ(removed.size(), 2u);
}

TEST(ChangeDetection, CostIsProportionalToChangesNotWorld) {
  World w;
  std::vector<Entity> es;
  for (int i = 0; i < 20000; ++i) {
    es.push_back(w.create());
    w.add(es.back(), Position{});
  }
  for (int frame = 0; frame < 10; ++frame) {
    Tick before = w.tick();
    w.advanceTick();
    for (int k = 0; k < 5; ++k) w.write<Position>(es[size_t(frame * 100 + k)]);
    w.trimChangeLogs(before);  // what the scheduler does: keep only what readers still need
    EXPECT_EQ(w.changedSince<Position>(before).size(), 5u);
    EXPECT_LE(w.poolIfAny<Position>()->changeLogSize(), 5u) << "the log holds only records newer than the trim point";
  }
}

TEST(ChangeDetection, ABulkLoadKeepsItsLogShortAndEveryChangeSeen) {
  // 100,000 components added over three ticks, some written again: the log stays under a quarter of the
  // pool, and readers of every age see exactly the entities whose tick is newer than theirs.
  World w;
  std::vector<Entity> es;
  std::vector<Tick> readers = {w.tick()};
  for (int phase = 0; phase < 3; ++phase) {
    for (int i = 0; i < 40000 - 10000 * phase; ++i) {
      es.push_back(w.create());
      w.add(es.back(), Position{});
    }
    for (size_t k = 0; k < es.size(); k += 7) w.write<Position>(es[k]);
    EXPECT_LE(w.poolIfAny<Position>()->changeLogSize(), es.size() / 4 + 1);
    readers.push_back(w.tick());
    w.advanceTick();
  }
  for (size_t k = 3; k < es.size(); k += 11) w.write<Position>(es[k]);
  for (Tick since : readers) {
    std::set<uint32_t> expected, seen;
    for (Entity e : es)
      if (w.poolIfAny<Position>()->changedTick(e) > since) expected.insert(e.index);
    for (Entity e : w.changedSince<Position>(since)) EXPECT_TRUE(seen.insert(e.index).second) << "reported twice";
    EXPECT_EQ(seen, expected) << "since tick " << since;
    EXPECT_FALSE(expected.empty());
  }
}

TEST(ChangeDetection, QueryOlderThanTrimFallsBackToFullScan) {
  World w;
  Entity a = w.create(), b = w.create();
  w.add(a, Position{});
  w.add(b, Position{});
  w.advanceTick();
  w.write<Position>(a);
  Tick mid = w.tick();
  w.advanceTick();
  w.write<Position>(b);
  w.trimChangeLogs(mid);
  EXPECT_EQ(w.changedSince<Position>(0).size(), 2u);  // both, via scan
  EXPECT_EQ(w.changedSince<Position>(mid).size(), 1u);
}

// A bulk load that reserves first: the pools take it without growing (no slack, no copies), and what
// they hold is what was added.
TEST(World, AReservedBulkLoadFillsItsArraysWithoutGrowingThem) {
  World w;
  for (int i = 0; i < 10; ++i) w.add(w.create(), Position{float(i)});
  constexpr size_t kMore = 5000;
  w.reserveEntities(kMore);
  w.reserve<Position>(kMore);
  const Position* before = &w.get<Position>(Entity{0, 0});
  std::vector<Entity> added;
  for (size_t i = 0; i < kMore; ++i) {
    const Entity e = w.create();
    w.add(e, Position{float(i)});
    added.push_back(e);
  }
  EXPECT_EQ(&w.get<Position>(Entity{0, 0}), before) << "the dense array was not reallocated";
  for (size_t i = 0; i < kMore; ++i) ASSERT_EQ(w.get<Position>(added[i]).x, float(i));
  EXPECT_EQ(w.aliveCount(), kMore + 10);
  // Not logged, yet seen: a reader from before the load gets all 5,010 by a scan; writes in later
  // ticks are logged again, and a reader from the load's tick sees them alone.
  EXPECT_EQ(w.poolIfAny<Position>()->changeLogSize(), 0u);
  const Tick load = w.tick();
  EXPECT_EQ(w.changedSince<Position>(load - 1).size(), kMore + 10);
  w.advanceTick();
  w.write<Position>(added[7]);
  EXPECT_EQ(w.poolIfAny<Position>()->changeLogSize(), 1u);
  const std::vector<Entity> later = w.changedSince<Position>(load);
  ASSERT_EQ(later.size(), 1u);
  EXPECT_EQ(later[0], added[7]);
}

// EntityMap and EntitySet against std::unordered_map under random inserts, lookups with stale
// generations, erases by key and erases while iterating (the swap-remove the containers use).
TEST(EntityMap, MatchesAStandardMapUnderRandomEditsAndStaleHandles) {
  std::mt19937 rng(7);
  EntityMap<uint64_t> map;
  EntitySet set;
  std::unordered_map<Entity, uint64_t> truth;
  auto randomEntity = [&] { return Entity{uint32_t(rng() % 300), uint32_t(rng() % 3)}; };
  auto same = [&] {
    ASSERT_EQ(map.size(), truth.size());
    ASSERT_EQ(set.size(), truth.size());
    std::map<std::pair<uint32_t, uint32_t>, uint64_t> seen;
    for (const auto& [e, v] : map) seen[{e.index, e.generation}] = v;
    std::set<std::pair<uint32_t, uint32_t>> inSet;
    for (Entity e : set) inSet.insert({e.index, e.generation});
    ASSERT_EQ(seen.size(), truth.size());  // no entry twice
    ASSERT_EQ(inSet.size(), truth.size());
    for (const auto& [e, v] : truth) {
      EXPECT_EQ((seen[{e.index, e.generation}]), v);
      EXPECT_TRUE(inSet.count({e.index, e.generation}));
    }
  };
  for (int step = 0; step < 20000; ++step) {
    const Entity e = randomEntity();
    switch (rng() % 6) {
      case 0:
      case 1: {
        const uint64_t v = rng();
        const bool added = map.try_emplace(e, v).second;
        EXPECT_EQ(added, truth.emplace(e, v).second);
        EXPECT_EQ(set.insert(e), added);
        break;
      }
      case 2:
        map[e] += 3, truth[e] += 3, set.insert(e);
        break;
      case 3:
        EXPECT_EQ(map.erase(e), truth.erase(e));
        set.erase(e);
        break;
      case 4:
        EXPECT_EQ(map.count(e), truth.count(e));
        EXPECT_EQ(set.count(e), truth.count(e));
        if (truth.count(e)) EXPECT_EQ(map.at(e), truth.at(e));
        else EXPECT_THROW(map.at(e), std::out_of_range);
        break;
      case 5:
        if (step % 50 == 0) {  // erase the odd values while walking, as an unordered_map loop would
          for (auto it = map.begin(); it != map.end();) it = it->second % 2 ? map.erase(it) : std::next(it);
          for (auto it = truth.begin(); it != truth.end();) {
            if (it->second % 2) set.erase(it->first), it = truth.erase(it);
            else ++it;
          }
        }
        break;
    }
    if (step % 1000 == 0) same();
  }
  same();
  map.clear(), set.clear(), truth.clear();
  same();
  EXPECT_EQ(map.count(Entity{5, 0}), 0u);
  EXPECT_EQ(set.count(kNullEntity), 0u) << "looking up the null entity is fine";
  EXPECT_THROW(map[kNullEntity], std::invalid_argument) << "keying by it is refused, not a 2^32 slot array";
  EXPECT_THROW(set.insert(kNullEntity), std::invalid_argument);
}
