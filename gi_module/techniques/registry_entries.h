#pragma once
// Each technique's registry entry, defined in its own folder (techniques/<name>/<name>_technique.cpp);
// techniques/registry.cpp lists them.
#include "dyngi/gi/technique.h"

namespace dyngi::gi {

TechniqueEntry manyLightsTechniqueEntry();
TechniqueEntry temporalTechniqueEntry();
TechniqueEntry vctTechniqueEntry();

}  // namespace dyngi::gi
