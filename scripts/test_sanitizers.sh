#!/usr/bin/env bash
# The AddressSanitizer + UndefinedBehaviorSanitizer job (RelWithDebInfo, float-cast-overflow included,
# no recovery: the first report fails the test). Builds build-asan/ and runs every unit, GI, end-to-end and
# render test; extra arguments go to ctest.
#
# The render and end-to-end tests run two at a time here (DYNGI_SERIAL_GPU_TESTS=OFF), unlike the Release
# job: under the sanitizers they wait on page faults, not on the CPU. ASan gives lavapipe's large
# allocations fresh pages, and on a virtual machine each fault costs the kernel tens of microseconds. Eight
# render tests took 85-97 s one at a time and 27-28 s two at a time (three or four at a time: no better).
#
# Lavapipe leaks a little at exit, and the Vulkan loader unloads the driver before LeakSanitizer's
# report, so those leaks show as "<unknown module>" with no way to tell them from ours. The driver is
# therefore kept loaded (LD_PRELOAD): its static data stays reachable and is not reported, while a leak
# in project code keeps its full stack and fails the run. No suppression list hides anything.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDYNGI_SANITIZE=ON -DDYNGI_BUILD_TESTS=ON \
  -DDYNGI_TEST_TIMEOUT_SCALE=6 -DDYNGI_SERIAL_GPU_TESTS=OFF >/dev/null
cmake --build build-asan -j"$(nproc)" --target dyngi_unit_tests dyngi_gi_tests dyngi_render_tests dyngi_e2e_tests dyngi_sample

driver=$(ls /usr/lib/*/libvulkan_lvp.so 2>/dev/null | head -1 || true)
if [ -z "$driver" ]; then
  echo "test_sanitizers: lavapipe (libvulkan_lvp.so) not found; setup.sh installs mesa-vulkan-drivers" >&2
  exit 1
fi
export LD_PRELOAD="$driver"
# verify_asan_link_order=0: the driver, not the ASan runtime, comes first in LD_PRELOAD (the runtime is
# linked into every instrumented binary, so it is loaded all the same).
export ASAN_OPTIONS="detect_leaks=1:verify_asan_link_order=0:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

cd build-asan
ctest --output-on-failure -j"$(nproc)" -L 'unit|gi|e2e' "$@"
# The validation layer's synchronization checks (Debian 12's layer, 1.3.239) leak 47,879 bytes in 325
# allocations of their own in every process, whatever the test does: here the render tests run with the
# layer's core checks only (the Release job keeps the synchronization checks on).
# Three quality measurements are left to the Release job: they run the same host code as the tests
# named beside them for hundreds of frames more, which under the sanitizers costs about 5 minutes and
# reaches no code those tests do not:
#   QualityFlickerAndSettleTime (lights switched and moved, a box moved): RenderTest.LightOffDrivesIndirectToZeroAndBack,
#     RenderTest.MovedObjectChangesIndirectWherePathTracerSays, RenderTest.VctFollowsMovedLightsAndObjectsAndSwitchedLights;
#   QualityFlickerUnderACameraPan (camera motion, reprojection): RenderTest.CameraMotionStaysCloseAndNeverLeavesHoles;
#   QualityGhostingBehindAMovingBox (an object moving every frame): RenderTest.MovedObjectChangesIndirectWherePathTracerSays,
#     RenderTest.IncrementalAccumulationEqualsFullReprojection.
# So are two accuracy measurements that run a technique many times over (12 and 6 runs):
#   BounceTailBringsBothVplTechniquesToThePathTracersManyBounces (the bounce tail): VplPaths.BounceTailRatio...,
#     ManyLightsTest.BounceTailScalesTheLastBounceByWhatItsProbesMeasure;
#   EmissivePanelLightsTheRoomThroughBothVplTechniques (emitters as VPL sources): RenderTest.SharedEmissiveCornellBox...,
#     RenderTest.EmissivePanelSwitchedOffTakesItsIndirectLightAway, VplPaths.Emi*.
# And the two longest left (74 and 45 s under the sanitizers at f1561e8, when the whole CI took 39 min):
#   EveryQualityKnobAtItsFloorKeepsTheMeanIndirectLight (each knob at its floor): RenderTest.AGiBudgetDrivesTheKnobsFromTheMeasuredCost
#     moves the same knobs through the same setters;
#   TemporalPathsMatchPathTracerPerRegionForEveryLightType (accuracy per light type): the light types' VPL shooting runs in
#     VplPaths.* (gi label) and RenderTest.LightOffDrivesIndirectToZeroAndBack.
# And one accuracy measurement that path traces twice at 512 spp: VplImageErrorTailStaysWithinTwiceThePathTracersOwnNoise
#   (the clamp compensation with 3 bounces): RenderTest.ClampCompensationGivesTheCornersTheirLightBack runs the same passes.
DYNGI_SYNC_VALIDATION=0 ctest --output-on-failure -j"$(nproc)" -L render \
  -E 'RenderTest\.(Quality(FlickerAndSettleTime|FlickerUnderACameraPan|GhostingBehindAMovingBox)PerTechnique|BounceTailBringsBothVplTechniquesToThePathTracersManyBounces|EmissivePanelLightsTheRoomThroughBothVplTechniques|EveryQualityKnobAtItsFloorKeepsTheMeanIndirectLight|TemporalPathsMatchPathTracerPerRegionForEveryLightType|VplImageErrorTailStaysWithinTwiceThePathTracersOwnNoise)' "$@"
