// The perceptual colormap of report.html's traversal-cost heatmaps (nodes visited per pixel):
// viridis (van der Walt and Smith, matplotlib 2.0), perceptually uniform, readable in grey and by
// most colour-blind readers, so "twice as bright" reads as "about twice the cost".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image/image.h"

namespace vkray::bench {

// A display colour, each channel in [0, 1] (sRGB-encoded: what the screen shows).
struct DisplayColor {
    float r = 0.0f, g = 0.0f, b = 0.0f;
};

// The colour of t in [0, 1] (0: dark violet, 1: yellow); t outside is clamped, NaN is 0.
DisplayColor viridis(double t);

// "#rrggbb", for SVG and CSS.
std::string cssColor(DisplayColor c);

// One pixel per value (top row first), coloured by viridis(value / maxValue): values at or above
// maxValue share the top colour, so a few outlier pixels cannot wash out the rest. A maxValue that
// is not positive maps 0 to the bottom colour and everything else to the top. The channels hold the
// display colour as is: the report stores them with Encoding::linear() (round(255 c), no transfer
// curve; image_meta.h), so the file shows exactly the colormap's colours. Throws vkray::Error when values.size() != w * h.
Image heatmapImage(const std::vector<uint32_t>& values, int w, int h, double maxValue);

}  // namespace vkray::bench
