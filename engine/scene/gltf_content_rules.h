#pragma once
// What the glTF importer lets a file make it do before tinygltf parses it and while tinygltf reads its
// buffers and images (docs/CONTENT.md): JSON nesting bounded, files opened only inside the allowed
// folders, images decoded only as PNG or JPEG by libpng and libjpeg-turbo, within a size budget.
#include <tiny_gltf.h>

#include <cstdint>
#include <string>
#include <vector>

namespace dyngi::scene::content {

constexpr int kMaxJsonDepth = 64;

// "" when no array or object in the JSON (a .gltf's text, or a .glb's JSON chunk) nests deeper than
// kMaxJsonDepth; tinygltf's conversion recurses once per level.
std::string checkJsonDepth(const uint8_t* data, size_t size);

// The folders a file's URIs may name files in (canonical paths), and what its images may cost.
struct ReadRules {
  std::vector<std::string> folders;
  uint32_t maxImageDimension = 0;
  uint64_t maxImageBytes = 0;  // decoded, all images of the file together
  uint64_t imageBytes = 0;     // decoded so far
  // The model tinygltf is filling: its buffers and bufferViews are parsed before its images, and tinygltf
  // hands an image's bufferView bytes over without checking that they lie inside the buffer.
  const tinygltf::Model* loading = nullptr;
};

// tinygltf's file access: a path outside every allowed folder does not exist and is never opened.
tinygltf::FsCallbacks containedFiles(ReadRules& rules);
// tinygltf's image decoder (user pointer: the ReadRules): an image's bufferView checked against its buffer,
// PNG or JPEG by signature, the size read from the header and refused before decoding when over the
// rules' limits.
bool decodeImage(tinygltf::Image* image, int index, std::string* err, std::string* warn, int, int, const unsigned char* bytes,
                 int size, void* rules);

// "" when every value the import reads is in glTF's range as the float it becomes (cameras, lights,
// material factors, samplers, the scene index); else the first one that is not.
std::string checkValues(const tinygltf::Model& model);
// The scene's root nodes, when the node graph is a forest (each node with at most one parent, each root
// listed once and nobody's child); else an error naming the node. Walks from them visit each node once.
std::string sceneRoots(const tinygltf::Model& model, std::vector<int>& roots);

}  // namespace dyngi::scene::content
