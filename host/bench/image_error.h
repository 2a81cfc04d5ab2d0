// The error of a bench render against the double-precision CPU reference: the image figures of
// `vkray compare` (image/compare.h) on the colour as the PNG stores it, and the share of pixels whose
// primary hit is another triangle.
#pragma once

#include "bench/bench_results.h"
#include "frame/frame.h"
#include "image/image.h"

namespace vkray::bench {

// Differences within this many 8-bit levels are what float vs double rounding gives
// (tests/golden): the difference images show them blue, beyond it red.
inline constexpr double kDiffThreshold = 2.0 / 255.0;

// The colour of a frame as the PNG stores it: clamped to [0, 1], NaN as 0.
Image colorImage(const Frame& frame);

// `frame` (whose colorImage() is `image`) against `reference` (whose colorImage() is `refImage`);
// the primary-hit mismatch needs both frames' AOVs and is 0 without them.
ImageError imageError(const Frame& frame, const Image& image, const Frame& reference, const Image& refImage);

}  // namespace vkray::bench
