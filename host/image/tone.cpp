// Linear floats to display values. See tone.h and image_meta.h.
#include "image/tone.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "core/error.h"

namespace vkray {

Encoding parseEncoding(std::string_view name, double exposure) {
    Encoding e;
    if (name == "srgb")
        e.srgb = true;
    else if (name == "linear")
        e.srgb = false;
    else
        throw Error("--encoding '" + std::string(name) + "': expected srgb or linear");
    if (!std::isfinite(exposure) || std::fabs(exposure) > double(kMaxExposureStops)) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%g", exposure);
        throw Error(std::string("--exposure ") + buf + ": must be a number of stops within +-" +
                    std::to_string(int(kMaxExposureStops)));
    }
    e.exposure = float(exposure);
    return e;
}

double srgbEncode(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055; }

LevelEncoder::LevelEncoder(const Encoding& encoding)
    : srgb_(encoding.srgb), scale_(std::exp2(double(encoding.exposure))) {
    if (!std::isfinite(encoding.exposure) || std::fabs(encoding.exposure) > kMaxExposureStops)
        throw Error("exposure " + std::to_string(encoding.exposure) + " is not a number of stops within +-" +
                    std::to_string(int(kMaxExposureStops)));
}

unsigned char LevelEncoder::operator()(float c) const {
    double v = double(c) * scale_;
    if (!(v > 0.0)) return 0;  // also NaN, which fails every comparison
    if (v >= 1.0) return 255;
    if (srgb_) v = srgbEncode(v);
    return static_cast<unsigned char>(std::lround(255.0 * v));
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
