#pragma once
// Options of the many-lights technique (VPLs from reflective shadow maps every frame, SVO visibility).
#include <cstdint>

#include "dyngi/gi/vpl_options.h"

namespace dyngi::gi {

enum class ManyLightsView { Final, Vpls, SubImages };

struct ManyLightsOptions {
  VplOptions vpl;
  uint32_t rsmResolution = 256;     // RSM texels per side, per light layer
  VisibilityBackend visibility = VisibilityBackend::Svo;  // Svo or None (V = 1: no indirect shadows, for comparisons)
  ManyLightsView view = ManyLightsView::Final;  // a debug view (Technique::setDebugView), not a table row

  static const OptionTable<ManyLightsOptions>& table();
};

}  // namespace dyngi::gi
