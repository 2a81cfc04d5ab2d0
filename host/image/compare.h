// Image difference metrics for `vkray compare` and for tests that check one renderer against another.
//
// Values are compared as stored in Image (toCommonSpace below brings two files into one space first):
// PNG/BMP in [0, 1] units, PFM raw (so for depth AOVs the errors are in scene units). Per channel,
// err = |a - b|, with these rules for non-finite values (AOVs hold +inf for a miss, and a broken
// shader may leave NaN):
//   - both values identical (the same infinity, or both NaN): err = 0, like any equal pair;
//   - otherwise, if either is non-finite (inf vs finite, +inf vs -inf, NaN vs a number): a
//     "non-finite mismatch". Its pixel is bad, maxError becomes +inf, and it is left out of the RMSE
//     (which would otherwise be inf and say nothing about the rest of the image); it is counted in
//     nonFiniteMismatches so it cannot go unnoticed.
#pragma once

#include <cstdint>
#include <string>

#include "image/image.h"
#include "image/image_io.h"
#include "image/image_meta.h"

namespace vkray {

// Slack added to the per-pixel threshold: 8-bit levels read back as float(k / 255) differ from the
// exact fractions by ~1e-8, so without it "differs by more than 2/255" would flip on rounding.
inline constexpr double kThresholdSlack = 1e-6;

struct CompareStats {
    double rmse = 0.0;      // sqrt(mean err^2) over all channel values except non-finite mismatches
    double psnr = 0.0;      // 20 log10(1 / rmse), peak value 1; +inf when rmse == 0
    double maxError = 0.0;  // largest err of any channel; +inf when there is a non-finite mismatch
    int maxErrorX = -1, maxErrorY = -1;  // pixel of maxError (column, row from the top); -1 when 0
    double badFraction = 0.0;            // badPixels / pixels
    int64_t badPixels = 0;               // pixels where some channel has err > threshold + kThresholdSlack
                                         // or a non-finite mismatch
    int64_t pixels = 0;
    int64_t nonFiniteMismatches = 0;     // channel values, not pixels
};

// How `vkray compare` puts two image files in one space before comparing them (docs/outputs.md,
// "Comparing images"):
//  - both 8-bit (PNG, BMP): their levels / 255 as stored, whatever encoding wrote them;
//  - both float (PFM, EXR): their raw values (linear radiance, or an AOV's data);
//  - one of each: linear radiance. The 8-bit image's levels are decoded with `eightBit` (decodeLevels,
//    tone.h): the file alone does not say whether it was written with the sRGB curve or without, nor
//    at which exposure. The float image is clamped to what the 8-bit one can hold, [0, 2^-exposure],
//    NaN as 0, as writing it as 8-bit would have done; so a PNG and the EXR of one render agree to
//    within the PNG's quantisation.
struct CompareSpace {
    bool linear = false;      // true: linear radiance (a float file is involved); false: 8-bit levels
    bool decoded = false;     // an 8-bit image was decoded with the encoding
    std::string description;  // "linear radiance (A: sRGB PNG decoded; B: EXR clamped to [0, 1])"
};

// Brings `a` and `b`, read from files of these formats, into the space above (in place) and says which.
CompareSpace toCommonSpace(Image& a, ImageFormat formatA, Image& b, ImageFormat formatB, const Encoding& eightBit);

// Throws vkray::Error when the sizes or channel counts differ. pixelThreshold >= 0.
CompareStats compareImages(const Image& a, const Image& b, double pixelThreshold);

// A 3-channel picture of where a and b differ, values in [0, 1] (write it as PNG):
//   - equal pixels:                      grey, 0.25 * the luminance of a (clamped to [0, 1]), so the
//                                        scene stays recognisable but dim;
//   - 0 < err <= threshold (tolerated):  blue, 0.4 + 0.6 * err / threshold;
//   - bad (err > threshold, or a non-finite mismatch): red (1, s, 0) with s rising from 0 just over
//     the threshold to 1 (yellow) at the largest finite error of the image; non-finite mismatches are
//     yellow.
// err here is the pixel's largest channel error. Throws like compareImages.
Image makeDiffImage(const Image& a, const Image& b, double pixelThreshold);

}  // namespace vkray
