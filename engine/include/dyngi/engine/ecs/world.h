#pragma once
// The World: entity slots, one sparse-set pool per component type, change ticks and deferred commands.
//
// Rules that keep systems honest:
// - Reads (`get`, `tryGet`, views) never count as changes; every write goes through `write`/`set`/`add`
//   and stamps the component with the current tick.
// - Structural changes (add/remove component, destroy entity) are refused while a view is iterating;
//   queue them on `commands()` instead. The scheduler flushes the queue after each system.
#include <functional>
#include <memory>
#include <stdexcept>
#include <tuple>
#include <typeindex>
#include <unordered_map>
#include <vector>

#include "dyngi/engine/ecs/component_pool.h"
#include "dyngi/engine/ecs/entity.h"

namespace dyngi::ecs {

class World;

// Structural changes recorded now, applied at the next flush.
class Commands {
 public:
  template <typename T>
  void add(Entity e, T value);
  void destroy(Entity e);
  template <typename T>
  void remove(Entity e);
  void run(std::function<void(World&)> fn) { ops_.push_back(std::move(fn)); }
  bool empty() const { return ops_.empty(); }

 private:
  friend class World;
  std::vector<std::function<void(World&)>> ops_;
};

class World {
 public:
  World() = default;
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // --- entities -------------------------------------------------------------------------------
  Entity create();
  void destroy(Entity e);
  bool alive(Entity e) const {
    return e.index < slots_.size() && slots_[e.index].alive && slots_[e.index].generation == e.generation;
  }
  size_t aliveCount() const { return aliveCount_; }
  // A bulk load that knows its size (the glTF importer) reserves before it creates: `more` entities,
  // then `more` components of each type it adds; the arrays then hold no growth slack (up to half of
  // them) and are not copied while they grow.
  void reserveEntities(size_t more) { slots_.reserve(slots_.size() + more); }
  template <typename T>
  void reserve(size_t more) {
    pool<T>().reserve(more, slots_.capacity(), tick_);
  }

  // --- components -----------------------------------------------------------------------------
  template <typename T>
  T& add(Entity e, T value = T{}) {
    requireStructuralChangeAllowed();
    requireAlive(e);
    return pool<T>().emplace(e, std::move(value), tick_);
  }
  template <typename T>
  bool remove(Entity e) {
    requireStructuralChangeAllowed();
    auto* p = const_cast<ComponentPool<T>*>(findPool<T>());  // our own pool; const only for lookup
    return p && p->removeIfPresent(e, tick_);
  }
  template <typename T>
  bool has(Entity e) const {
    auto* p = findPool<T>();
    return p && p->contains(e);
  }
  template <typename T>
  const T* tryGet(Entity e) const {
    auto* p = findPool<T>();
    return p ? p->tryGet(e) : nullptr;
  }
  template <typename T>
  const T& get(Entity e) const {
    const T* c = tryGet<T>(e);
    if (!c) throw std::out_of_range(alive(e) ? "entity lacks the requested component" : "stale or null entity handle");
    return *c;
  }
  // Mutable access; stamps the component as changed at the current tick.
  template <typename T>
  T& write(Entity e) {
    if (!alive(e)) throw std::out_of_range("stale or null entity handle");
    return pool<T>().write(e, tick_);
  }
  template <typename T>
  void set(Entity e, T value) {
    write<T>(e) = std::move(value);
  }

  // --- change detection ------------------------------------------------------------------------
  Tick tick() const { return tick_; }
  Tick advanceTick() { return ++tick_; }

  template <typename T, typename Fn>
  void forEachChanged(Tick since, Fn&& fn) const {
    if (auto* p = findPool<T>()) p->forEachChangedSince(since, fn);
  }
  template <typename T>
  std::vector<Entity> changedSince(Tick since) const {
    std::vector<Entity> out;
    forEachChanged<T>(since, [&](Entity e) { out.push_back(e); });
    return out;
  }
  template <typename T>
  std::vector<Entity> removedSince(Tick since) const {
    std::vector<Entity> out;
    if (auto* p = findPool<T>()) p->forEachRemovedSince(since, [&](Entity e) { out.push_back(e); });
    return out;
  }
  // Forget change records at or before `tick`; later queries older than that fall back to a scan.
  void trimChangeLogs(Tick tick) {
    for (auto& [_, p] : pools_) p->trimLogs(tick);
  }

  // --- views ---------------------------------------------------------------------------------
  // Calls fn(Entity, const A&, const B&, ...) for every entity that has all the listed components.
  // Iterates the smallest pool and probes the others.
  template <typename... Ts, typename Fn>
  void each(Fn&& fn) const {
    static_assert(sizeof...(Ts) > 0);
    if (!(findPool<Ts>() && ...)) return;
    const ComponentPoolBase* pools[] = {findPool<Ts>()...};
    const ComponentPoolBase* smallest = pools[0];
    for (auto* p : pools)
      if (p->size() < smallest->size()) smallest = p;
    IterationGuard guard(*this);
    // Copy the driving entity list: writes (not structural) may still happen inside fn.
    const std::vector<Entity>& driver = entitiesOf(smallest, findPool<Ts>()...);
    for (size_t i = 0; i < driver.size(); ++i) {
      Entity e = driver[i];
      if ((findPool<Ts>()->contains(e) && ...)) fn(e, *findPool<Ts>()->tryGet(e)...);
    }
  }
  template <typename T>
  size_t count() const {
    auto* p = findPool<T>();
    return p ? p->size() : 0;
  }

  // --- deferred structural changes -----------------------------------------------------------
  Commands& commands() { return commands_; }
  void flushCommands();
  bool iterating() const { return iterationDepth_ > 0; }

  template <typename T>
  const ComponentPool<T>* poolIfAny() const {
    return findPool<T>();
  }

 private:
  struct Slot {
    uint32_t generation = 0;
    bool alive = false;
  };
  struct IterationGuard {
    explicit IterationGuard(const World& w) : world(w) { ++world.iterationDepth_; }
    ~IterationGuard() { --world.iterationDepth_; }
    const World& world;
  };

  template <typename T>
  ComponentPool<T>& pool() {
    auto key = std::type_index(typeid(T));
    auto it = pools_.find(key);
    if (it == pools_.end()) it = pools_.emplace(key, std::make_unique<ComponentPool<T>>()).first;
    return static_cast<ComponentPool<T>&>(*it->second);
  }
  template <typename T>
  const ComponentPool<T>* findPool() const {
    auto it = pools_.find(std::type_index(typeid(T)));
    return it == pools_.end() ? nullptr : static_cast<const ComponentPool<T>*>(it->second.get());
  }
  template <typename... Pools>
  static const std::vector<Entity>& entitiesOf(const ComponentPoolBase* which, const Pools*... pools) {
    const std::vector<Entity>* result = nullptr;
    ((static_cast<const ComponentPoolBase*>(pools) == which && !result ? (result = &pools->entities(), 0) : 0), ...);
    return *result;
  }
  void requireStructuralChangeAllowed() const {
    if (iterationDepth_ > 0)
      throw std::logic_error("structural change during iteration: queue it on world.commands()");
  }
  void requireAlive(Entity e) const {
    if (!alive(e)) throw std::out_of_range("stale or null entity handle");
  }

  std::vector<Slot> slots_;
  std::vector<uint32_t> freeSlots_;
  size_t aliveCount_ = 0;
  std::unordered_map<std::type_index, std::unique_ptr<ComponentPoolBase>> pools_;
  Tick tick_ = 1;
  mutable int iterationDepth_ = 0;
  Commands commands_;
};

template <typename T>
void Commands::add(Entity e, T value) {
  ops_.push_back([e, v = std::move(value)](World& w) mutable {
    if (w.alive(e)) w.add<T>(e, std::move(v));
  });
}

template <typename T>
void Commands::remove(Entity e) {
  ops_.push_back([e](World& w) { w.remove<T>(e); });
}

}  // namespace dyngi::ecs
