// Putting an image together from tiles: EXR files each holding part of one image (its data window
// inside a shared display window, ImageMeta), as `vkray render --crop/--tile` writes them on the
// nodes of a cluster. `vkray assemble` is this and a write.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "image/image.h"
#include "image/image_meta.h"

namespace vkray {

// The attribute naming a tile of a regular split: "I/N", tile I (0..N-1) of N. It alone may differ
// between the tiles of one image; every other attribute (vkray:version, vkray:scene, ...) must match.
inline constexpr const char* kTileAttribute = "vkray:tile";

struct ImageTile {
    std::filesystem::path path;  // named in every error
    Image image;
    ImageMeta meta;              // as readImage fills it
};

struct AssembledImage {
    Image image;    // displayWidth x displayHeight
    ImageMeta meta; // the display window, origin 0, the tiles' attributes except kTileAttribute
};

// Checks that the tiles make up one image exactly and returns it; else a one-line vkray::Error naming
// what is wrong: channel counts, display windows or an attribute that differ (the attribute, both
// values, both files), a data window outside the display window, a pixel covered twice (both files
// and the pixel), pixels covered by no tile (with kTileAttribute on the tiles: "missing tiles 1, 3
// of 4", tiles numbered from 0; else how many pixels and their box). Pixels are copied bit for bit.
AssembledImage assembleTiles(const std::vector<ImageTile>& tiles);

// Reads every file (each must be an EXR: a display window is what places it) and assembles them.
AssembledImage assembleTileFiles(const std::vector<std::filesystem::path>& paths);

}  // namespace vkray
