// Randomized test of the ECS against a trivially correct model: std::map keyed by handle.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>

#include "dyngi/engine/ecs/world.h"

using namespace dyngi::ecs;

namespace {
struct A { int v = 0; };
struct B { int v = 0; };

struct Model {
  std::set<Entity> alive;
  std::map<Entity, int> a, b;
  std::map<Entity, Tick> aChanged;  // last write tick of A
};
}  // namespace

TEST(EcsModel, RandomOperationsMatchMapModel) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    std::mt19937 rng(seed);
    World w;
    Model m;
    std::vector<Entity> everSeen;
    Tick queryFrom = w.tick();
    for (int op = 0; op < 8000; ++op) {
      if (op % 50 == 0) w.advanceTick();
      auto pick = [&]() -> Entity {
        if (everSeen.empty()) return kNullEntity;
        return everSeen[rng() % everSeen.size()];  // may be stale on purpose
      };
      int kind = int(rng() % 8);
      Entity e = pick();
      bool isAlive = m.alive.count(e) > 0;
      switch (kind) {
        case 0: {
          Entity n = w.create();
          ASSERT_FALSE(m.alive.count(n));
          m.alive.insert(n);
          everSeen.push_back(n);
          break;
        }
        case 1:
          if (isAlive) {
            w.destroy(e);
            m.alive.erase(e);
            m.a.erase(e);
            m.b.erase(e);
            m.aChanged.erase(e);
          } else if (!e.isNull()) {
            EXPECT_THROW(w.destroy(e), std::out_of_range);
          }
          break;
        case 2:
          if (isAlive) {
            int v = int(rng() % 1000);
            w.add(e, A{v});
            m.a[e] = v;
            m.aChanged[e] = w.tick();
          }
          break;
        case 3:
          if (isAlive) {
            int v = int(rng() % 1000);
            w.add(e, B{v});
            m.b[e] = v;
          }
          break;
        case 4:
          if (isAlive) {
            EXPECT_EQ(w.remove<A>(e), m.a.erase(e) > 0);
            m.aChanged.erase(e);
          }
          break;
        case 5:
          if (isAlive && m.a.count(e)) {
            int v = int(rng() % 1000);
            w.write<A>(e).v = v;
            m.a[e] = v;
            m.aChanged[e] = w.tick();
          }
          break;
        case 6: {  // compare a random handle fully
          EXPECT_EQ(w.alive(e), isAlive);
          const A* ca = w.tryGet<A>(e);
          EXPECT_EQ(ca != nullptr, m.a.count(e) > 0);
          if (ca && m.a.count(e)) {
            EXPECT_EQ(ca->v, m.a[e]);
          }
          const B* cb = w.tryGet<B>(e);
          EXPECT_EQ(cb != nullptr, m.b.count(e) > 0);
          if (cb && m.b.count(e)) {
            EXPECT_EQ(cb->v, m.b[e]);
          }
          break;
        }
        case 7: {  // change query against the model
          std::set<Entity> expect;
          for (auto& [ent, t] : m.aChanged)
            if (t > queryFrom) expect.insert(ent);
          auto got = w.changedSince<A>(queryFrom);
          std::set<Entity> gotSet(got.begin(), got.end());
          EXPECT_EQ(gotSet.size(), got.size()) << "no duplicates";
          EXPECT_EQ(gotSet, expect);
          if (rng() % 4 == 0) queryFrom = w.tick();
          break;
        }
      }
    }
    // Final full comparison, including a view over both components.
    std::set<Entity> both;
    for (auto& [e, _] : m.a)
      if (m.b.count(e)) both.insert(e);
    std::set<Entity> viewed;
    w.each<A, B>([&](Entity e, const A& a, const B& b) {
      viewed.insert(e);
      EXPECT_EQ(a.v, m.a[e]);
      EXPECT_EQ(b.v, m.b[e]);
    });
    EXPECT_EQ(viewed, both);
    EXPECT_EQ(w.aliveCount(), m.alive.size());
    EXPECT_EQ(w.count<A>(), m.a.size());
  }
}
