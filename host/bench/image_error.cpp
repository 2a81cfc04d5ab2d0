#include "bench/image_error.h"

#include <algorithm>
#include <cmath>

#include "image/compare.h"

namespace vkray::bench {

Image colorImage(const Frame& frame) {
    Image img(frame.width, frame.height, 3);
    for (size_t i = 0; i < frame.color.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = frame.color[i][c];
            img.data[i * 3 + size_t(c)] = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
        }
    return img;
}

ImageError imageError(const Frame& frame, const Image& image, const Frame& reference, const Image& refImage) {
    const CompareStats s = compareImages(image, refImage, kDiffThreshold);
    ImageError e;
    e.rmse = s.rmse;
    if (s.rmse > 0.0) e.psnr = s.psnr;
    e.maxError = s.maxError;
    size_t differ = 0;
    const bool both = frame.hasAovs() && reference.hasAovs() && !frame.primId.empty();
    if (both)
        for (size_t i = 0; i < frame.primId.size(); ++i) differ += frame.primId[i] != reference.primId[i];
    e.primaryMismatch = both ? double(differ) / double(frame.primId.size()) : 0.0;
    return e;
}

}  // namespace vkray::bench
