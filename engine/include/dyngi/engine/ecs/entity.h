#pragma once
// Entity handles: an index into the world's slot table plus the generation of that slot.
// Destroying an entity bumps its slot's generation, so an old handle is detected as stale
// and never aliases the entity that later reuses the slot.
#include <cstdint>
#include <functional>

namespace dyngi::ecs {

struct Entity {
  static constexpr uint32_t kInvalidIndex = 0xFFFFFFFFu;
  uint32_t index = kInvalidIndex;
  uint32_t generation = 0;

  constexpr bool isNull() const { return index == kInvalidIndex; }
  friend constexpr bool operator==(Entity a, Entity b) = default;
  friend constexpr bool operator<(Entity a, Entity b) {
    return a.index != b.index ? a.index < b.index : a.generation < b.generation;
  }
};

inline constexpr Entity kNullEntity{};

// A world tick. Every write through the World API stamps the component with the current tick;
// systems remember the tick of their last run and ask for what changed after it.
using Tick = uint32_t;

}  // namespace dyngi::ecs

template <>
struct std::hash<dyngi::ecs::Entity> {
  size_t operator()(dyngi::ecs::Entity e) const noexcept {
    return std::hash<uint64_t>()((uint64_t(e.generation) << 32) | e.index);
  }
};
