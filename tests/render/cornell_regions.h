#pragma once
// The Cornell box's regions in a rendered frame, for per-region comparisons against the path tracer:
// the interior pixels (all four neighbours alike) of each wall and of each face of the two boxes.
#include <map>
#include <string>
#include <vector>

#include "render/render_fixture.h"

namespace dyngi::test {

struct Regions {
  std::map<std::string, std::vector<uint8_t>> masks;  // "floor", "red wall", "tall_box -x", ... -> pixel mask
};

// From the frame's G-buffer (position, normal) and the boxes' transforms; `size` x `size` frames.
Regions cornellRegions(const Frame& f, const scene::AssetStore& assets, uint32_t size);

// The pixels of a surface by its G-buffer normal (within ~18 degrees of `normal`), emitters (red >= 1)
// left out: the walls of a scene that is not the built-in box. `count` gets how many.
std::vector<uint8_t> surfaceFacing(const Frame& f, const glm::vec3& normal, size_t& count);

inline double luminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

}  // namespace dyngi::test
