#pragma once
// The table the gather's clamp spread reads (shaders/shared/clamp_spread.h), and its C++ twin's lookup.
#include <vector>

#include <glm/glm.hpp>

namespace dyngi::gi {

// (I, N) at every sample of the table, computed by quadrature on the first call (about 25 ms) and kept:
// every gather pass (each technique, each switch) uploads the same table.
const std::vector<glm::vec2>& clampSpreadTable();
// Bilinear lookup of (I, N) at (eta, c), as gather.glsl does it.
glm::vec2 clampSpreadLookup(const std::vector<glm::vec2>& table, float eta, float c);

}  // namespace dyngi::gi
