// From linear floats to what a viewer shows: the 8-bit levels of an Encoding (image_meta.h), and
// the normalisation `vkray convert --normalize` applies to data such as a depth AOV.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "image/image.h"
#include "image/image_meta.h"

namespace vkray {

// The 8-bit level of a linear value under an Encoding (see image_meta.h): exposure, then the sRGB
// curve or none, then round(255 v) of v clamped to [0, 1]; NaN is 0.
class LevelEncoder {
public:
    explicit LevelEncoder(const Encoding& encoding);
    // round(255 * encode(2^exposure c)), clamped to [0, 255]; NaN gives 0.
    unsigned char operator()(float c) const {
        const double v = double(c) * scale_;
        if (!(v > 0.0)) return 0;  // also NaN, which fails every comparison
        if (v >= 1.0) return 255;
        unsigned level = bucket_[size_t(v * kBuckets)];
        while (v >= threshold_[level + 1]) ++level;
        return static_cast<unsigned char>(level);
    }
    // The same level from the formula itself: what the tables were built from.
    unsigned char direct(float c) const;

private:
    // A pow per channel value would dominate writing an 8-bit image. Instead the level is looked
    // up: threshold_[k] is the least v whose level is k or more, found by bisection over
    // the doubles with the formula itself; as the formula's levels rise with v, the lookup gives
    // its level exactly (tone_test.cpp checks the floats around every level boundary). bucket_[b]
    // is the level of v = b / kBuckets, from which a step or two reaches v's: sRGB's steepest
    // slope, 12.92 x 255 levels a unit, is under one level a bucket.
    static constexpr size_t kBuckets = 4096;
    unsigned levelOf(double v) const;  // the formula, for v in (0, 1)
    bool srgb_;
    double scale_;  // 2^exposure
    std::array<double, 257> threshold_{};  // [0] = 0, [256] = +inf
    std::array<uint8_t, kBuckets> bucket_{};
};

// sRGB transfer function of IEC 61966-2-1 (linear to encoded), for v in [0, 1], and its inverse.
double srgbEncode(double v);
double srgbDecode(double v);

// The linear values an 8-bit image's levels (read as level / 255) stand for under `encoding`: the
// sRGB curve undone (when srgb), then divided by 2^exposure. The inverse of LevelEncoder within a
// level, for the values it did not clamp. Throws like LevelEncoder for a bad exposure.
Image decodeLevels(const Image& levels, const Encoding& encoding);

// `image` with its finite values mapped linearly from [lowest, highest] (over all channels) to
// [0, 1], and every non-finite value (a depth AOV's misses: +inf) to 0. An image whose finite
// values are all equal maps them to 1; one without finite values is all 0.
Image normalizedForViewing(const Image& image);

}  // namespace vkray
