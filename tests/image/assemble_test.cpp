// Assembling an image from EXR tiles written through writeImage with an ImageMeta: an exact cover
// gives back the source bit for bit; a missing tile, an overlap, a mismatched attribute, another
// display window, a window outside the display and a non-EXR tile are refused with the cause.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "image/assemble.h"
#include "image/image_io.h"

namespace fs = std::filesystem;
using namespace vkray;

namespace {

fs::path out(const std::string& name) { return fs::path(VKRAY_TEST_OUTPUT_DIR) / ("assemble_" + name); }

// 7x5 with NaN and infinities, so a lost or reordered bit shows.
Image source() {
    Image im(7, 5, 3);
    for (size_t k = 0; k < im.data.size(); ++k) im.data[k] = float(k) * 0.731f - 9.0f;
    im.data[4] = std::numeric_limits<float>::quiet_NaN();
    im.data[40] = std::numeric_limits<float>::infinity();
    im.data[77] = -0.0f;
    return im;
}

struct Box {
    int x0, y0, w, h;
};

// The four quarters of a 7x5 image (uneven: 4 + 3 columns, 3 + 2 rows), in reading order.
const Box kQuarters[4] = {{0, 0, 4, 3}, {4, 0, 3, 3}, {0, 3, 4, 2}, {4, 3, 3, 2}};

Image crop(const Image& im, const Box& b) {
    Image c(b.w, b.h, im.channels);
    for (int y = 0; y < b.h; ++y)
        for (int x = 0; x < b.w; ++x)
            for (int k = 0; k < im.channels; ++k) c.at(x, y, k) = im.at(b.x0 + x, b.y0 + y, k);
    return c;
}

// index: the tile's number, 0..count-1, or -1 for none (a crop).
ImageMeta tileMeta(const Box& b, int index, int count) {
    ImageMeta m;
    m.displayWidth = 7;
    m.displayHeight = 5;
    m.x0 = b.x0;
    m.y0 = b.y0;
    m.attributes = {{"vkray:version", "0.1.0"}, {"vkray:scene", "abc123"}, {"vkray:settings", "--spp 1"}};
    if (index >= 0) m.attributes["vkray:tile"] = std::to_string(index) + "/" + std::to_string(count);
    return m;
}

// Writes the four quarters as `stem`-I.exr, tile I of 4 (or unnumbered), and returns their paths.
std::vector<fs::path> quarters(const std::string& stem, bool numbered = true) {
    std::vector<fs::path> paths;
    for (int i = 0; i < 4; ++i) {
        paths.push_back(out(stem + "-" + std::to_string(i) + ".exr"));
        writeImage(paths.back(), crop(source(), kQuarters[i]), tileMeta(kQuarters[i], numbered ? i : -1, 4));
    }
    return paths;
}

std::string errorOf(const std::vector<fs::path>& paths) {
    try {
        assembleTileFiles(paths);
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

std::vector<uint32_t> bits(const std::vector<float>& v) {
    std::vector<uint32_t> b(v.size());
    std::memcpy(b.data(), v.data(), v.size() * 4);
    return b;
}

#define EXPECT_HAS(s, part) EXPECT_NE((s).find(part), std::string::npos) << (s)

}  // namespace

TEST(Assemble, ExactCoverIsBitIdenticalToTheSource) {
    std::vector<fs::path> paths = quarters("ok");
    std::swap(paths[0], paths[3]);  // any order
    const AssembledImage a = assembleTileFiles(paths);
    EXPECT_EQ(a.image.width, 7);
    EXPECT_EQ(a.image.height, 5);
    EXPECT_EQ(bits(a.image.data), bits(source().data));
    EXPECT_EQ(a.meta.attributes.count("vkray:tile"), 0u);
    EXPECT_EQ(a.meta.attributes.at("vkray:scene"), "abc123");

    // Written as EXR: data window = display window, attributes but vkray:tile kept, floats exact.
    writeImage(out("whole.exr"), a.image, a.meta);
    ImageMeta m;
    const Image back = readImage(out("whole.exr"), &m);
    EXPECT_EQ(bits(back.data), bits(source().data));
    EXPECT_EQ(m.x0, 0);
    EXPECT_EQ(m.displayWidth, 7);
    EXPECT_EQ(m.attributes, a.meta.attributes);
    // Unnumbered tiles (crops) that cover the image work the same.
    EXPECT_EQ(bits(assembleTileFiles(quarters("crop", false)).image.data), bits(source().data));
}

TEST(Assemble, MissingTilesAreNamed) {
    const std::vector<fs::path> q = quarters("miss");
    EXPECT_HAS(errorOf({q[0], q[1], q[3]}), "missing tile 2 of 4");
    EXPECT_HAS(errorOf({q[1], q[3]}), "missing tiles 0, 2 of 4");
    // Without tile numbers: the uncovered pixels' count and box (quarter 4: columns 4-6, rows 3-4).
    const std::vector<fs::path> c = quarters("misscrop", false);
    const std::string e = errorOf({c[0], c[1], c[2]});
    EXPECT_HAS(e, "6 of the 7x5 pixels are in no tile");
    EXPECT_HAS(e, "rows 3-4, columns 4-6");
}

TEST(Assemble, OverlapNamesBothFilesAndAPixel) {
    const std::vector<fs::path> q = quarters("overlap");
    ImageMeta m = tileMeta({3, 0, 4, 3}, 1, 4);  // quarter 2 moved one column left onto quarter 1
    const fs::path moved = out("overlap-moved.exr");
    writeImage(moved, crop(source(), {3, 0, 4, 3}), m);
    const std::string e = errorOf({q[0], moved, q[2], q[3]});
    EXPECT_HAS(e, "pixel (3, 0) is in both " + q[0].string() + " and " + moved.string());
    EXPECT_HAS(errorOf({q[0], q[1], q[2], q[3], q[1]}), "is in both");  // the same tile twice
}

TEST(Assemble, MismatchedAttributeNamesItBothValuesAndBothFiles) {
    const std::vector<fs::path> q = quarters("attr");
    ImageMeta m = tileMeta(kQuarters[2], 2, 4);
    m.attributes["vkray:version"] = "0.2.0";
    const fs::path other = out("attr-other.exr");
    writeImage(other, crop(source(), kQuarters[2]), m);
    EXPECT_HAS(errorOf({q[0], q[1], other, q[3]}),
               "attribute vkray:version differs: '0.1.0' in " + q[0].string() + ", '0.2.0' in " + other.string());
    m.attributes.erase("vkray:version");
    writeImage(other, crop(source(), kQuarters[2]), m);
    EXPECT_HAS(errorOf({q[0], q[1], other, q[3]}), "'0.1.0' in " + q[0].string() + ", missing in " + other.string());
}

TEST(Assemble, DifferentDisplayWindowIsRefused) {
    const std::vector<fs::path> q = quarters("display");
    ImageMeta m = tileMeta(kQuarters[3], 3, 4);
    m.displayWidth = 8;
    const fs::path other = out("display-other.exr");
    writeImage(other, crop(source(), kQuarters[3]), m);
    EXPECT_HAS(errorOf({q[0], q[1], q[2], other}),
               "display windows differ: 7x5 in " + q[0].string() + ", 8x5 in " + other.string());
}

TEST(Assemble, OtherRefusals) {
    const std::vector<fs::path> q = quarters("other");
    writeImage(out("other.pfm"), crop(source(), kQuarters[0]));
    EXPECT_HAS(errorOf({out("other.pfm"), q[1]}), "must be an EXR");
    EXPECT_HAS(errorOf({}), "no tiles");
    // A data window outside the display window (EXR allows it; the writer never writes one).
    ImageTile outside{"outside.exr", crop(source(), kQuarters[3]), tileMeta({5, 3, 3, 2}, 3, 4)};
    try {
        assembleTiles({outside});
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        EXPECT_HAS(std::string(e.what()), "outside.exr: its 3x2 data window at (5, 3) lies outside the 7x5");
    }
    ImageTile bad{"bad.exr", crop(source(), kQuarters[0]), tileMeta(kQuarters[0], 0, 4)};
    bad.meta.attributes["vkray:tile"] = "4/4";
    EXPECT_THROW(assembleTiles({bad}), Error);
    ImageTile grey{"grey.exr", Image(3, 2, 1), tileMeta(kQuarters[3], 3, 4)};
    ImageTile colour{"colour.exr", crop(source(), kQuarters[0]), tileMeta(kQuarters[0], 0, 4)};
    try {
        assembleTiles({colour, grey});
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        EXPECT_HAS(std::string(e.what()), "colour.exr has 3 channel(s), grey.exr has 1");
    }
}
