// libFuzzer target: the glTF / GLB importer on arbitrary bytes (built by scripts/fuzz.sh with clang,
// -fsanitize=fuzzer,address,undefined). Any crash, sanitizer report or hang is a finding; the importer
// must answer every input with success or one error line.
#include <cstddef>
#include <cstdint>

#include "dyngi/engine/scene/gltf_import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  dyngi::ecs::World world;
  dyngi::scene::AssetStore assets;
  dyngi::scene::ImportReport report;
  // External URIs resolve into a directory that does not exist: the fuzzer explores the bytes, not the disk.
  std::string err = dyngi::scene::importGltfFromMemory(data, size, "fuzz-input", "/nonexistent-dyngi-fuzz-dir", world, assets,
                                                       &report);
  if (!err.empty() && err.find('\n') != std::string::npos) __builtin_trap();  // the contract: one line
  return 0;
}
