// Image difference metrics; the rules (especially for inf and NaN) are documented in compare.h.
#include "image/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "core/error.h"
#include "image/tone.h"

namespace vkray {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

void checkComparable(const Image& a, const Image& b, double pixelThreshold) {
    auto describe = [](const Image& im) {
        return std::to_string(im.width) + "x" + std::to_string(im.height) + " with " + std::to_string(im.channels) +
               (im.channels == 1 ? " channel" : " channels");
    };
    if (a.width != b.width || a.height != b.height || a.channels != b.channels)
        throw Error("images differ in size or channels: " + describe(a) + " vs " + describe(b));
    if (a.data.size() != a.pixelCount() * size_t(a.channels) || b.data.size() != a.data.size())
        throw Error("image buffer does not match its size");
    if (!(pixelThreshold >= 0.0)) throw Error("the pixel threshold must be a number >= 0");
}

// Error of one channel value; +inf marks a non-finite mismatch (see compare.h).
double channelError(float x, float y) {
    if (x == y || (std::isnan(x) && std::isnan(y))) return 0.0;
    if (!std::isfinite(x) || !std::isfinite(y)) return kInf;
    return std::abs(double(x) - double(y));
}

// Largest channel error of pixel i.
double pixelError(const Image& a, const Image& b, size_t i) {
    double e = 0.0;
    for (int c = 0; c < a.channels; ++c) {
        const size_t k = i * size_t(a.channels) + size_t(c);
        e = std::max(e, channelError(a.data[k], b.data[k]));
    }
    return e;
}

bool isBad(double pixelErr, double threshold) { return pixelErr > threshold + kThresholdSlack; }

// "[0, 1]", or "[0, 0.5]" at exposure +1: the linear values an 8-bit image at that exposure holds.
std::string heldRange(const Encoding& e) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "[0, %g]", std::exp2(-double(e.exposure)));
    return buf;
}

// What writing `image` as 8-bit levels keeps of its linear values: [0, top], NaN as 0.
void clampToHeld(Image& image, const Encoding& e) {
    const float top = float(std::exp2(-double(e.exposure)));
    for (float& v : image.data) v = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, top);
}

}  // namespace

CompareSpace toCommonSpace(Image& a, ImageFormat formatA, Image& b, ImageFormat formatB, const Encoding& eightBit) {
    const bool eightA = isEightBit(formatA), eightB = isEightBit(formatB);
    const std::string names = std::string("A: ") + formatName(formatA) + ", B: " + formatName(formatB);
    if (eightA && eightB) return {false, false, "8-bit levels as stored (" + names + ")"};
    if (!eightA && !eightB) return {true, false, "linear values as stored (" + names + ")"};
    Image& levels = eightA ? a : b;
    Image& floats = eightA ? b : a;
    levels = decodeLevels(levels, eightBit);
    clampToHeld(floats, eightBit);
    char exposure[64] = "";
    if (eightBit.exposure != 0.0f) std::snprintf(exposure, sizeof exposure, " at exposure %+g", double(eightBit.exposure));
    const std::string decoded = std::string(eightA ? "A: " : "B: ") + (eightBit.srgb ? "sRGB " : "linear ") +
                                formatName(eightA ? formatA : formatB) + exposure + " decoded";
    const std::string clamped = std::string(eightA ? "B: " : "A: ") + formatName(eightA ? formatB : formatA) +
                                " clamped to " + heldRange(eightBit) + " as 8 bits hold it";
    return {true, true, "linear radiance (" + (eightA ? decoded + "; " + clamped : clamped + "; " + decoded) + ")"};
}

CompareStats compareImages(const Image& a, const Image& b, double pixelThreshold) {
    checkComparable(a, b, pixelThreshold);
    CompareStats s;
    s.pixels = int64_t(a.pixelCount());
    double sumSq = 0.0;
    int64_t counted = 0;
    for (size_t i = 0; i < a.pixelCount(); ++i) {
        double pixelErr = 0.0;
        for (int c = 0; c < a.channels; ++c) {
            const size_t k = i * size_t(a.channels) + size_t(c);
            const double e = channelError(a.data[k], b.data[k]);
            if (std::isinf(e)) {
                ++s.nonFiniteMismatches;
            } else {
                sumSq += e * e;
                ++counted;
            }
            pixelErr = std::max(pixelErr, e);
        }
        if (pixelErr > s.maxError) {
            s.maxError = pixelErr;
            s.maxErrorX = int(i % size_t(a.width));
            s.maxErrorY = int(i / size_t(a.width));
        }
        if (isBad(pixelErr, pixelThreshold)) ++s.badPixels;
    }
    s.rmse = counted > 0 ? std::sqrt(sumSq / double(counted)) : 0.0;
    s.psnr = s.rmse > 0.0 ? 20.0 * std::log10(1.0 / s.rmse) : kInf;
    s.badFraction = s.pixels > 0 ? double(s.badPixels) / double(s.pixels) : 0.0;
    return s;
}

Image makeDiffImage(const Image& a, const Image& b, double pixelThreshold) {
    checkComparable(a, b, pixelThreshold);
    std::vector<double> err(a.pixelCount());
    double maxFinite = 0.0;
    for (size_t i = 0; i < err.size(); ++i) {
        err[i] = pixelError(a, b, i);
        if (std::isfinite(err[i])) maxFinite = std::max(maxFinite, err[i]);
    }
    Image out(a.width, a.height, 3);
    for (size_t i = 0; i < err.size(); ++i) {
        float* px = out.data.data() + i * 3;
        const double e = err[i];
        if (e == 0.0) {
            const float* src = a.data.data() + i * size_t(a.channels);
            double luma = a.channels == 3 ? 0.2126 * src[0] + 0.7152 * src[1] + 0.0722 * src[2] : double(src[0]);
            luma = std::isnan(luma) ? 0.0 : std::clamp(luma, 0.0, 1.0);
            px[0] = px[1] = px[2] = float(0.25 * luma);
        } else if (!isBad(e, pixelThreshold)) {
            const double t = pixelThreshold > 0.0 ? std::min(e / pixelThreshold, 1.0) : 1.0;
            px[0] = px[1] = 0.0f;
            px[2] = float(0.4 + 0.6 * t);
        } else {
            const double span = maxFinite - pixelThreshold;
            const double s = !std::isfinite(e) ? 1.0 : span > 0.0 ? std::clamp((e - pixelThreshold) / span, 0.0, 1.0) : 1.0;
            px[0] = 1.0f;
            px[1] = float(s);
            px[2] = 0.0f;
        }
    }
    return out;
}

}  // namespace vkray
