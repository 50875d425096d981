#include "dyngi/gi/vpl_options.h"

namespace dyngi::gi {

const OptionTable<VplOptions>& VplOptions::table() {
  static const OptionTable<VplOptions> t =
      OptionTable<VplOptions>()
          .add(DYNGI_OPTION(VplOptions, vpls), "VPLs over all bounces (rounded down to a multiple of the bounces)", 16, 65536)
          .add(DYNGI_OPTION(VplOptions, bounces), "light bounces carried by VPLs", 1, 3)
          .add(DYNGI_OPTION(VplOptions, bounceTail), "the light of every bounce after the last (one probe ray per last-bounce VPL, gathered as one more bounce scaled by the ratio the probes measure)", 0, 1)
          .add(DYNGI_OPTION(VplOptions, bounceTailStride), "the bounce tail gathers one probe in this many, each carrying the light of all of them (a GI budget doubles it)", 1, 4)
          .add(DYNGI_OPTION(VplOptions, interleave), "K: the gather splits the image into K x K sub-images", 1, 8)
          .add(DYNGI_OPTION(VplOptions, gatherScale), "the gather and filter run on a screen s times smaller a side (1.5: 4 pixels in 9), upsampled to the rest with depth and normal weights", 1, 4)
          .add(DYNGI_OPTION(VplOptions, directionalReach), "metres around the camera over which directional lights shoot their VPLs when the scene is wider (0: the whole scene)", 0, 100000)
          .add(DYNGI_OPTION(VplOptions, distanceClamp), "distance clamp B in world units^2: G = cos cos / max(B, d^2)", 0, 100)
          .add(DYNGI_OPTION(VplOptions, clampSpread), "give back the light the distance clamp drops, spread within sqrt(B) on the receiving plane and stretched this many times along the corner (0: off; 1, or less: round; off while --clamp-compensation is on)", 0, 16)
          .add(DYNGI_OPTION(VplOptions, clampCompensation), "screen-space rays per traced pixel (one in 4 x 4) that give back the light the distance clamp drops (0: off)", 0, 64)
          .add(DYNGI_OPTION(VplOptions, luminanceThreshold), "skip VPLs dimmer than this fraction of a first-bounce VPL", 0, 1)
          .add(DYNGI_OPTION(VplOptions, liftVoxels), "SVO visibility: segment ends leave their surface by this many voxels", 0, 8)
          .add(DYNGI_OPTION(VplOptions, filterPlaneTolerance), "filter taps count within this fraction of the view distance off the pixel's plane", 0, 1)
          .add(DYNGI_OPTION(VplOptions, seed), "seed of the VPLs' random numbers", 0, 4294967295.0);
  return t;
}

}  // namespace dyngi::gi
