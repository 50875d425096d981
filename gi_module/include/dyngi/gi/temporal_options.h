#pragma once
// Options of the temporal technique (incremental VPL paths, temporal sets, reprojection): read by its
// CPU side (VplPaths) and its render side (TemporalIndirect) alike.
#include "dyngi/gi/vpl_options.h"

namespace dyngi::gi {

enum class VisibilityBackend { Svo, Bvh, None };

struct TemporalOptions {
  VplOptions vpl;
  uint32_t temporalSets = 16;         // T: VPLs are gathered one set (1/T of them) per frame
  uint32_t reshootBudget = 0;         // VPLs reshot per frame; 0: vplCount / T (one set's worth: steady frame time)
  float reprojectionCutoff = 0.02f;   // a stored sample counts when its surface is this close (fraction of the view distance)
  // A light counts as moved/turned once it is this far (fraction of the scene diagonal) or this many
  // radians from where its VPLs were shot. 0 invalidates on any motion; the default keeps VPLs of a
  // slowly moving light alive for a few frames, which bounds the bias and keeps the pool full.
  float lightMoveTolerance = 0.02f;
  float lightTurnTolerance = 0.03f;
  // false: every pixel is reprojected from every set each frame, as when the camera moves (the reference
  // the O(1) update for a still camera is tested against).
  bool incrementalAccumulation = true;
  VisibilityBackend visibility = VisibilityBackend::Svo;  // chosen with the technique (--gi svo | bvh), not a table row

  static const OptionTable<TemporalOptions>& table();
};

}  // namespace dyngi::gi
