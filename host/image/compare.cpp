// Image difference metrics; the rules (especially for inf and NaN) are documented in compare.h.
#include "image/compare.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"

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

}  // namespace

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
