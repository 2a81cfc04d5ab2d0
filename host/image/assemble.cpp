// Assembling an image from EXR tiles. See assemble.h for the contract.
#include "image/assemble.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <optional>
#include <set>

#include "core/error.h"
#include "image/image_io.h"
#include "scene/text_input.h"

namespace fs = std::filesystem;

namespace vkray {
namespace {

std::string size(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

Error cannot(const std::string& why) { return Error("cannot assemble: " + why); }

// Same channels, display window and attributes (but kTileAttribute) as the first tile.
void checkMatches(const ImageTile& first, const ImageTile& t) {
    const std::string a = first.path.string(), b = t.path.string();
    if (t.image.channels != first.image.channels)
        throw cannot(a + " has " + std::to_string(first.image.channels) + " channel(s), " + b + " has " +
                     std::to_string(t.image.channels));
    if (t.meta.displayWidth != first.meta.displayWidth || t.meta.displayHeight != first.meta.displayHeight)
        throw cannot("display windows differ: " + size(first.meta.displayWidth, first.meta.displayHeight) + " in " +
                     a + ", " + size(t.meta.displayWidth, t.meta.displayHeight) + " in " + b);
    std::set<std::string> names;
    for (const auto& [k, v] : first.meta.attributes) names.insert(k);
    for (const auto& [k, v] : t.meta.attributes) names.insert(k);
    for (const std::string& name : names) {
        if (name == kTileAttribute) continue;
        const auto x = first.meta.attributes.find(name), y = t.meta.attributes.find(name);
        auto show = [](const std::map<std::string, std::string>& m, std::map<std::string, std::string>::const_iterator it,
                       const std::string& file) {
            return it == m.end() ? "missing in " + file : "'" + it->second + "' in " + file;
        };
        if (x == first.meta.attributes.end() || y == t.meta.attributes.end() || x->second != y->second)
            throw cannot("attribute " + name + " differs: " + show(first.meta.attributes, x, a) + ", " +
                         show(t.meta.attributes, y, b));
    }
}

void checkInside(const ImageTile& t) {
    const ImageMeta& m = t.meta;
    if (m.x0 < 0 || m.y0 < 0 || int64_t(m.x0) + t.image.width > m.displayWidth ||
        int64_t(m.y0) + t.image.height > m.displayHeight)
        throw cannot(t.path.string() + ": its " + size(t.image.width, t.image.height) + " data window at (" +
                     std::to_string(m.x0) + ", " + std::to_string(m.y0) + ") lies outside the " +
                     size(m.displayWidth, m.displayHeight) + " display window");
}

// I and N of a tile's kTileAttribute "I/N" (0 <= I < N); nothing when it has none.
std::optional<std::pair<int, int>> tileIndex(const ImageTile& t) {
    const auto it = t.meta.attributes.find(kTileAttribute);
    if (it == t.meta.attributes.end()) return std::nullopt;
    const std::optional<IndexOfCount> p = parseIndexOfCount(it->second);
    if (!p || p->index >= p->count)
        throw cannot(t.path.string() + ": attribute " + kTileAttribute + " '" + it->second +
                     "' is not I/N with 0 <= I < N");
    return std::pair{p->index, p->count};
}

// The error for pixels no tile covers: the missing tile numbers when every tile names its own.
Error uncovered(const std::vector<ImageTile>& tiles, const std::vector<int32_t>& owner, int w, int h) {
    std::set<int> present;
    int count = -1;
    bool numbered = true;
    for (const ImageTile& t : tiles) {
        const auto idx = tileIndex(t);
        if (!idx) {
            numbered = false;
            continue;
        }
        if (count >= 0 && idx->second != count)
            throw cannot(std::string(kTileAttribute) + " counts differ: " + tiles.front().path.string() + " is of " +
                         std::to_string(count) + ", " + t.path.string() + " of " + std::to_string(idx->second));
        count = idx->second;
        present.insert(idx->first);
    }
    if (numbered && count > 0 && int(present.size()) < count) {
        std::string list;
        for (int i = 0; i < count; ++i)
            if (!present.count(i)) list += (list.empty() ? "" : ", ") + std::to_string(i);
        const bool one = int(present.size()) + 1 == count;
        return cannot("missing tile" + std::string(one ? " " : "s ") + list + " of " + std::to_string(count));
    }
    int64_t n = 0;
    int x0 = w, y0 = h, x1 = -1, y1 = -1;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (owner[size_t(y) * size_t(w) + size_t(x)] < 0) {
                ++n;
                x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
            }
    return cannot(std::to_string(n) + " of the " + size(w, h) + " pixels are in no tile, within rows " +
                  std::to_string(y0) + "-" + std::to_string(y1) + ", columns " + std::to_string(x0) + "-" +
                  std::to_string(x1));
}

}  // namespace

AssembledImage assembleTiles(const std::vector<ImageTile>& tiles) {
    if (tiles.empty()) throw cannot("no tiles");
    const ImageTile& first = tiles.front();
    const int w = first.meta.displayWidth, h = first.meta.displayHeight;
    if (w <= 0 || h <= 0 || w > kMaxImageDimension || h > kMaxImageDimension || size_t(w) * size_t(h) > kMaxReadPixels)
        throw cannot(first.path.string() + ": implausible display window " + size(w, h));
    for (const ImageTile& t : tiles) {
        checkMatches(first, t);
        checkInside(t);
        tileIndex(t);  // a malformed tile number is refused even when the cover is complete
    }
    std::vector<int32_t> owner(size_t(w) * size_t(h), -1);
    for (size_t k = 0; k < tiles.size(); ++k) {
        const ImageTile& t = tiles[k];
        for (int y = t.meta.y0; y < t.meta.y0 + t.image.height; ++y)
            for (int x = t.meta.x0; x < t.meta.x0 + t.image.width; ++x) {
                int32_t& o = owner[size_t(y) * size_t(w) + size_t(x)];
                if (o >= 0)
                    throw cannot("pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is in both " +
                                 tiles[size_t(o)].path.string() + " and " + t.path.string());
                o = int32_t(k);
            }
    }
    if (std::find(owner.begin(), owner.end(), -1) != owner.end()) throw uncovered(tiles, owner, w, h);

    AssembledImage out;
    out.image = Image(w, h, first.image.channels);
    out.meta.displayWidth = w;
    out.meta.displayHeight = h;
    out.meta.attributes = first.meta.attributes;
    out.meta.attributes.erase(kTileAttribute);
    const size_t c = size_t(first.image.channels);
    for (const ImageTile& t : tiles)
        for (int y = 0; y < t.image.height; ++y)
            std::memcpy(&out.image.at(t.meta.x0, t.meta.y0 + y), t.image.data.data() + t.image.offset(0, y),
                        size_t(t.image.width) * c * sizeof(float));
    return out;
}

AssembledImage assembleTileFiles(const std::vector<fs::path>& paths) {
    std::vector<ImageTile> tiles;
    tiles.reserve(paths.size());
    for (const fs::path& p : paths) {
        if (readImageFormat(p) != ImageFormat::Exr)
            throw Error(FileLoc{p.string()}, "a tile must be an EXR (its data window places it in the image)");
        ImageTile t{p, {}, {}};
        t.image = readImage(p, &t.meta);
        tiles.push_back(std::move(t));
    }
    return assembleTiles(tiles);
}

}  // namespace vkray
