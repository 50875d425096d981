#pragma once
// Hostile content made in code, for the importer's tests and the fuzz corpus: deep JSON, image bytes
// that are not what they claim, PNG and JPEG headers that promise huge images, graphs that are not forests.
#include <cstdint>
#include <string>
#include <vector>

#include "support/gltf_writer.h"

namespace dyngi::test {

// "[[[...0...]]]" nested `depth` deep.
std::string deepJsonArray(int depth);
// A 16-bit binary PGM of width x height; without its pixel data when `withData` is false.
std::vector<uint8_t> pgm16(uint32_t width, uint32_t height, bool withData);
// A Radiance HDR whose first RLE scanline ends early (stb_image looped on it).
std::vector<uint8_t> truncatedRadianceHdr();
// A PNG whose header says width x height, followed by a token IDAT: valid up to its pixel data.
std::vector<uint8_t> pngHeader(uint32_t width, uint32_t height);
// The start of a JPEG (SOI, a baseline SOF0 of width x height), then nothing.
std::vector<uint8_t> jpegHeader(uint16_t width, uint16_t height);
// A real 2 x 2 RGBA PNG.
std::vector<uint8_t> smallPng();

// One quad, textured by image 0 (the caller fills spec.imagesJson).
GltfSpec texturedQuad();
// `layers` layers of two nodes, each node a child of both nodes of the layer above: 2^layers paths.
GltfSpec diamondGraph(int layers);

}  // namespace dyngi::test
