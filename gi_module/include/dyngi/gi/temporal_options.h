#pragma once
// Options of the temporal technique (incremental VPL paths, temporal sets, reprojection): read by its
// CPU side (VplPaths) and its render side (TemporalIndirect) alike.
#include "dyngi/gi/vpl_options.h"

namespace dyngi::gi {

struct TemporalOptions {
  VplOptions vpl;
  uint32_t temporalSets = 16;         // T: VPLs are gathered one set (1/T of them) per frame
  uint32_t reshootBudget = 0;         // VPLs reshot per frame; 0: vpls / T (one set's worth: steady frame time)
  // When more VPLs are invalid than the budget (a light switched on, moved or turned), all of them are
  // reshot in that frame, up to this many (0: never more than the budget): the pool is whole again at
  // once, at a CPU cost of about 0.5 us a VPL here.
  uint32_t reshootBurst = 4096;
  // A temporal set whose stored light is more than this fraction stale (VplPaths::setStaleFraction: its
  // VPLs' light switched, re-coloured or jumped since it was gathered) leaves the average until it is
  // gathered again: after a light switch the image is the fresh sets' average at once, noisier, instead
  // of fading in over T frames. A light moving by its tolerance is not stale (no pumping as it moves).
  // 1: sets are never dropped.
  float dropStaleSets = 0.5f;
  // While sets hold no light (at the start, or dropped as stale), up to this many are gathered in one
  // frame: a light switched on is whole again in T / catchUpSets frames, at that many times one set's
  // gather cost (and Embree visibility cost) in those frames.
  uint32_t catchUpSets = 4;
  float reprojectionCutoff = 0.02f;   // a stored sample counts when its surface is this close (fraction of the view distance)
  // A light counts as moved/turned once it is this far (fraction of the scene diagonal) or this many
  // radians from where its VPLs were shot. 0 invalidates on any motion; the default keeps VPLs of a
  // slowly moving light alive for a few frames, which bounds the bias and keeps the pool full.
  float lightMoveTolerance = 0.02f;
  float lightTurnTolerance = 0.03f;
  // false: every pixel is reprojected from every set each frame, as when the camera moves (the reference
  // the O(1) update for a still camera is tested against).
  bool incrementalAccumulation = true;
  VisibilityBackend visibility = VisibilityBackend::Svo;  // the SVO on the GPU, Embree on the CPU, or none (V = 1)

  static const OptionTable<TemporalOptions>& table();
};

}  // namespace dyngi::gi
