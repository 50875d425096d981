#include "techniques/registry_entries.h"

namespace dyngi::gi {

const std::vector<TechniqueEntry>& techniqueRegistry() {
  // A new technique adds its entry here (docs/ARCHITECTURE.md, "How to add a technique").
  static const std::vector<TechniqueEntry> entries = {temporalTechniqueEntry(), manyLightsTechniqueEntry(), vctTechniqueEntry()};
  return entries;
}

const TechniqueEntry* findTechnique(std::string_view name) {
  for (const TechniqueEntry& e : techniqueRegistry())
    if (name == e.name) return &e;
  return nullptr;
}

}  // namespace dyngi::gi
