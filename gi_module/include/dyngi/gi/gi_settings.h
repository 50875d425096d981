#pragma once
// What a host sets to configure the GI: the technique by name and every technique's options struct.
// Techniques include this (not gi_system.h) to find their options in it.
#include <string>

#include "dyngi/gi/budget_controller.h"
#include "dyngi/gi/many_lights_options.h"
#include "dyngi/gi/temporal_options.h"
#include "dyngi/gi/vct_options.h"
#include "dyngi/gi/voxel_scene.h"

namespace dyngi::gi {

// Every technique's options, each struct the one home of its defaults; `technique` picks which is used.
struct GiSettings {
  std::string technique = "temporal";  // a name from techniqueRegistry()
  VoxelSettings voxels;                // the voxel scene, for techniques that use one (resolution)
  ManyLightsOptions manyLights;
  TemporalOptions temporal;
  VctOptions vct;
  BudgetOptions budget;                // off by default: a GI budget in milliseconds (budget_controller.h)
};

}  // namespace dyngi::gi
