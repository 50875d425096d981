#pragma once
// Per-entity side tables for systems that follow many entities (GI's voxel ranges, BVH instances): a map
// and a set keyed by Entity, stored as a dense array of entries plus a slot array indexed by the entity's
// index. About 4 bytes per entity index and 4 per entry over the entry itself, where a std::unordered_map
// node costs 40-60 bytes over its value; a lookup reads two arrays.
//
// Differences from std::unordered_map: erase moves the last entry into the erased one's place, so
// erase(it) returns `it` (the moved entry, not visited yet) and erasing by key while iterating skips an
// entry; inserting may move entries, so references do not outlive an insert. Two generations of one
// index are two keys. Iteration is in insertion order until the first erase.
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <iterator>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "dyngi/engine/ecs/entity.h"

namespace dyngi::ecs {

template <typename T>
class EntityMap {
 public:
  using value_type = std::pair<Entity, T>;
  using iterator = typename std::vector<value_type>::iterator;
  using const_iterator = typename std::vector<value_type>::const_iterator;

  iterator begin() { return dense_.begin(); }
  iterator end() { return dense_.end(); }
  const_iterator begin() const { return dense_.begin(); }
  const_iterator end() const { return dense_.end(); }
  size_t size() const { return dense_.size(); }
  bool empty() const { return dense_.empty(); }
  void reserve(size_t n) { dense_.reserve(n), next_.reserve(n); }

  iterator find(Entity e) { return dense_.begin() + ptrdiff_t(position(e)); }
  const_iterator find(Entity e) const { return dense_.begin() + ptrdiff_t(position(e)); }
  size_t count(Entity e) const { return position(e) < dense_.size() ? 1 : 0; }
  bool contains(Entity e) const { return count(e) > 0; }
  T& at(Entity e) { return dense_[checked(e)].second; }
  const T& at(Entity e) const { return dense_[checked(e)].second; }
  T& operator[](Entity e) { return try_emplace(e).first->second; }

  // Adds (e, T(args...)) unless e is present; the entry and whether it was added.
  template <typename... Args>
  std::pair<iterator, bool> try_emplace(Entity e, Args&&... args) {
    const size_t p = position(e);
    if (p < dense_.size()) return {dense_.begin() + ptrdiff_t(p), false};
    if (e.isNull()) throw std::invalid_argument("EntityMap: the null entity is not a key");  // its index would size head_ to 2^32
    if (dense_.size() >= kAbsent) throw std::length_error("EntityMap: too many entries");
    if (e.index >= head_.size()) head_.resize(size_t(e.index) + 1 + head_.size() / 2, kAbsent);
    dense_.emplace_back(std::piecewise_construct, std::forward_as_tuple(e), std::forward_as_tuple(std::forward<Args>(args)...));
    next_.push_back(head_[e.index]);  // another generation of the index may be held too (a stale handle)
    head_[e.index] = uint32_t(dense_.size() - 1);
    return {dense_.end() - 1, true};
  }
  template <typename... Args>
  std::pair<iterator, bool> emplace(Entity e, Args&&... args) { return try_emplace(e, std::forward<Args>(args)...); }

  size_t erase(Entity e) {
    const size_t p = position(e);
    if (p >= dense_.size()) return 0;
    erase(dense_.begin() + ptrdiff_t(p));
    return 1;
  }
  // Erases the entry at `it`; the last entry takes its place, so `it` is the next one to visit.
  iterator erase(iterator it) {
    const uint32_t p = uint32_t(it - dense_.begin());
    *linkTo(p) = next_[p];
    const uint32_t last = uint32_t(dense_.size() - 1);
    if (p != last) {
      *linkTo(last) = p;
      dense_[p] = std::move(dense_[last]);
      next_[p] = next_[last];
    }
    dense_.pop_back();
    next_.pop_back();
    return dense_.begin() + ptrdiff_t(p);
  }
  void clear() {
    for (const value_type& v : dense_) head_[v.first.index] = kAbsent;
    dense_.clear();
    next_.clear();
  }

 private:
  static constexpr uint32_t kAbsent = 0xFFFFFFFFu;
  // The entry's position, or size() when e (this generation of it) is absent.
  size_t position(Entity e) const {
    if (e.index >= head_.size()) return dense_.size();
    for (uint32_t p = head_[e.index]; p != kAbsent; p = next_[p])
      if (dense_[p].first == e) return p;
    return dense_.size();
  }
  size_t checked(Entity e) const {
    const size_t p = position(e);
    if (p >= dense_.size()) throw std::out_of_range("EntityMap::at: entity absent");
    return p;
  }
  // The link that holds position p: the head of its index's chain or the entry before it.
  uint32_t* linkTo(uint32_t p) {
    uint32_t* link = &head_[dense_[p].first.index];
    while (*link != p) link = &next_[*link];
    return link;
  }

  std::vector<uint32_t> head_;   // by entity index: the first entry of that index, or kAbsent
  std::vector<value_type> dense_;
  std::vector<uint32_t> next_;   // by entry: the next entry of the same index (another generation)
};

class EntitySet {
  struct Nothing {};
  using Map = EntityMap<Nothing>;

 public:
  class iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = Entity;
    using difference_type = ptrdiff_t;
    using pointer = const Entity*;
    using reference = const Entity&;
    iterator() = default;
    explicit iterator(Map::const_iterator it) : it_(it) {}
    const Entity& operator*() const { return it_->first; }
    const Entity* operator->() const { return &it_->first; }
    iterator& operator++() { return ++it_, *this; }
    iterator operator++(int) { iterator old = *this; ++it_; return old; }
    friend bool operator==(const iterator& a, const iterator& b) { return a.it_ == b.it_; }

   private:
    Map::const_iterator it_;
  };
  using const_iterator = iterator;

  EntitySet() = default;
  EntitySet(std::initializer_list<Entity> entities) { insert(entities.begin(), entities.end()); }

  iterator begin() const { return iterator(map_.begin()); }
  iterator end() const { return iterator(map_.end()); }
  size_t size() const { return map_.size(); }
  bool empty() const { return map_.empty(); }
  void reserve(size_t n) { map_.reserve(n); }
  size_t count(Entity e) const { return map_.count(e); }
  bool contains(Entity e) const { return map_.contains(e); }
  bool insert(Entity e) { return map_.try_emplace(e).second; }  // whether e was absent
  template <typename It>
  void insert(It first, It last) {
    for (; first != last; ++first) insert(*first);
  }
  size_t erase(Entity e) { return map_.erase(e); }
  void clear() { map_.clear(); }

 private:
  Map map_;
};

}  // namespace dyngi::ecs
