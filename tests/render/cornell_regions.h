#pragma once
// The Cornell box's regions in a rendered frame, for per-region comparisons against the path tracer:
// the interior pixels (all four neighbours alike) of each wall and of each face of the two boxes.
#include <map>
#include <string>
#include <vector>

#include "dyngi/engine/render/image_metrics.h"
#include "render/render_fixture.h"

namespace dyngi::test {

struct Regions {
  std::map<std::string, std::vector<uint8_t>> masks;  // "floor", "red wall", "tall_box -x", ... -> pixel mask
};

// From the frame's G-buffer (position, normal) and the boxes' transforms; `size` x `size` frames.
Regions cornellRegions(const Frame& f, const scene::AssetStore& assets, uint32_t size);

// The pixels of a surface by its G-buffer normal (within ~18 degrees of `normal`), emitters left out:
// the walls of a scene that is not the built-in box. An emitter is a pixel the `reference` image (the
// path tracer's, same view) shows with red >= 1: the mask must not depend on the image under test, or
// a technique that over-brightens a wall would drop that wall's brightest pixels from its own check.
// `count` gets how many.
std::vector<uint8_t> surfaceFacing(const Frame& f, const render::ImageRgba& reference, const glm::vec3& normal, size_t& count);

inline double luminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

}  // namespace dyngi::test
