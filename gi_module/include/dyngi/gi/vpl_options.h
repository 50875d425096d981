#pragma once
// The settings both VPL techniques share (many lights from RSMs, temporal VPL paths): how many VPLs,
// how they are gathered (the interleaved gather and the geometry-aware filter in gi_module/indirect/).
// Each technique's options struct holds one VplOptions; the defaults here are the only ones.
#include <algorithm>
#include <cstdint>

#include "dyngi/gi/options.h"

namespace dyngi::gi {

// How a VPL technique decides whether a VPL sees a pixel: a march through the voxel scene's SVO on the
// GPU, Embree rays on the CPU (exact), or not at all (V = 1: no indirect shadows, for comparisons).
enum class VisibilityBackend { Svo, Bvh, None };

struct VplOptions {
  uint32_t vpls = 512;                 // total over all bounces (per bounce: vpls / bounces)
  uint32_t bounces = 1;                // light bounces simulated by VPLs, 1..3
  // The light of the bounces after the last one simulated (shaders/shared/bounce_tail.h): both VPL
  // techniques gather one more bounce (each last-bounce VPL's probe), scaled to carry every later one.
  bool bounceTail = true;
  // The tail gathers the probes of one last-bounce VPL in this many (a fixed, evenly spread choice), each
  // carrying the light of all of them: its gather costs less, its noise grows. A GI budget doubles it.
  uint32_t bounceTailStride = 1;
  uint32_t interleave = 4;             // K: the G-buffer is split into K x K sub-images
  // The gather and the filter run on a screen gatherScale times smaller a side, and a depth- and
  // normal-aware upsample fills the rest (indirect/reduced_screen.h); a GI budget raises it further.
  float gatherScale = 1.0f;
  float distanceClamp = 0.01f;         // B (world units^2): G = cos cos / max(B, d^2)
  // The light the clamp drops for VPLs within sqrt(B) of a pixel, given back spread within sqrt(B) on the
  // pixel's plane and stretched this many times along the corner (shaders/shared/clamp_spread.h): the
  // corners the clamp darkens get it back. 0: off; 1: round.
  float clampSpread = 8.0f;
  // What the gather uses (GatherPush::clampSpread): 0 when off (or with no clamp), else at least 1. The
  // screen-space compensation (clampCompensation), when on, gives back the same light instead.
  float clampSpreadStretch() const {
    return clampSpread > 0.0f && distanceClamp > 0.0f && clampCompensation == 0 ? std::max(1.0f, clampSpread) : 0.0f;
  }
  // Screen-space rays per traced pixel (one in 4 x 4) that give back the light the clamp drops (0: off;
  // indirect/shaders/compensate.comp). Off by default: it can only give back what the screen shows, and a
  // larger B, where it pays, then loses the light of hidden surfaces (a panel lamp's top, docs/QUALITY.md).
  uint32_t clampCompensation = 0;
  float luminanceThreshold = 0.01f;    // skip VPLs dimmer than this fraction of a first-bounce VPL
  // Directional lights shoot their VPLs over the part of the scene within this many metres of the camera
  // (its centre snapped to a grid of half of it) when the scene is wider: a sun over a 400 m street puts
  // its VPLs where the camera sees their light. 0: over the whole scene (camera_focus.h).
  float directionalReach = 64.0f;
  float liftVoxels = 1.5f;             // SVO visibility: segment ends leave their surface by this many voxels
  float filterPlaneTolerance = 0.02f;  // filter: taps on the pixel's plane within this fraction of the view distance
  uint32_t seed = 1;                   // random sequences of the VPLs

  // The VPL count used: vpls rounded down to a multiple of the bounces (each bounce level holds
  // the same number). The one rounding rule of both techniques.
  uint32_t effectiveVplCount() const {
    const uint32_t b = std::clamp(bounces, 1u, 3u);
    return std::max(1u, vpls / b) * b;
  }
  static const OptionTable<VplOptions>& table();
};

}  // namespace dyngi::gi
