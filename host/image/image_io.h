// Image files: colour output (PNG, BMP, PFM, EXR), the AOV files of docs/outputs.md ("AOV files"),
// and reading any of them back for `vkray compare` and the tests. Every failure (a file that cannot
// be written, an unsupported extension, a truncated or garbage file) is a vkray::Error naming the path.
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "frame/frame.h"
#include "image/image.h"
#include "image/image_meta.h"

namespace vkray {

// Largest image accepted when reading: headers claiming more are rejected as corrupt before any
// allocation (a garbage header must not make us try to allocate terabytes).
inline constexpr int kMaxImageDimension = 32768;
inline constexpr size_t kMaxReadPixels = size_t(1) << 26;  // 64 Mpixel = 768 MiB as float RGB

// Writes the colour image (linear RGB, top row first). The format follows the extension,
// case-insensitively: .png (also when there is no extension), .bmp, .pfm, .exr; anything else is an
// error naming the supported ones.
// PNG/BMP: 8 bits per channel, each value encoded as `encoding` says (image_meta.h: by default
// exposure 0 and the sRGB curve; Encoding::linear() stores round(255 c) of c clamped to [0, 1]); NaN
// is stored as 0. PFM and EXR: the raw linear floats, unclamped (NaN and inf kept), whatever the
// encoding. EXR: 32-bit FLOAT channels R, G, B, ZIP compression, and `meta`'s data window, display
// window and string attributes (other formats ignore `meta`). An image that does not fit in its
// display window is an error.
void writeColorImage(const std::filesystem::path& path, int width, int height,
                     const std::vector<glm::vec3>& rgbTopFirst, const ImageMeta& meta = {},
                     const Encoding& encoding = {});

// Writes any Image (1 or 3 channels) with the same rules as writeColorImage; a 1-channel image
// becomes grey in PNG/BMP, "Pf" in PFM and channel Y in EXR.
void writeImage(const std::filesystem::path& path, const Image& image, const ImageMeta& meta = {},
                const Encoding& encoding = {});

// The PNG bytes writeImage would write for this image with this encoding (1 channel: grey, 3: RGB),
// for embedding without a file (report.html's data URIs). The default here is Encoding::linear():
// the values are taken as display values (colour maps), round(255 c) of c clamped to [0, 1], NaN as
// 0. A vkray::Error for an image whose size or buffer is not valid.
std::vector<unsigned char> encodePng(const Image& image, const Encoding& encoding = Encoding::linear());

// Writes a PFM: "PF" (3 channels) or "Pf" (1 channel), little-endian (scale -1.0), rows bottom to top
// as PFM requires; `topFirst` holds width * height * channels floats, top row first.
void writePfm(const std::filesystem::path& path, int width, int height, int channels, const float* topFirst);

// What a file holds, by its magic bytes (readImageFormat) or by the extension of a name to write
// (imageFormatForPath: the rules of writeColorImage, an error for an unsupported one).
enum class ImageFormat { Png, Bmp, Pfm, Exr };
ImageFormat readImageFormat(const std::filesystem::path& path);
ImageFormat imageFormatForPath(const std::filesystem::path& path);
inline bool isEightBit(ImageFormat f) { return f == ImageFormat::Png || f == ImageFormat::Bmp; }
// "PNG", "BMP", "PFM", "EXR".
const char* formatName(ImageFormat f);

// Reads a PNG or BMP (8- or 16-bit; returns 3 channels, the stored levels / 255 (or / 65535), with
// no transfer function undone: grey is replicated, alpha dropped), a PFM (1 or 3 channels, raw
// floats, either byte order as the sign of the scale says; the scale's magnitude is ignored) or an
// EXR (R, G, B, else Y; HALF or FLOAT read as float). The format is recognised by its magic bytes,
// whatever the extension (EXR: 0x762f3101). The result is top row first. `meta`, when given, gets
// an EXR's display window, data window origin and string attributes; for other formats the image
// itself (display window = its size, origin 0) and no attributes.
Image readImage(const std::filesystem::path& path, ImageMeta* meta = nullptr);
// The same for a file's bytes already in memory (the fuzzer's entry point); errors name `path`.
Image decodeImage(const std::filesystem::path& path, const std::vector<unsigned char>& bytes, ImageMeta* meta = nullptr);

// Throws the vkray::Error that writeColorImage / writeAov would throw for this path's name (an
// unsupported extension, an AOV file that is not .pfm or .exr, a directory that does not exist), so a
// caller can refuse a bad output before spending minutes on a render.
void checkColorImagePath(const std::filesystem::path& path);
void checkAovPath(const std::filesystem::path& path, std::string_view name);

// Throws when `path`, an output named on the command line (`option`: "-o", "OUT"), has no extension
// to choose its format by, naming the extensions accepted: there a missing one is more likely a slip
// than a wish for PNG. (A scene file's `output` name keeps the CSE167 rule: no extension is PNG.)
void checkExtensionGiven(const std::filesystem::path& path, std::string_view option);

// The AOV names writeAov accepts: depth, primid, normal.
const std::vector<std::string_view>& aovNames();

// Writes one AOV of `frame` as a PFM or an EXR (the path must end in .pfm or .exr): depth (1
// channel, t, +inf on a miss; EXR channel Y), primid (1 channel, triangle index as a float, -1 on a
// miss; Y), normal (3 channels, 0 on a miss; R, G, B). `meta` places an EXR as writeImage does. An
// unknown name is a vkray::Error listing the valid ones.
void writeAov(const std::filesystem::path& path, const Frame& frame, std::string_view name,
              const ImageMeta& meta = {});

}  // namespace vkray
