// Image files: PNG/BMP/PFM/EXR round trips (values and orientation), the PFM bytes docs/outputs.md fixes,
// the AOV writers, and errors (never crashes) for unwritable paths and bad or truncated files.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <stb_image.h>

#include "core/error.h"
#include "image/image_io.h"

namespace fs = std::filesystem;
using namespace vkray;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

fs::path out(const std::string& name) { return fs::path(VKRAY_TEST_OUTPUT_DIR) / ("image_io_" + name); }

std::vector<unsigned char> fileBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void putBytes(const fs::path& p, const std::vector<unsigned char>& bytes) {
    std::ofstream o(p, std::ios::binary);
    o.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

void putText(const fs::path& p, const std::string& s) { putBytes(p, {s.begin(), s.end()}); }

float littleEndianFloat(const unsigned char* p) {
    const uint32_t bits = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
}

// Every channel an exact 8-bit level, varying with column and row, so a flip or a shift shows.
std::vector<glm::vec3> levelImage(int w, int h) {
    std::vector<glm::vec3> rgb(size_t(w * h));
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            rgb[size_t(j * w + i)] =
                glm::vec3(float((20 * i + 1) % 256), float((50 * j + 2) % 256), float((7 * (i + j) + 100) % 256)) / 255.0f;
    return rgb;
}

// Asserts the call throws vkray::Error whose message contains every fragment.
template <class F>
void expectError(F&& f, std::initializer_list<std::string> fragments) {
    try {
        f();
        ADD_FAILURE() << "no vkray::Error thrown";
    } catch (const Error& e) {
        for (const std::string& s : fragments) EXPECT_NE(std::string(e.what()).find(s), std::string::npos) << e.what();
    }
}

void roundTrip8Bit(const std::string& fileName) {
    const int w = 4, h = 3;
    const auto rgb = levelImage(w, h);
    writeColorImage(out(fileName), w, h, rgb, {}, Encoding::linear());
    const Image img = readImage(out(fileName));
    ASSERT_EQ(img.width, w);
    ASSERT_EQ(img.height, h);
    ASSERT_EQ(img.channels, 3);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(img.at(i, j, c), rgb[size_t(j * w + i)][c]) << i << "," << j;
}

}  // namespace

TEST(ImageIo, PngRoundTripKeepsLevelsAndOrientation) { roundTrip8Bit("levels.png"); }
TEST(ImageIo, BmpRoundTripKeepsLevelsAndOrientation) { roundTrip8Bit("levels.bmp"); }
TEST(ImageIo, ExtensionIsCaseInsensitive) { roundTrip8Bit("levels_upper.BMP"); }

TEST(ImageIo, NoExtensionMeansPng) {
    writeColorImage(out("noext"), 1, 1, {glm::vec3(1, 0, 0)});
    const auto bytes = fileBytes(out("noext"));
    ASSERT_GE(bytes.size(), 8u);
    EXPECT_EQ(std::memcmp(bytes.data(), "\x89PNG", 4), 0);
}

TEST(ImageIo, EightBitConversionClampsRoundsAndZeroesNan) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<glm::vec3> rgb = {{-0.5f, 1.7f, nan}, {0.5f, kInf, -kInf}, {0.2f, 1.0f / 255.0f, 0.499f / 255.0f}};
    writeColorImage(out("convert.png"), 3, 1, rgb, {}, Encoding::linear());
    const Image img = readImage(out("convert.png"));
    auto level = [&](int i, int c) { return int(std::lround(img.at(i, 0, c) * 255.0f)); };
    EXPECT_EQ(level(0, 0), 0);    // clamped below
    EXPECT_EQ(level(0, 1), 255);  // clamped above
    EXPECT_EQ(level(0, 2), 0);    // NaN
    EXPECT_EQ(level(1, 0), 128);  // round(127.5), no gamma curve
    EXPECT_EQ(level(1, 1), 255);
    EXPECT_EQ(level(1, 2), 0);
    EXPECT_EQ(level(2, 0), 51);   // 0.2 * 255 exactly
    EXPECT_EQ(level(2, 1), 1);
    EXPECT_EQ(level(2, 2), 0);
}

TEST(ImageIo, PfmColourRoundTripIsExactAndUnclamped) {
    const std::vector<glm::vec3> rgb = {{-1.25f, 3.5f, kInf}, {0.1f, 1e-20f, 7.0f}, {100.0f, -kInf, 0.0f},
                                        {2.0f, 0.3f, 0.7f}};
    writeColorImage(out("colour.pfm"), 2, 2, rgb);
    const Image img = readImage(out("colour.pfm"));
    ASSERT_EQ(img.width, 2);
    ASSERT_EQ(img.height, 2);
    ASSERT_EQ(img.channels, 3);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(img.at(i, j, c), rgb[size_t(j * 2 + i)][c]);
}

// docs/outputs.md, "AOV files": "PF"/"Pf", scale -1.0 (little-endian), rows bottom to top: the top row of
// the image is the last row in the file.
TEST(ImageIo, PfmBytesAreLittleEndianBottomRowFirst) {
    const int w = 3, h = 2;
    const std::vector<float> topFirst = {1, 2, 3,   // top row
                                         4, 5, 6};  // bottom row
    writePfm(out("bytes1.pfm"), w, h, 1, topFirst.data());
    const auto bytes = fileBytes(out("bytes1.pfm"));
    const std::string header = "Pf\n3 2\n-1.0\n";
    ASSERT_EQ(bytes.size(), header.size() + 6 * 4);
    EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + std::ptrdiff_t(header.size())), header);
    const float expected[] = {4, 5, 6, 1, 2, 3};
    for (int k = 0; k < 6; ++k) EXPECT_EQ(littleEndianFloat(bytes.data() + header.size() + 4 * k), expected[k]) << k;

    const std::vector<float> rgbTop = {1, 2, 3, 4, 5, 6};  // 1x2, three channels
    writePfm(out("bytes3.pfm"), 1, 2, 3, rgbTop.data());
    const auto b3 = fileBytes(out("bytes3.pfm"));
    const std::string h3 = "PF\n1 2\n-1.0\n";
    ASSERT_EQ(b3.size(), h3.size() + 6 * 4);
    EXPECT_EQ(std::string(b3.begin(), b3.begin() + std::ptrdiff_t(h3.size())), h3);
    EXPECT_EQ(littleEndianFloat(b3.data() + h3.size()), 4.0f);        // bottom pixel's red first
    EXPECT_EQ(littleEndianFloat(b3.data() + h3.size() + 12), 1.0f);   // then the top pixel
}

TEST(ImageIo, ReadsBigEndianPfmAndOtherHeaderSpacing) {
    // Scale > 0 means big-endian; 2x1 one-channel, single spaces instead of newlines.
    std::string s = "Pf 2 1 1.0\n";
    std::vector<unsigned char> bytes(s.begin(), s.end());
    for (float f : {1.5f, -2.0f}) {
        uint32_t bits;
        std::memcpy(&bits, &f, 4);
        for (int shift = 24; shift >= 0; shift -= 8) bytes.push_back(static_cast<unsigned char>(bits >> shift));
    }
    putBytes(out("big.pfm"), bytes);
    const Image img = readImage(out("big.pfm"));
    ASSERT_EQ(img.channels, 1);
    ASSERT_EQ(img.width, 2);
    EXPECT_EQ(img.at(0, 0), 1.5f);
    EXPECT_EQ(img.at(1, 0), -2.0f);
}

TEST(ImageIo, WriteImageHandlesOneChannel) {
    Image grey(2, 1, 1);
    grey.data = {0.0f, 1.0f};
    writeImage(out("grey.png"), grey);
    const Image png = readImage(out("grey.png"));
    ASSERT_EQ(png.channels, 3);  // PNG/BMP always read back as RGB
    EXPECT_EQ(png.at(1, 0, 0), 1.0f);
    EXPECT_EQ(png.at(1, 0, 2), 1.0f);
    EXPECT_EQ(png.at(0, 0, 1), 0.0f);
    writeImage(out("grey.pfm"), grey);
    const Image pfm = readImage(out("grey.pfm"));
    ASSERT_EQ(pfm.channels, 1);
    EXPECT_EQ(pfm.data, grey.data);
}

// encodePng is what writeImage writes with the same encoding (same bytes), and decodes to the same
// clamped, rounded levels, NaN as 0, top row first; one channel stays one channel (grey).
TEST(ImageIo, EncodePngMatchesTheFileAndDecodesToTheSameLevels) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    Image rgb(3, 2, 3);
    rgb.data = {-0.5f, 1.7f, nan, 0.5f, kInf, 0.2f, 1.0f / 255.0f, 0.25f, 0.75f,   // top row
                0.0f,  1.0f, 0.12f, 0.92f, 0.33f, 0.6f, 0.4f,       0.8f,  0.05f};  // bottom row
    const std::vector<unsigned char> png = encodePng(rgb);
    writeImage(out("encode.png"), rgb, {}, Encoding::linear());
    EXPECT_EQ(png, fileBytes(out("encode.png")));

    int w = 0, h = 0, comp = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> px(
        stbi_load_from_memory(png.data(), int(png.size()), &w, &h, &comp, 0), stbi_image_free);
    ASSERT_TRUE(px);
    ASSERT_EQ(w, 3);
    ASSERT_EQ(h, 2);
    ASSERT_EQ(comp, 3);
    const int expected[] = {0, 255, 0, 128, 255, 51, 1, 64, 191, 0, 255, 31, 235, 84, 153, 102, 204, 13};
    for (size_t k = 0; k < rgb.data.size(); ++k) EXPECT_EQ(int(px.get()[k]), expected[k]) << k;

    Image grey(2, 1, 1);
    grey.data = {0.5f, 1.0f};
    const std::vector<unsigned char> greyPng = encodePng(grey);
    std::unique_ptr<stbi_uc, void (*)(void*)> g(
        stbi_load_from_memory(greyPng.data(), int(greyPng.size()), &w, &h, &comp, 0), stbi_image_free);
    ASSERT_TRUE(g);
    EXPECT_EQ(comp, 1);
    EXPECT_EQ(int(g.get()[0]), 128);
    EXPECT_EQ(int(g.get()[1]), 255);
}

TEST(ImageIo, EncodePngRejectsInvalidImages) {
    expectError([] { encodePng(Image()); }, {"0x0", "PNG"});
    expectError([] { encodePng(Image(2, 2, 2)); }, {"2 channels"});
    Image shortBuffer(2, 2, 3);
    shortBuffer.data.pop_back();
    expectError([&] { encodePng(shortBuffer); }, {"buffer"});
}

TEST(ImageIo, AovWritersFollowDesign) {
    Frame f;
    f.resize(2, 2);  // misses everywhere ...
    f.depth[f.index(1, 0)] = 3.25f;  // ... except a hit at the top right
    f.primId[f.index(1, 0)] = 16777215;  // 2^24 - 1 is exact as a float
    f.normal[f.index(1, 0)] = glm::vec3(0, 0.6f, 0.8f);
    writeAov(out("depth.pfm"), f, "depth");
    writeAov(out("primid.pfm"), f, "primid");
    writeAov(out("normal.pfm"), f, "normal");

    const Image depth = readImage(out("depth.pfm"));
    ASSERT_EQ(depth.channels, 1);
    EXPECT_EQ(depth.at(1, 0), 3.25f);
    EXPECT_EQ(depth.at(0, 0), kInf);
    EXPECT_EQ(depth.at(1, 1), kInf);
    const auto depthBytes = fileBytes(out("depth.pfm"));
    EXPECT_EQ(std::string(depthBytes.begin(), depthBytes.begin() + 3), "Pf\n");

    const Image id = readImage(out("primid.pfm"));
    ASSERT_EQ(id.channels, 1);
    EXPECT_EQ(id.at(1, 0), 16777215.0f);
    EXPECT_EQ(id.at(0, 1), -1.0f);

    const Image n = readImage(out("normal.pfm"));
    ASSERT_EQ(n.channels, 3);
    EXPECT_EQ(n.at(1, 0, 1), 0.6f);
    EXPECT_EQ(n.at(1, 0, 2), 0.8f);
    EXPECT_EQ(n.at(0, 1, 2), 0.0f);

    // The top-right hit is in the last row of the file: the file's last float is the depth 3.25.
    const auto bytes = fileBytes(out("depth.pfm"));
    EXPECT_EQ(littleEndianFloat(bytes.data() + bytes.size() - 4), 3.25f);
}

TEST(ImageIo, AovErrors) {
    Frame f;
    f.resize(1, 1);
    expectError([&] { writeAov(out("x.pfm"), f, "albedo"); }, {"albedo", "depth", "primid", "normal"});
    expectError([&] { writeAov(out("depth_aov.png"), f, "depth"); }, {"depth_aov.png", ".pfm", ".exr"});
    f.depth.clear();
    expectError([&] { writeAov(out("nodepth.pfm"), f, "depth"); }, {"nodepth.pfm", "depth"});
}

TEST(ImageIo, WriteErrorsNameThePath) {
    const std::vector<glm::vec3> px(1);
    expectError([&] { writeColorImage(out("photo.jpg"), 1, 1, px); }, {"photo.jpg", ".png", ".bmp", ".pfm", ".exr"});
    const fs::path missingDir = out("no_such_dir") / "a.png";
    expectError([&] { writeColorImage(missingDir, 1, 1, px); }, {missingDir.string(), "cannot open"});
    expectError([&] { writeColorImage(out("bad.png"), 2, 2, px); }, {"bad.png"});  // 1 pixel for 2x2
    expectError([&] { writeColorImage(out("bad.png"), 0, 1, {}); }, {"bad.png"});
}

TEST(ImageIo, ReadErrorsNameThePathAndCause) {
    expectError([] { readImage(out("does_not_exist.png")); }, {"does_not_exist.png", "cannot open"});
    expectError([] { readImage(VKRAY_TEST_OUTPUT_DIR); }, {"directory"});
    putText(out("empty.png"), "");
    expectError([] { readImage(out("empty.png")); }, {"empty.png", "empty"});
    putText(out("text.png"), "hello, I am not an image");
    expectError([] { readImage(out("text.png")); }, {"text.png", "not a PNG, BMP, PFM or EXR"});
    // A PNG signature followed by garbage.
    putText(out("garbage.png"), std::string("\x89PNG\r\n\x1a\n", 8) + std::string(100, 'x'));
    expectError([] { readImage(out("garbage.png")); }, {"garbage.png", "cannot decode"});
}

TEST(ImageIo, BadPfmHeadersAreRejected) {
    const std::string body(16, '\0');
    const std::pair<std::string, std::string> cases[] = {
        {"PF\n100000000 100000000\n-1.0\n", "implausible"},  // absurd size, rejected before allocating
        {"PF\n0 1\n-1.0\n", "implausible"},
        {"PF\n-2 1\n-1.0\n", "implausible"},
        {"PF\n2 x\n-1.0\n", "height"},
        {"PF\n99999999999999999999999 1\n-1.0\n", "width"},
        {"Pf\n2 2\n0.0\n", "scale"},
        {"Pf\n2 2\nnan\n", "scale"},
        {"Pf\n2 2\n-1.0", "scale"},  // header ends without its final whitespace
        {"Pf\n2 2\n", "scale"},
    };
    int k = 0;
    for (const auto& [header, fragment] : cases) {
        const fs::path p = out("badheader" + std::to_string(k++) + ".pfm");
        putText(p, header);
        expectError([&] { readImage(p); }, {p.filename().string(), fragment});
    }
}

TEST(ImageIo, PfmDataSizeMustMatchHeader) {
    putText(out("short.pfm"), "Pf\n2 2\n-1.0\n" + std::string(15, '\0'));
    expectError([] { readImage(out("short.pfm")); }, {"short.pfm", "truncated", "16 bytes", "15 found"});
    putText(out("long.pfm"), "Pf\n2 2\n-1.0\n" + std::string(20, '\0'));
    expectError([] { readImage(out("long.pfm")); }, {"long.pfm", "4 bytes after"});
}

// Every prefix of a valid file is an error naming the path, never a crash or a silently damaged
// image. The one exception: a PNG cut inside its final (empty) IEND chunk still holds all pixels.
TEST(ImageIo, TruncatedFilesGiveErrors) {
    const auto rgb = levelImage(7, 5);  // odd width: BMP rows carry padding
    for (const std::string name : {"full.png", "full.bmp", "full.pfm", "full.exr"}) {
        writeColorImage(out(name), 7, 5, rgb);
        const auto bytes = fileBytes(out(name));
        const Image full = readImage(out(name));
        for (size_t len = 0; len < bytes.size(); ++len) {
            const fs::path p = out("cut_" + name);
            putBytes(p, std::vector<unsigned char>(bytes.begin(), bytes.begin() + std::ptrdiff_t(len)));
            try {
                const Image img = readImage(p);
                EXPECT_TRUE(name == "full.png" && len >= bytes.size() - 4) << name << " cut to " << len;
                EXPECT_EQ(img.data, full.data) << name << " cut to " << len;
            } catch (const Error& e) {
                EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
            }
        }
    }
}

// Random byte corruption of valid files: each read succeeds or throws vkray::Error.
TEST(ImageIo, CorruptedFilesNeverCrash) {
    std::mt19937 rng(12345);
    const auto rgb = levelImage(8, 8);
    for (const std::string name : {"fuzz.png", "fuzz.bmp", "fuzz.pfm", "fuzz.exr"}) {
        writeColorImage(out(name), 8, 8, rgb);
        const auto good = fileBytes(out(name));
        for (int trial = 0; trial < 300; ++trial) {
            auto bytes = good;
            const int flips = 1 + int(rng() % 4);
            for (int f = 0; f < flips; ++f) {
                // Bias towards the header, where the dangerous fields are.
                const size_t at = trial % 2 ? rng() % std::min<size_t>(bytes.size(), 64) : rng() % bytes.size();
                bytes[at] = static_cast<unsigned char>(rng());
            }
            const fs::path p = out("fuzzed_" + name);
            putBytes(p, bytes);
            try {
                const Image img = readImage(p);
                EXPECT_EQ(img.data.size(), img.pixelCount() * size_t(img.channels));
            } catch (const Error&) {
            }
        }
    }
}

// Inputs the fuzzer (tests/fuzz, image target) found, kept there as regressions/image/: each read
// ends in a one-line vkray::Error or an image, never a message broken over lines or undefined behaviour.
TEST(ImageIo, FuzzFindingsGiveOneLineErrors) {
    const auto finding = [](const std::string& name) {
        return fileBytes(fs::path(VKRAY_SOURCE_DIR) / "tests/fuzz/regressions/image" / name);
    };
    const auto oneLineError = [](const std::vector<unsigned char>& bytes) {
        try {
            decodeImage("finding", bytes);
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    // stb names an unknown PNG chunk by its type's four bytes, here two of them line ends.
    const std::string chunk = oneLineError(finding("png-chunk-type-line-feed.png"));
    EXPECT_NE(chunk.find("finding: cannot decode: "), std::string::npos) << chunk;
    // An EXR whose only channels are named "\n" and "G".
    const std::string channels = oneLineError(finding("exr-channel-name-line-feed.exr"));
    EXPECT_NE(channels.find("EXR without R, G, B or Y channels (it has: \\n, G)"), std::string::npos) << channels;
    // A zero-length IDAT chunk first (stb copies 0 bytes into a buffer it has not allocated).
    try {
        const Image image = decodeImage("finding", finding("png-empty-idat.png"));
        EXPECT_EQ(image.data.size(), image.pixelCount() * 3);
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
}
