// Image files: colour output (PNG, BMP, PFM), the AOV files of docs/outputs.md ("AOV files"),
// and reading any of them back for `vkray compare` and the tests. Every failure (a file that cannot
// be written, an unsupported extension, a truncated or garbage file) is a vkray::Error naming the path.
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "image/image.h"
#include "render/frame.h"

namespace vkray {

// Largest image accepted when reading: headers claiming more are rejected as corrupt before any
// allocation (a garbage header must not make us try to allocate terabytes).
inline constexpr int kMaxImageDimension = 32768;
inline constexpr size_t kMaxReadPixels = size_t(1) << 26;  // 64 Mpixel = 768 MiB as float RGB

// Writes the colour image (linear RGB, top row first). The format follows the extension,
// case-insensitively: .png (also when there is no extension), .bmp, .pfm; anything else is an error.
// PNG/BMP: each channel clamped to [0, 1] and stored as round(255 c), no gamma (docs/shading.md
// "Output"); NaN is stored as 0. PFM: the raw floats, unclamped (NaN and inf kept, for debugging).
void writeColorImage(const std::filesystem::path& path, int width, int height,
                     const std::vector<glm::vec3>& rgbTopFirst);

// Writes any Image (1 or 3 channels) with the same extension rules as writeColorImage; a 1-channel
// image becomes grey in PNG/BMP and "Pf" in PFM.
void writeImage(const std::filesystem::path& path, const Image& image);

// The PNG bytes writeImage would write for this image (1 channel: grey, 3: RGB; each channel clamped
// to [0, 1] and stored as round(255 c), NaN as 0), for embedding without a file (report.html's data
// URIs). A vkray::Error for an image whose size or buffer is not valid.
std::vector<unsigned char> encodePng(const Image& image);

// Writes a PFM: "PF" (3 channels) or "Pf" (1 channel), little-endian (scale -1.0), rows bottom to top
// as PFM requires; `topFirst` holds width * height * channels floats, top row first.
void writePfm(const std::filesystem::path& path, int width, int height, int channels, const float* topFirst);

// Reads a PNG or BMP (recognised by their magic bytes, whatever the extension; 8- or 16-bit; returns
// 3 channels in [0, 1]: grey is replicated, alpha dropped) or a PFM (1 or 3 channels, raw floats,
// either byte order as the sign of the scale says; the scale's magnitude is ignored). The result is
// top row first.
Image readImage(const std::filesystem::path& path);

// Throws the vkray::Error that writeColorImage / writeAov would throw for this path's name (an
// unsupported extension, an AOV name that is not .pfm, a directory that does not exist), so a
// caller can refuse a bad output before spending minutes on a render.
void checkColorImagePath(const std::filesystem::path& path);
void checkAovPath(const std::filesystem::path& path, std::string_view name);

// The AOV names writeAov accepts: depth, primid, normal.
const std::vector<std::string_view>& aovNames();

// Writes one AOV of `frame` as a PFM (the path must end in .pfm): depth (1 channel, t, +inf on a
// miss), primid (1 channel, triangle index as a float, -1 on a miss), normal (3 channels, 0 on a
// miss). An unknown name is a vkray::Error listing the valid ones.
void writeAov(const std::filesystem::path& path, const Frame& frame, std::string_view name);

}  // namespace vkray
