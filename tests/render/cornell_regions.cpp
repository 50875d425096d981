#include "render/cornell_regions.h"

#include <cmath>

namespace dyngi::test {

Regions cornellRegions(const Frame& f, const scene::AssetStore& assets, uint32_t size) {
  std::vector<std::string> label(f.hdr.size());
  std::vector<Obb> boxes;
  std::vector<std::string> boxNames;
  for (const auto& d : f.snapshot.draws) {
    const auto& m = assets.mesh(d.mesh);
    if (m.name == "short_box" || m.name == "tall_box") boxes.push_back({d.model, m.bounds.extent() * 0.5f}), boxNames.push_back(m.name);
  }
  for (size_t i = 0; i < f.hdr.size(); ++i) {
    const glm::vec4& p = f.position[i];
    const glm::vec4& n = f.normal[i];
    if (p.w < 0.5f) continue;
    for (size_t b = 0; b < boxes.size(); ++b) {
      glm::vec3 l = glm::vec3(glm::inverse(boxes[b].model) * glm::vec4(glm::vec3(p), 1.0f));
      glm::vec3 h = boxes[b].halfExtent + 1e-3f;
      if (std::abs(l.x) <= h.x && std::abs(l.y) <= h.y && std::abs(l.z) <= h.z) {
        glm::vec3 ln = glm::vec3(glm::inverse(boxes[b].model) * glm::vec4(glm::vec3(n), 0.0f));
        int axis = std::abs(ln.x) > 0.9f ? 0 : std::abs(ln.y) > 0.9f ? 1 : 2;
        label[i] = boxNames[b] + (ln[axis] > 0 ? " +" : " -") + "xyz"[axis];
      }
    }
    if (!label[i].empty()) continue;
    if (std::abs(p.y) < 1e-3f && n.y > 0.99f) label[i] = "floor";
    else if (std::abs(p.y - 2.0f) < 1e-3f && n.y < -0.99f) label[i] = "ceiling";
    else if (p.z < -0.999f && n.z > 0.99f) label[i] = "back wall";
    else if (p.x < -0.999f && n.x > 0.99f) label[i] = "red wall";
    else if (p.x > 0.999f && n.x < -0.99f) label[i] = "green wall";
  }
  Regions r;
  for (uint32_t y = 1; y + 1 < size; ++y)
    for (uint32_t x = 1; x + 1 < size; ++x) {
      size_t i = size_t(y) * size + x;
      const std::string& l = label[i];
      if (l.empty() || label[i - 1] != l || label[i + 1] != l || label[i - size] != l || label[i + size] != l) continue;
      auto& m = r.masks[l];
      if (m.empty()) m.assign(f.hdr.size(), 0);
      m[i] = 1;
    }
  return r;
}

std::vector<uint8_t> surfaceFacing(const Frame& f, const render::ImageRgba& reference, const glm::vec3& normal, size_t& count) {
  std::vector<uint8_t> mask(f.hdr.size(), 0);
  count = 0;
  for (size_t i = 0; i < mask.size(); ++i) {
    mask[i] = f.position[i].w > 0.5f && glm::dot(glm::vec3(f.normal[i]), normal) > 0.95f && reference[i].r < 1.0f;
    count += mask[i];
  }
  return mask;
}

}  // namespace dyngi::test
