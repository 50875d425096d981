#pragma once
// Image comparison metrics for tests and tools. Images are linear RGBA float, row-major, equal size.
// Metrics use RGB (alpha ignored); `mask` (optional, same size, nonzero = counted) selects a region.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace dyngi::render {

using ImageRgba = std::vector<glm::vec4>;

double rmse(const ImageRgba& a, const ImageRgba& reference, const std::vector<uint8_t>* mask = nullptr);
// Mean of (a - ref)^2 / (ref^2 + 0.01) per channel: scale-independent error used for GI comparisons.
double relativeMse(const ImageRgba& a, const ImageRgba& reference, const std::vector<uint8_t>* mask = nullptr);
// PSNR in dB against `peak` (the reference's maximum when 0). Infinite for identical images.
double psnr(const ImageRgba& a, const ImageRgba& reference, double peak = 0.0);
// Mean SSIM over 8x8 windows (stride 4) of luminance, constants for a dynamic range L (the reference's
// maximum luminance when 0).
double ssim(const ImageRgba& a, const ImageRgba& reference, uint32_t width, uint32_t height, double range = 0.0);
// Sum over pixels of |a - ref| (RGB) over the sum of ref (RGB): the error relative to the image's own
// level, not dominated by dim pixels. 0 when both are black; 1 for an image against black.
double relativeL1(const ImageRgba& a, const ImageRgba& reference, const std::vector<uint8_t>* mask = nullptr);
// The q-quantile (0.99: the 99th percentile) over pixels of the relative luminance error
// |L(a) - L(ref)| / max(L(ref), 0.1 x the reference's mean luminance): the tail that averages hide (hot
// pixels, blocks, streaks). Pixels darker than a tenth of the mean count against that tenth, so black
// corners do not dominate. 0 for an empty or black reference.
double relativeLuminanceErrorQuantile(const ImageRgba& a, const ImageRgba& reference, double q, const std::vector<uint8_t>* mask = nullptr);
// That error per pixel, signed (positive where `a` is brighter), 0 outside the mask: what
// relativeLuminanceErrorQuantile ranks and dyngi_imgcmp --error-map draws.
std::vector<double> relativeLuminanceErrors(const ImageRgba& a, const ImageRgba& reference, const std::vector<uint8_t>* mask = nullptr);
// Flicker of a sequence of frames of a static scene: the mean absolute frame-to-frame change, relative
// to the frames' mean level (the mean over consecutive pairs of relativeL1(frame i, frame i-1)).
double flicker(const std::vector<ImageRgba>& frames);
// One frame's change under a moving camera: each pixel of `current` that shows a surface (position
// w != 0) is compared with `previous` where its point projects through `previousViewProj` (Vulkan clip
// space, pixel = (ndc / 2 + 1/2) x size, as the temporal reprojection does), interpolated bilinearly
// between pixels that show the same surface (positions within `positionTolerance` of the point); pixels
// that were off screen or hidden are left out. Relative like relativeL1 (previous as the reference); 0
// when nothing matched.
double reprojectedChange(const ImageRgba& current, const ImageRgba& currentPosition, const ImageRgba& previous,
                         const ImageRgba& previousPosition, const glm::mat4& previousViewProj, uint32_t width, uint32_t height,
                         float positionTolerance);
// After a change: the number of frames until every later frame is within `tolerance` (relativeL1) of
// `converged`: 0 when the first frame already is; frames.size() when the sequence never settles.
size_t settleFrames(const std::vector<ImageRgba>& frames, const ImageRgba& converged, double tolerance);
// Mean RGB over the masked pixels.
glm::dvec3 meanOver(const ImageRgba& a, const std::vector<uint8_t>* mask = nullptr);

// The tone map of the GPU pass (tonemap.comp) on the CPU, for images produced on the CPU (path tracer).
std::vector<uint8_t> tonemapToSrgb8(const ImageRgba& hdr, float exposure, int toneMapper);

}  // namespace dyngi::render
