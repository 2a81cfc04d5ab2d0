// From linear floats to what a viewer shows: the 8-bit levels of an Encoding (image_meta.h), and
// the normalisation `vkray convert --normalize` applies to data such as a depth AOV.
#pragma once

#include "image/image.h"
#include "image/image_meta.h"

namespace vkray {

// The 8-bit level of a linear value under an Encoding (see image_meta.h): exposure, then the sRGB
// curve or none, then round(255 v) of v clamped to [0, 1]; NaN is 0.
class LevelEncoder {
public:
    explicit LevelEncoder(const Encoding& encoding);
    unsigned char operator()(float c) const;

private:
    bool srgb_;
    double scale_;  // 2^exposure
};

// sRGB transfer function of IEC 61966-2-1 (linear to encoded), for v in [0, 1].
double srgbEncode(double v);

// `image` with its finite values mapped linearly from [lowest, highest] (over all channels) to
// [0, 1], and every non-finite value (a depth AOV's misses: +inf) to 0. An image whose finite
// values are all equal maps them to 1; one without finite values is all 0.
Image normalizedForViewing(const Image& image);

}  // namespace vkray
