#pragma once
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace dyngi::render {

// Returns an empty string on success, else a one-line error.
std::string writePng(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba8);
// Linear float RGB(A) EXR (half is not used: tests compare linear radiance).
std::string writeExr(const std::string& path, uint32_t width, uint32_t height, const std::vector<glm::vec4>& rgba);
// Reads back an EXR written by writeExr (tests and tools).
std::string readExr(const std::string& path, uint32_t& width, uint32_t& height, std::vector<glm::vec4>& rgba);

}  // namespace dyngi::render
