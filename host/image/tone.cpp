// Linear floats to display values. See tone.h and image_meta.h.
#include "image/tone.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "core/error.h"

namespace vkray {
namespace {

bool isExposure(double stops) { return std::isfinite(stops) && std::fabs(stops) <= double(kMaxExposureStops); }

void checkExposure(float exposure) {
    if (!isExposure(exposure))
        throw Error("exposure " + std::to_string(exposure) + " is not a number of stops within +-" +
                    std::to_string(int(kMaxExposureStops)));
}

}  // namespace

Encoding parseEncoding(std::string_view name, double exposure) {
    Encoding e;
    if (name == "srgb")
        e.srgb = true;
    else if (name == "linear")
        e.srgb = false;
    else
        throw Error("--encoding '" + std::string(name) + "': expected srgb or linear");
    if (!isExposure(exposure)) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%g", exposure);
        throw Error(std::string("--exposure ") + buf + ": must be a number of stops within +-" +
                    std::to_string(int(kMaxExposureStops)));
    }
    e.exposure = float(exposure);
    return e;
}

double srgbEncode(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055; }

double srgbDecode(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

Image decodeLevels(const Image& levels, const Encoding& encoding) {
    checkExposure(encoding.exposure);
    const double scale = std::exp2(-double(encoding.exposure));
    Image out = levels;
    for (float& v : out.data) v = float((encoding.srgb ? srgbDecode(double(v)) : double(v)) * scale);
    return out;
}

LevelEncoder::LevelEncoder(const Encoding& encoding)
    : srgb_(encoding.srgb), scale_(std::exp2(double(encoding.exposure))) {
    checkExposure(encoding.exposure);
    // Positive doubles order as their bit patterns: bisect on those, between +0 (level 0) and 1
    // (level 255), for the least double of level k or more.
    threshold_[0] = 0.0;
    for (unsigned k = 1; k < 256; ++k) {
        uint64_t lo = 0, hi = std::bit_cast<uint64_t>(1.0);  // levelOf(lo) < k <= levelOf(hi)
        while (hi - lo > 1) {
            const uint64_t mid = lo + (hi - lo) / 2;
            (levelOf(std::bit_cast<double>(mid)) >= k ? hi : lo) = mid;
        }
        threshold_[k] = std::bit_cast<double>(hi);
    }
    threshold_[256] = std::numeric_limits<double>::infinity();
    unsigned level = 0;
    for (size_t b = 0; b < kBuckets; ++b) {
        const double v = double(b) / double(kBuckets);
        while (v >= threshold_[level + 1]) ++level;
        bucket_[b] = uint8_t(level);
    }
}

unsigned LevelEncoder::levelOf(double v) const {
    return unsigned(std::lround(255.0 * (srgb_ ? srgbEncode(v) : v)));
}

unsigned char LevelEncoder::direct(float c) const {
    const double v = double(c) * scale_;
    if (!(v > 0.0)) return 0;
    if (v >= 1.0) return 255;
    return static_cast<unsigned char>(levelOf(v));
}

Image normalizedForViewing(const Image& image) {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (float v : image.data)
        if (std::isfinite(v)) {
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    Image out = image;
    for (float& v : out.data) {
        if (!std::isfinite(v))
            v = 0.0f;
        else
            v = hi > lo ? float((double(v) - lo) / (double(hi) - lo)) : 1.0f;
    }
    return out;
}

}  // namespace vkray
