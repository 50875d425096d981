#pragma once
// Sparse-set storage for one component type.
//
// Why sparse sets rather than archetypes: dyngi's systems mostly touch one or two component types
// (Transform -> WorldTransform, MeshInstance + WorldTransform), components are added and removed at
// run time (tags, lights switched on/off), and change detection wants a stable per-component slot to
// stamp. Sparse sets give O(1) add/remove/lookup with no table moves, dense arrays for iteration,
// and a natural place for per-component change ticks. See docs/ARCHITECTURE.md.
#include <algorithm>
#include <cassert>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <optional>
#include <vector>

#include "dyngi/engine/ecs/entity.h"

namespace dyngi::ecs {

// One record per (entity, tick) at which a component was written or removed. The log is ordered by
// tick, so "changed since T" walks only the records newer than T.
struct ChangeRecord {
  Entity entity;
  Tick tick;
  // The component's latest record is the one whose seq it holds. 32 bits wrap, but only between records
  // 2^32 apart, and a record still in a log has fewer behind it (they would take 64 GB).
  uint32_t seq = 0;
};

class ComponentPoolBase {
 public:
  virtual ~ComponentPoolBase() = default;
  virtual bool contains(Entity e) const = 0;
  virtual bool removeIfPresent(Entity e, Tick tick) = 0;
  virtual size_t size() const = 0;
  virtual void trimLogs(Tick olderOrEqual) = 0;
  virtual const char* typeName() const = 0;
};

template <typename T>
class ComponentPool final : public ComponentPoolBase {
 public:
  static constexpr uint32_t kAbsent = 0xFFFFFFFFu;
  static constexpr size_t kMinDroppedLog = 4096;  // shorter logs are kept: a small pool's scan is no cheaper

  bool contains(Entity e) const override {
    return e.index < sparse_.size() && sparse_[e.index] != kAbsent && entities_[sparse_[e.index]] == e;
  }
  size_t size() const override { return dense_.size(); }
  const char* typeName() const override { return typeid(T).name(); }

  T* tryGet(Entity e) { return contains(e) ? &dense_[sparse_[e.index]] : nullptr; }
  const T* tryGet(Entity e) const { return contains(e) ? &dense_[sparse_[e.index]] : nullptr; }

  // Room for `more` components beside those held, and entity indices below `indexBound`. A bulk load
  // (`more` past kMinDroppedLog) is not logged for the rest of `tick`: its records would be dropped at a
  // quarter of the pool anyway; readers from before the tick scan the pool.
  void reserve(size_t more, size_t indexBound, Tick tick) {
    const size_t n = dense_.size() + more;
    dense_.reserve(n);
    entities_.reserve(n);
    changedTick_.reserve(n);
    lastSeq_.reserve(n);
    sparse_.reserve(indexBound);
    if (more >= kMinDroppedLog) {
      changeLog_ = {};
      logFloor_ = std::max(logFloor_, tick);
      unloggedTick_ = tick;
    }
  }

  T& emplace(Entity e, T value, Tick tick) {
    if (contains(e)) {
      uint32_t d = sparse_[e.index];
      dense_[d] = std::move(value);
      stamp(d, tick);
      return dense_[d];
    }
    if (e.index >= sparse_.size()) sparse_.resize(size_t(e.index) + 1, kAbsent);
    sparse_[e.index] = uint32_t(dense_.size());
    dense_.push_back(std::move(value));
    entities_.push_back(e);
    changedTick_.push_back(0);
    lastSeq_.push_back(0);
    stamp(uint32_t(dense_.size() - 1), tick);
    return dense_.back();
  }

  // Mutable access that counts as a write.
  T& write(Entity e, Tick tick) {
    uint32_t d = denseIndexOrThrow(e);
    stamp(d, tick);
    return dense_[d];
  }

  bool removeIfPresent(Entity e, Tick tick) override {
    if (!contains(e)) return false;
    uint32_t d = sparse_[e.index];
    uint32_t last = uint32_t(dense_.size() - 1);
    if (d != last) {
      dense_[d] = std::move(dense_[last]);
      entities_[d] = entities_[last];
      changedTick_[d] = changedTick_[last];
      lastSeq_[d] = lastSeq_[last];
      sparse_[entities_[d].index] = d;
    }
    dense_.pop_back();
    entities_.pop_back();
    changedTick_.pop_back();
    lastSeq_.pop_back();
    sparse_[e.index] = kAbsent;
    removedLog_.push_back({e, tick, ++seq_});
    return true;
  }

  Tick changedTick(Entity e) const { return changedTick_[denseIndexOrThrow(e)]; }

  // Entities whose component was added or written after `since`, each once, in order of last write.
  // Cost: proportional to the writes since `since` (when the log still reaches back that far),
  // otherwise a scan of the pool.
  template <typename Fn>
  void forEachChangedSince(Tick since, Fn&& fn) const {
    if (since < logFloor_) {
      for (size_t d = 0; d < dense_.size(); ++d)
        if (changedTick_[d] > since) fn(entities_[d]);
      return;
    }
    auto first = std::upper_bound(changeLog_.begin(), changeLog_.end(), since,
                                  [](Tick t, const ChangeRecord& r) { return t < r.tick; });
    for (auto it = first; it != changeLog_.end(); ++it) {
      // Only the record of the latest write counts: an older record of a rewritten component, or of a
      // removed (and maybe re-added) one, no longer matches, so each entity is reported once.
      if (contains(it->entity) && lastSeq_[sparse_[it->entity.index]] == it->seq) fn(it->entity);
    }
  }

  template <typename Fn>
  void forEachRemovedSince(Tick since, Fn&& fn) const {
    auto first = std::upper_bound(removedLog_.begin(), removedLog_.end(), since,
                                  [](Tick t, const ChangeRecord& r) { return t < r.tick; });
    for (auto it = first; it != removedLog_.end(); ++it) fn(it->entity);
  }

  void trimLogs(Tick olderOrEqual) override {
    auto trim = [olderOrEqual](std::vector<ChangeRecord>& log) {
      auto keep = std::upper_bound(log.begin(), log.end(), olderOrEqual,
                                   [](Tick t, const ChangeRecord& r) { return t < r.tick; });
      log.erase(log.begin(), keep);
    };
    trim(changeLog_);
    trim(removedLog_);
    logFloor_ = std::max(logFloor_, olderOrEqual);
  }
  size_t changeLogSize() const { return changeLog_.size(); }

  const std::vector<Entity>& entities() const { return entities_; }
  const std::vector<T>& components() const { return dense_; }

 private:
  void stamp(uint32_t d, Tick tick) {
    if (changedTick_[d] == tick) return;  // already logged during this tick
    changedTick_[d] = tick;
    lastSeq_[d] = ++seq_;
    // A log holding records for a quarter of the pool walks about as fast as a scan of it (which reads
    // the ticks in order; forEachChangedSince scans for readers older than logFloor_): it is dropped
    // with its memory, so a bulk load of N entities logs N / 4 records at most.
    if (tick == unloggedTick_) return;  // a reserved bulk load: readers from before it scan
    if (changeLog_.size() >= kMinDroppedLog && 4 * changeLog_.size() >= dense_.size()) {
      changeLog_ = {};
      logFloor_ = std::max(logFloor_, tick);
      return;
    }
    changeLog_.push_back({entities_[d], tick, seq_});
  }
  uint32_t denseIndexOrThrow(Entity e) const {
    if (!contains(e))
      throw std::out_of_range(std::string("entity has no component ") + typeid(T).name());
    return sparse_[e.index];
  }

  std::vector<uint32_t> sparse_;
  std::vector<T> dense_;
  std::vector<Entity> entities_;
  std::vector<Tick> changedTick_;
  std::vector<uint32_t> lastSeq_;
  std::vector<ChangeRecord> changeLog_;
  uint32_t seq_ = 0;
  std::vector<ChangeRecord> removedLog_;
  Tick logFloor_ = 0;  // the logs hold every record newer than this
  std::optional<Tick> unloggedTick_;  // the tick of a reserved bulk load
};

}  // namespace dyngi::ecs
