#include <gtest/gtest.h>

#include "dyngi/engine/ecs/scheduler.h"

using namespace dyngi::ecs;

namespace {
struct Value { int v = 0; };
}

TEST(Scheduler, PhasesRunInOrderAndSystemsSeeOnlyNewChanges) {
  World w;
  Entity e = w.create();
  w.add(e, Value{});
  Scheduler s;
  std::vector<std::string> order;
  std::vector<size_t> seenByReader;
  // Registered out of phase order on purpose.
  s.add(Phase::PostUpdate, "reader", [&](World& world, const SystemContext& ctx) {
    order.push_back("reader");
    seenByReader.push_back(world.changedSince<Value>(ctx.lastRun).size());
  });
  s.add(Phase::Update, "writer", [&](World& world, const SystemContext& ctx) {
    order.push_back("writer");
    if (ctx.time.frame % 2 == 0) world.write<Value>(e).v++;
  });
  for (uint64_t f = 0; f < 4; ++f) s.runFrame(w, FrameTime{1.0 / 60, double(f) / 60, f});
  EXPECT_EQ(order, (std::vector<std::string>{"writer", "reader", "writer", "reader", "writer", "reader", "writer", "reader"}));
  // Frame 0 sees the add and the write, 1 nothing, 2 the write, 3 nothing.
  EXPECT_EQ(seenByReader, (std::vector<size_t>{1, 0, 1, 0}));
  ASSERT_EQ(s.lastTimings().size(), 2u);
  EXPECT_EQ(s.lastTimings()[0].name, "writer");
}

TEST(Scheduler, CommandsAreFlushedAfterEachSystem) {
  World w;
  Scheduler s;
  size_t countSeen = 99;
  s.add(Phase::Update, "spawner", [&](World& world, const SystemContext&) {
    world.each<Value>([&](Entity, const Value&) {});
    Entity n = world.create();
    world.commands().add(n, Value{7});
  });
  s.add(Phase::Update, "counter", [&](World& world, const SystemContext&) { countSeen = world.count<Value>(); });
  s.runFrame(w, {});
  EXPECT_EQ(countSeen, 1u);
}
