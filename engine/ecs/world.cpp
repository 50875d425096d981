#include "dyngi/engine/ecs/world.h"

namespace dyngi::ecs {

void Commands::destroy(Entity e) {
  ops_.push_back([e](World& w) {
    if (w.alive(e)) w.destroy(e);
  });
}

Entity World::create() {
  // Allocating a slot does not disturb any pool, so creation is allowed during iteration.
  uint32_t index;
  if (!freeSlots_.empty()) {
    index = freeSlots_.back();
    freeSlots_.pop_back();
  } else {
    index = uint32_t(slots_.size());
    slots_.push_back({});
  }
  slots_[index].alive = true;
  ++aliveCount_;
  return Entity{index, slots_[index].generation};
}

void World::destroy(Entity e) {
  requireStructuralChangeAllowed();
  requireAlive(e);
  for (auto& [_, p] : pools_) p->removeIfPresent(e, tick_);
  slots_[e.index].alive = false;
  ++slots_[e.index].generation;
  freeSlots_.push_back(e.index);
  --aliveCount_;
}

void World::flushCommands() {
  // Commands may queue further commands; run until the queue is empty.
  while (!commands_.ops_.empty()) {
    auto ops = std::move(commands_.ops_);
    commands_.ops_.clear();
    for (auto& op : ops) op(*this);
  }
}

}  // namespace dyngi::ecs
