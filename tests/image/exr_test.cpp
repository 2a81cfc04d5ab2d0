// EXR files: bit-exact float round trips (NaN, inf, -0, denormals), one channel as Y, the data and
// display windows and string attributes of ImageMeta, HALF files read as float, EXR AOVs, and errors.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "image/image_io.h"

namespace fs = std::filesystem;
using namespace vkray;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

fs::path out(const std::string& name) { return fs::path(VKRAY_TEST_OUTPUT_DIR) / ("exr_" + name); }

// Bits, so NaN == NaN and -0 != +0.
std::vector<uint32_t> bits(const std::vector<float>& v) {
    std::vector<uint32_t> b(v.size());
    std::memcpy(b.data(), v.data(), v.size() * 4);
    return b;
}

Image awkwardImage(int w, int h, int channels) {
    Image im(w, h, channels);
    const float special[] = {std::numeric_limits<float>::quiet_NaN(), kInf, -kInf, -0.0f, 1e-42f, 3.4e38f, -1.25f};
    for (size_t k = 0; k < im.data.size(); ++k)
        im.data[k] = k < std::size(special) ? special[k] : float(k) * 0.37f - 3.0f;
    return im;
}

template <class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(Exr, ColourRoundTripIsBitExact) {
    const Image im = awkwardImage(5, 3, 3);
    writeImage(out("rgb.exr"), im);
    ImageMeta meta;
    const Image back = readImage(out("rgb.exr"), &meta);
    ASSERT_EQ(back.width, 5);
    ASSERT_EQ(back.height, 3);
    ASSERT_EQ(back.channels, 3);
    EXPECT_EQ(bits(back.data), bits(im.data));
    EXPECT_EQ(meta.displayWidth, 5);
    EXPECT_EQ(meta.displayHeight, 3);
    EXPECT_EQ(meta.x0, 0);
    EXPECT_TRUE(meta.attributes.empty());

    // R, G, B as 32-bit FLOAT, ZIP compression, as OpenEXR itself reads the header.
    Imf::InputFile file(out("rgb.exr").c_str());
    const Imf::ChannelList& ch = file.header().channels();
    for (const char* name : {"R", "G", "B"}) {
        ASSERT_NE(ch.findChannel(name), nullptr) << name;
        EXPECT_EQ(ch.findChannel(name)->type, Imf::FLOAT) << name;
    }
    EXPECT_EQ(file.header().compression(), Imf::ZIP_COMPRESSION);
}

TEST(Exr, ColourImageAndOneChannelAsY) {
    const std::vector<glm::vec3> rgb = {{0.1f, 2.0f, kInf}, {-1.0f, 0.5f, 1e6f}};
    writeColorImage(out("colour.exr"), 2, 1, rgb);
    const Image back = readImage(out("colour.exr"));
    for (int i = 0; i < 2; ++i)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(back.at(i, 0, c), rgb[size_t(i)][c]);

    const Image grey = awkwardImage(3, 4, 1);
    writeImage(out("y.exr"), grey);
    const Image g = readImage(out("y.exr"));
    EXPECT_EQ(g.channels, 1);
    EXPECT_EQ(bits(g.data), bits(grey.data));
    Imf::InputFile file(out("y.exr").c_str());
    EXPECT_NE(file.header().channels().findChannel("Y"), nullptr);
    EXPECT_EQ(file.header().channels().findChannel("R"), nullptr);
}

TEST(Exr, DataWindowDisplayWindowAndAttributesRoundTrip) {
    const Image im = awkwardImage(3, 2, 3);
    ImageMeta meta;
    meta.displayWidth = 8;
    meta.displayHeight = 6;
    meta.x0 = 5;
    meta.y0 = 4;
    meta.attributes = {{"vkray:version", "0.1.0"}, {"vkray:tile", "2/4"}, {"note", ""}};
    writeImage(out("window.exr"), im, meta);
    ImageMeta back;
    const Image b = readImage(out("window.exr"), &back);
    EXPECT_EQ(bits(b.data), bits(im.data));
    EXPECT_EQ(back.displayWidth, 8);
    EXPECT_EQ(back.displayHeight, 6);
    EXPECT_EQ(back.x0, 5);
    EXPECT_EQ(back.y0, 4);
    EXPECT_EQ(back.attributes, meta.attributes);

    Imf::InputFile file(out("window.exr").c_str());  // EXR's inclusive boxes
    EXPECT_EQ(file.header().displayWindow().max.x, 7);
    EXPECT_EQ(file.header().displayWindow().max.y, 5);
    EXPECT_EQ(file.header().dataWindow().min.x, 5);
    EXPECT_EQ(file.header().dataWindow().max.x, 7);
    EXPECT_EQ(file.header().dataWindow().max.y, 5);

    // Formats without windows report the image itself.
    writeImage(out("window.pfm"), im, meta);
    ImageMeta pfm;
    pfm.attributes["x"] = "y";
    readImage(out("window.pfm"), &pfm);
    EXPECT_EQ(pfm.displayWidth, 3);
    EXPECT_EQ(pfm.displayHeight, 2);
    EXPECT_EQ(pfm.x0, 0);
    EXPECT_TRUE(pfm.attributes.empty());
}

TEST(Exr, DataWindowOutsideTheDisplayWindowIsAWriteError) {
    const Image im(4, 4, 3);
    ImageMeta meta;
    meta.displayWidth = 6;
    meta.displayHeight = 6;
    meta.x0 = 3;
    const std::string e = errorOf([&] { writeImage(out("outside.exr"), im, meta); });
    EXPECT_TRUE(contains(e, "outside.exr")) << e;
    EXPECT_TRUE(contains(e, "outside its 6x6 display window")) << e;
    EXPECT_FALSE(fs::exists(out("outside.exr")));
    meta.x0 = 0;
    meta.attributes["channels"] = "x";  // a standard attribute's name
    EXPECT_TRUE(contains(errorOf([&] { writeImage(out("std.exr"), im, meta); }), "'channels'"));
}

// HALF channels (vkray never writes them) are read as float; the magic number, not the name, says EXR.
TEST(Exr, ReadsHalfChannelsWhateverTheExtension) {
    const fs::path p = out("half.png");  // an EXR under a PNG name
    {
        Imf::Header header(2, 1);
        header.channels().insert("Y", Imf::Channel(Imf::HALF));
        const half px[2] = {half(0.5f), half(-2.0f)};
        Imf::FrameBuffer fb;
        fb.insert("Y", Imf::Slice(Imf::HALF, (char*)px, sizeof(half), sizeof(half) * 2));
        Imf::OutputFile file(p.c_str(), header);
        file.setFrameBuffer(fb);
        file.writePixels(1);
    }
    EXPECT_EQ(readImageFormat(p), ImageFormat::Exr);
    const Image im = readImage(p);
    ASSERT_EQ(im.channels, 1);
    EXPECT_EQ(im.at(0, 0), 0.5f);
    EXPECT_EQ(im.at(1, 0), -2.0f);
}

TEST(Exr, ChannelsOtherThanRgbOrYAreRefused) {
    const fs::path p = out("uv.exr");
    {
        Imf::Header header(1, 1);
        header.channels().insert("U", Imf::Channel(Imf::FLOAT));
        float u = 1.0f;
        Imf::FrameBuffer fb;
        fb.insert("U", Imf::Slice(Imf::FLOAT, (char*)&u, sizeof(float), sizeof(float)));
        Imf::OutputFile file(p.c_str(), header);
        file.setFrameBuffer(fb);
        file.writePixels(1);
    }
    const std::string e = errorOf([&] { readImage(p); });
    EXPECT_TRUE(contains(e, "uv.exr")) << e;
    EXPECT_TRUE(contains(e, "no R, G, B or Y") || contains(e, "without R, G, B or Y")) << e;
    EXPECT_TRUE(contains(e, "U")) << e;
}

TEST(Exr, AovsAsExr) {
    Frame f;
    f.resize(2, 2);
    f.depth[f.index(1, 0)] = 3.25f;
    f.primId[f.index(1, 0)] = 16777215;
    f.normal[f.index(1, 0)] = glm::vec3(0, 0.6f, 0.8f);
    ImageMeta meta;
    meta.displayWidth = 4;
    meta.displayHeight = 4;
    meta.x0 = 2;
    writeAov(out("depth.exr"), f, "depth", meta);
    writeAov(out("primid.exr"), f, "primid");
    writeAov(out("normal.exr"), f, "normal");
    ImageMeta back;
    const Image d = readImage(out("depth.exr"), &back);
    ASSERT_EQ(d.channels, 1);
    EXPECT_EQ(d.at(1, 0), 3.25f);
    EXPECT_EQ(d.at(0, 0), kInf);
    EXPECT_EQ(back.x0, 2);
    EXPECT_EQ(back.displayWidth, 4);
    const Image id = readImage(out("primid.exr"));
    EXPECT_EQ(id.at(1, 0), 16777215.0f);
    EXPECT_EQ(id.at(0, 1), -1.0f);
    const Image n = readImage(out("normal.exr"));
    ASSERT_EQ(n.channels, 3);
    EXPECT_EQ(n.at(1, 0, 2), 0.8f);
    EXPECT_NO_THROW(checkAovPath(out("d.EXR"), "depth"));
    const std::string e = errorOf([&] { checkAovPath(out("d.png"), "depth"); });
    EXPECT_TRUE(contains(e, "AOV files are PFM or EXR")) << e;
}
