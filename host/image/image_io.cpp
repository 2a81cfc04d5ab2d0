// Image files: PNG/BMP through stb and EXR through OpenEXR (exr_io.cpp), all encoded and decoded in
// memory, so all file I/O and its error messages are ours; PFM by hand. See image_io.h for the
// contract.
#include "image/image_io.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include <stb_image.h>
#include <stb_image_write.h>

#include "core/error.h"
#include "core/file_output.h"
#include "image/exr_io.h"
#include "image/tone.h"
#include "scene/text_input.h"

namespace fs = std::filesystem;

namespace vkray {
namespace {

// The extensions of imageFormatForPath, for messages.
constexpr const char* kImageExtensions = ".png, .bmp, .pfm, .exr";

std::string lowerExtension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

void checkDirectoryExists(const fs::path& path) {
    const fs::path dir = path.parent_path();
    if (!dir.empty() && !fs::is_directory(dir))
        throw fileError(path, "cannot write: directory " + dir.string() + " does not exist");
}

void checkSize(const fs::path& path, int width, int height, int channels) {
    if (width <= 0 || height <= 0 || (channels != 1 && channels != 3))
        throw fileError(path, "cannot write a " + std::to_string(width) + "x" + std::to_string(height) + " image with " +
                                  std::to_string(channels) + " channels");
}

void appendBytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    const auto* p = static_cast<const unsigned char*>(data);
    out->insert(out->end(), p, p + size);
}

// PNG or BMP bytes of an image whose size checkSize has accepted; empty when stb fails.
std::vector<unsigned char> encode8Bit(ImageFormat format, const Image& image, const Encoding& encoding) {
    std::vector<unsigned char> pixels(image.data.size());
    std::transform(image.data.begin(), image.data.end(), pixels.begin(), LevelEncoder(encoding));
    std::vector<unsigned char> encoded;
    const int ok = format == ImageFormat::Png
                       ? stbi_write_png_to_func(appendBytes, &encoded, image.width, image.height, image.channels,
                                                pixels.data(), image.width * image.channels)
                       : stbi_write_bmp_to_func(appendBytes, &encoded, image.width, image.height, image.channels,
                                                pixels.data());
    if (!ok) encoded.clear();
    return encoded;
}

void write8Bit(const fs::path& path, ImageFormat format, const Image& image, const Encoding& encoding) {
    const std::vector<unsigned char> encoded = encode8Bit(format, image, encoding);
    if (encoded.empty()) throw fileError(path, "cannot encode the image");
    writeFileBytes(path, encoded.data(), encoded.size());
}

uint32_t byteSwap(uint32_t v) {
    return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

// ---- Reading ----------------------------------------------------------------------------------

// The largest file the largest image we accept could need (+ EXR offsets); well below INT_MAX, what
// stb_image's lengths are.
constexpr size_t kMaxFileBytes = kMaxReadPixels * 3 * sizeof(float) + (size_t(1) << 20);
const char* const kTooLarge = "file too large to be an image we accept";

// Whole file into memory, refusing anything bigger than kMaxFileBytes.
std::vector<unsigned char> readBytes(const fs::path& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw fileError(path, "cannot read: is a directory");
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw fileError(path, std::string("cannot open: ") + std::strerror(errno));
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> closer(f, std::fclose);
    std::vector<unsigned char> bytes;
    unsigned char chunk[1 << 16];
    size_t n;
    while ((n = std::fread(chunk, 1, sizeof chunk, f)) > 0) {
        if (bytes.size() + n > kMaxFileBytes) throw fileError(path, kTooLarge);
        bytes.insert(bytes.end(), chunk, chunk + n);
    }
    if (std::ferror(f)) throw fileError(path, std::string("read failed: ") + std::strerror(errno));
    return bytes;
}

void checkDimensions(const fs::path& path, long long width, long long height) {
    if (width <= 0 || height <= 0 || width > kMaxImageDimension || height > kMaxImageDimension ||
        size_t(width) * size_t(height) > kMaxReadPixels)
        throw fileError(path, "implausible image size " + std::to_string(width) + "x" + std::to_string(height) +
                                  " (corrupt header?)");
}

uint32_t le32(const unsigned char* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24; }
uint16_t le16(const unsigned char* p) { return uint16_t(p[0] | p[1] << 8); }

// stb reads past the end of a truncated BMP as zeros and returns a partly black image without a
// word, so check that the pixel array the header describes is all there (uncompressed BMPs; stb
// rejects the RLE kinds itself).
void checkBmpLength(const fs::path& path, const std::vector<unsigned char>& bytes) {
    const unsigned char* b = bytes.data();
    if (bytes.size() < 26) throw fileError(path, "truncated BMP header");
    const uint32_t pixelOffset = le32(b + 10), infoSize = le32(b + 14);
    long long width, height;
    uint32_t bpp, compression = 0;
    if (infoSize == 12) {  // BITMAPCOREHEADER
        width = le16(b + 18);
        height = int16_t(le16(b + 20));
        bpp = le16(b + 24);
    } else {
        if (bytes.size() < 34) throw fileError(path, "truncated BMP header");
        width = int32_t(le32(b + 18));
        height = int32_t(le32(b + 22));
        bpp = le16(b + 28);
        compression = le32(b + 30);
    }
    if (compression != 0 && compression != 3 && compression != 6) return;  // 3, 6: bit fields
    checkDimensions(path, width, height < 0 ? -height : height);          // height < 0: top-down rows
    const uint64_t rowBytes = (uint64_t(width) * bpp + 31) / 32 * 4;
    const uint64_t needed = uint64_t(pixelOffset) + rowBytes * uint64_t(height < 0 ? -height : height);
    if (bytes.size() < needed)
        throw fileError(path, "truncated BMP: " + std::to_string(needed) + " bytes expected, " +
                                  std::to_string(bytes.size()) + " found");
}

// stb's reason for the last failure, one line: some reasons quote the file's bytes ("XXXX PNG chunk
// not known" with the chunk's type).
std::string stbFailure() {
    const char* reason = stbi_failure_reason();
    return reason ? escapedControls(reason) : "no reason given";
}

Image decodeWithStb(const fs::path& path, const std::vector<unsigned char>& bytes) {
    const auto* buf = bytes.data();
    const int len = int(bytes.size());  // at most kMaxFileBytes
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(buf, len, &w, &h, &comp))
        throw fileError(path, "cannot decode: " + stbFailure());
    checkDimensions(path, w, h);  // before stb allocates anything for the pixels
    Image image;
    if (stbi_is_16_bit_from_memory(buf, len)) {
        std::unique_ptr<stbi_us, void (*)(void*)> px(stbi_load_16_from_memory(buf, len, &w, &h, &comp, 3),
                                                     stbi_image_free);
        if (!px) throw fileError(path, "cannot decode: " + stbFailure());
        image = Image(w, h, 3);
        for (size_t i = 0; i < image.data.size(); ++i) image.data[i] = float(px.get()[i]) / 65535.0f;
    } else {
        std::unique_ptr<stbi_uc, void (*)(void*)> px(stbi_load_from_memory(buf, len, &w, &h, &comp, 3),
                                                     stbi_image_free);
        if (!px) throw fileError(path, "cannot decode: " + stbFailure());
        image = Image(w, h, 3);
        for (size_t i = 0; i < image.data.size(); ++i) image.data[i] = float(px.get()[i]) / 255.0f;
    }
    return image;
}

bool isSpace(unsigned char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

// PFM header: "PF"|"Pf", whitespace, width, whitespace, height, whitespace, scale, exactly one
// whitespace byte, then the pixels: rows bottom to top, little-endian when scale < 0.
Image decodePfm(const fs::path& path, const std::vector<unsigned char>& bytes) {
    const int channels = bytes[1] == 'F' ? 3 : 1;
    size_t pos = 2;
    auto token = [&](const char* what) {
        const size_t start = pos;
        while (pos < bytes.size() && isSpace(bytes[pos])) ++pos;
        if (pos == start) throw fileError(path, std::string("bad PFM header: expected whitespace before the ") + what);
        const size_t begin = pos;
        while (pos < bytes.size() && !isSpace(bytes[pos]) && pos - begin < 32) ++pos;
        if (pos == bytes.size() || pos == begin || !isSpace(bytes[pos]))
            throw fileError(path, std::string("bad PFM header: cannot read the ") + what);
        return std::string(bytes.begin() + std::ptrdiff_t(begin), bytes.begin() + std::ptrdiff_t(pos));
    };
    auto integer = [&](const char* what) {
        const std::string s = token(what);
        long long v = 0;
        const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        if (ec != std::errc() || end != s.data() + s.size())
            throw fileError(path, std::string("bad PFM header: ") + what + " '" + s + "' is not an integer");
        return v;
    };
    const long long width = integer("width");
    const long long height = integer("height");
    checkDimensions(path, width, height);
    const std::string scaleText = token("scale");
    double scale = 0.0;
    const auto [end, ec] = std::from_chars(scaleText.data(), scaleText.data() + scaleText.size(), scale);
    if (ec != std::errc() || end != scaleText.data() + scaleText.size() || !std::isfinite(scale) || scale == 0.0)
        throw fileError(path, "bad PFM header: scale '" + scaleText + "' is not a non-zero number");
    ++pos;  // the single whitespace byte that ends the header

    Image image(int(width), int(height), channels);
    const size_t expected = image.data.size() * sizeof(float);
    const size_t found = bytes.size() - pos;
    if (found < expected)
        throw fileError(path, "truncated PFM: " + std::to_string(expected) + " bytes of pixels expected, " +
                                  std::to_string(found) + " found");
    if (found > expected)
        throw fileError(path, std::to_string(found - expected) +
                                  " bytes after the pixels (wrong size in the PFM header?)");
    const bool fileLittle = scale < 0.0;
    const bool swap = fileLittle != (std::endian::native == std::endian::little);
    const size_t rowFloats = size_t(width) * size_t(channels);
    for (int fileRow = 0; fileRow < height; ++fileRow) {
        const unsigned char* src = bytes.data() + pos + size_t(fileRow) * rowFloats * sizeof(float);
        float* dst = image.data.data() + size_t(height - 1 - fileRow) * rowFloats;
        for (size_t k = 0; k < rowFloats; ++k) {
            uint32_t bits;
            std::memcpy(&bits, src + k * sizeof(float), sizeof bits);
            if (swap) bits = byteSwap(bits);
            std::memcpy(dst + k, &bits, sizeof bits);
        }
    }
    return image;
}

// The format of a file from its first bytes (8 are enough); an error for anything else.
ImageFormat sniffFormat(const fs::path& path, const std::vector<unsigned char>& bytes) {
    static const unsigned char kPngMagic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (bytes.empty()) throw fileError(path, "empty file");
    if (bytes.size() >= 3 && bytes[0] == 'P' && (bytes[1] == 'F' || bytes[1] == 'f') && isSpace(bytes[2]))
        return ImageFormat::Pfm;
    if (bytes.size() >= 8 && std::memcmp(bytes.data(), kPngMagic, 8) == 0) return ImageFormat::Png;
    if (bytes.size() >= 2 && bytes[0] == 'B' && bytes[1] == 'M') return ImageFormat::Bmp;
    if (hasExrMagic(bytes)) return ImageFormat::Exr;
    throw fileError(path, "not a PNG, BMP, PFM or EXR file");
}

}  // namespace

void writePfm(const fs::path& path, int width, int height, int channels, const float* topFirst) {
    checkSize(path, width, height, channels);
    const std::string header =
        std::string(channels == 3 ? "PF" : "Pf") + "\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
    const size_t rowFloats = size_t(width) * size_t(channels);
    std::vector<unsigned char> bytes(header.begin(), header.end());
    bytes.resize(header.size() + rowFloats * size_t(height) * sizeof(float));
    unsigned char* out = bytes.data() + header.size();
    for (int row = height - 1; row >= 0; --row) {  // PFM stores the bottom row first
        const float* src = topFirst + size_t(row) * rowFloats;
        for (size_t k = 0; k < rowFloats; ++k, out += sizeof(float)) {
            uint32_t bits;
            std::memcpy(&bits, src + k, sizeof bits);
            if constexpr (std::endian::native != std::endian::little) bits = byteSwap(bits);
            std::memcpy(out, &bits, sizeof bits);
        }
    }
    writeFileBytes(path, bytes.data(), bytes.size());
}

void writeImage(const fs::path& path, const Image& image, const ImageMeta& meta, const Encoding& encoding) {
    const ImageFormat format = imageFormatForPath(path);
    checkSize(path, image.width, image.height, image.channels);
    if (image.data.size() != image.pixelCount() * size_t(image.channels))
        throw fileError(path, "image buffer does not match its size");
    if (format == ImageFormat::Pfm) {
        writePfm(path, image.width, image.height, image.channels, image.data.data());
    } else if (format == ImageFormat::Exr) {
        const std::vector<unsigned char> bytes = encodeExr(path, image, meta);
        writeFileBytes(path, bytes.data(), bytes.size());
    } else {
        write8Bit(path, format, image, encoding);
    }
}

std::vector<unsigned char> encodePng(const Image& image, const Encoding& encoding) {
    auto describe = [&] { return std::to_string(image.width) + "x" + std::to_string(image.height) + " image with " +
                                 std::to_string(image.channels) + " channels"; };
    if (image.width <= 0 || image.height <= 0 || (image.channels != 1 && image.channels != 3))
        throw Error("cannot encode a " + describe() + " as PNG");
    if (image.data.size() != image.pixelCount() * size_t(image.channels))
        throw Error("cannot encode a " + describe() + " as PNG: its buffer does not match its size");
    std::vector<unsigned char> encoded = encode8Bit(ImageFormat::Png, image, encoding);
    if (encoded.empty()) throw Error("cannot encode a " + describe() + " as PNG");
    return encoded;
}

void writeColorImage(const fs::path& path, int width, int height, const std::vector<glm::vec3>& rgbTopFirst,
                     const ImageMeta& meta, const Encoding& encoding) {
    checkSize(path, width, height, 3);
    if (rgbTopFirst.size() != size_t(width) * size_t(height))
        throw fileError(path, "colour buffer holds " + std::to_string(rgbTopFirst.size()) + " pixels, not " +
                                  std::to_string(width) + "x" + std::to_string(height));
    Image image(width, height, 3);
    for (size_t i = 0; i < rgbTopFirst.size(); ++i)
        for (int c = 0; c < 3; ++c) image.data[i * 3 + size_t(c)] = rgbTopFirst[i][c];
    writeImage(path, image, meta, encoding);
}

const char* formatName(ImageFormat f) {
    switch (f) {
    case ImageFormat::Png: return "PNG";
    case ImageFormat::Bmp: return "BMP";
    case ImageFormat::Pfm: return "PFM";
    case ImageFormat::Exr: return "EXR";
    }
    return "?";
}

ImageFormat imageFormatForPath(const fs::path& path) {
    const std::string ext = lowerExtension(path);
    if (ext.empty() || ext == ".png") return ImageFormat::Png;
    if (ext == ".bmp") return ImageFormat::Bmp;
    if (ext == ".pfm") return ImageFormat::Pfm;
    if (ext == ".exr") return ImageFormat::Exr;
    throw fileError(path, "unsupported image file extension '" + path.extension().string() + "' (supported: " +
                              kImageExtensions + ")");
}

void checkExtensionGiven(const fs::path& path, std::string_view option) {
    if (!path.has_extension())
        throw Error(std::string(option) + " " + path.string() + ": no file extension to choose the format by (give " +
                    kImageExtensions + ")");
}

ImageFormat readImageFormat(const fs::path& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw fileError(path, "cannot read: is a directory");
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw fileError(path, std::string("cannot open: ") + std::strerror(errno));
    std::vector<unsigned char> head(8);
    head.resize(std::fread(head.data(), 1, head.size(), f));
    std::fclose(f);
    return sniffFormat(path, head);
}

Image readImage(const fs::path& path, ImageMeta* meta) { return decodeImage(path, readBytes(path), meta); }

Image decodeImage(const fs::path& path, const std::vector<unsigned char>& bytes, ImageMeta* meta) {
    if (bytes.size() > kMaxFileBytes) throw fileError(path, kTooLarge);
    const ImageFormat format = sniffFormat(path, bytes);
    if (format == ImageFormat::Exr) return decodeExr(path, bytes, meta);
    if (format == ImageFormat::Bmp) checkBmpLength(path, bytes);
    Image image = format == ImageFormat::Pfm ? decodePfm(path, bytes) : decodeWithStb(path, bytes);
    if (meta) *meta = ImageMeta{image.width, image.height, 0, 0, {}};
    return image;
}

const std::vector<std::string_view>& aovNames() {
    static const std::vector<std::string_view> names{"depth", "primid", "normal"};
    return names;
}

void checkColorImagePath(const fs::path& path) {
    imageFormatForPath(path);
    checkDirectoryExists(path);
}

void checkAovPath(const fs::path& path, std::string_view name) {
    if (std::find(aovNames().begin(), aovNames().end(), name) == aovNames().end())
        throw Error("unknown AOV '" + std::string(name) + "' (valid: depth, primid, normal)");
    // AOVs carry +inf and -1, which no 8-bit format can hold: insist on a float format.
    const std::string ext = lowerExtension(path);
    if (ext != ".pfm" && ext != ".exr")
        throw fileError(path, "AOV files are PFM or EXR: the name must end in .pfm or .exr");
    checkDirectoryExists(path);
}

void writeAov(const fs::path& path, const Frame& frame, std::string_view name, const ImageMeta& meta) {
    checkAovPath(path, name);
    const size_t n = size_t(frame.width) * size_t(frame.height);
    auto missing = [&] { return fileError(path, "the frame has no " + std::string(name) + " AOV of its size"); };
    const int channels = name == "normal" ? 3 : 1;
    checkSize(path, frame.width, frame.height, channels);
    Image image(frame.width, frame.height, channels);
    if (name == "depth") {
        if (frame.depth.size() != n) throw missing();
        image.data = frame.depth;
    } else if (name == "primid") {
        if (frame.primId.size() != n) throw missing();
        std::transform(frame.primId.begin(), frame.primId.end(), image.data.begin(), [](int32_t id) { return float(id); });
    } else {
        if (frame.normal.size() != n) throw missing();
        for (size_t i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) image.data[i * 3 + size_t(c)] = frame.normal[i][c];
    }
    writeImage(path, image, meta);
}

}  // namespace vkray
