// What an image file carries besides its pixels: where the image lies in a larger one and what
// produced it (ImageMeta, kept by EXR only), and how linear radiance becomes the 8-bit levels of a
// PNG or BMP (Encoding; HDR files, EXR and PFM, always hold the raw linear floats).
#pragma once

#include <map>
#include <string>
#include <string_view>

namespace vkray {

// Where an image lies in a larger one and what produced it: the EXR data window (x0,y0 of this
// image inside a display window of displayWidth x displayHeight; 0 = the image itself) and string
// attributes (stored as EXR string attributes; other formats ignore both).
struct ImageMeta {
    int displayWidth = 0, displayHeight = 0;  // 0: same as the image
    int x0 = 0, y0 = 0;                       // the image's top-left pixel in the display window
    std::map<std::string, std::string> attributes;
};

// How a linear value c becomes an 8-bit level when quantised (PNG, BMP): v = c * 2^exposure, then
// with `srgb` the sRGB transfer function of IEC 61966-2-1 (12.92 v up to 0.0031308, else
// 1.055 v^(1/2.4) - 0.055), then round(255 v) of v clamped to [0, 1]; NaN becomes 0. `linear` (srgb
// false, exposure 0) stores round(255 c), the levels the CSE167 reference images hold. EXR and PFM
// ignore the encoding: they keep the raw linear floats.
struct Encoding {
    bool srgb = true;
    float exposure = 0.0f;  // stops: the colour is multiplied by 2^exposure before encoding

    static Encoding linear() { return Encoding{false, 0.0f}; }
};

// The largest |exposure| accepted: 2^64 already maps every finite radiance to black or white.
inline constexpr float kMaxExposureStops = 64.0f;

// An Encoding from the command line's words: `name` "srgb" or "linear", `exposure` in stops within
// +-kMaxExposureStops. Throws a one-line vkray::Error naming the flag (--encoding, --exposure).
Encoding parseEncoding(std::string_view name, double exposure);

}  // namespace vkray
