// OpenEXR files for image_io.cpp: encoding and decoding in memory (all file I/O and its error
// messages stay image_io's). 32-bit FLOAT channels, ZIP compression; R, G, B for colour, Y for one
// channel; the data window and display window of ImageMeta, its attributes as string attributes.
#pragma once

#include <filesystem>
#include <vector>

#include "image/image.h"
#include "image/image_meta.h"

namespace vkray {

// The first four bytes of every OpenEXR file: 0x762f3101, little-endian.
bool hasExrMagic(const std::vector<unsigned char>& bytes);

// The bytes of an EXR file holding `image` (1 or 3 channels, already checked) placed by `meta`. A
// data window outside the display window, or an attribute whose name a standard EXR attribute
// uses, is a vkray::Error naming `path`.
std::vector<unsigned char> encodeExr(const std::filesystem::path& path, const Image& image, const ImageMeta& meta);

// Decodes an EXR file (scan lines or tiles, any compression, HALF, FLOAT or UINT channels read as
// float): R, G, B when it has them, else Y. Fills `meta` (when not null) with the display window's
// size, the data window's origin within it and the string attributes. Errors name `path`.
Image decodeExr(const std::filesystem::path& path, const std::vector<unsigned char>& bytes, ImageMeta* meta);

}  // namespace vkray
