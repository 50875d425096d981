#pragma once
// Options of the many-lights technique (VPLs from reflective shadow maps every frame, SVO visibility).
#include <cstdint>

#include "dyngi/gi/vpl_options.h"

namespace dyngi::gi {

enum class ManyLightsView { Final, Indirect, Vpls, SubImages };

struct ManyLightsOptions {
  VplOptions vpl;
  uint32_t rsmResolution = 256;     // RSM texels per side, per light layer
  bool visibility = true;           // false: V = 1 (no indirect shadows), for comparisons
  ManyLightsView view = ManyLightsView::Final;  // a debug view (Technique::setDebugView), not a table row

  static const OptionTable<ManyLightsOptions>& table();
};

}  // namespace dyngi::gi
