// The window flags of `vkray render` (cli/cli_options.h): pixel boxes from crop fractions, pixel
// bounds, one pixel and tiles, and the errors for values that are malformed or leave the image.
#include <string>

#include <gtest/gtest.h>

#include "cli/cli_options.h"
#include "core/error.h"

namespace vkray::cli {
namespace {

TEST(WindowOptions, CropRoundsUpAsPbrt) {
    // pbrt-v4: columns ceil(x0 W) .. ceil(x1 W), rows likewise.
    EXPECT_EQ(parseCrop("0,1,0,1", 640, 480), (PixelWindow{0, 0, 640, 480}));
    EXPECT_EQ(parseCrop("0.25,0.5,0.1,0.2", 640, 480), (PixelWindow{160, 48, 320, 96}));
    EXPECT_EQ(parseCrop("0.001,0.002,0,0.5", 640, 480), (PixelWindow{1, 0, 2, 240}));
    EXPECT_EQ(parseCrop("0.25 0.5 0.1 0.2", 640, 480), (PixelWindow{160, 48, 320, 96}));  // pbrt's spaces
}

TEST(WindowOptions, PixelBoundsAndPixel) {
    EXPECT_EQ(parsePixelBounds("10,20,30,45", 64, 48), (PixelWindow{10, 30, 20, 45}));
    EXPECT_EQ(parsePixel("63,47", 64, 48), (PixelWindow{63, 47, 64, 48}));
}

TEST(WindowOptions, TilesCoverTheRowsExactlyOnce) {
    for (const int height : {1, 7, 480, 481}) {
        for (const int count : {1, 2, 3, 4, 7}) {
            if (count > height) continue;
            int next = 0;
            for (int i = 0; i < count; ++i) {
                const PixelWindow w = tileWindow({i, count}, 50, height);
                EXPECT_EQ(w.x0, 0);
                EXPECT_EQ(w.x1, 50);
                EXPECT_EQ(w.y0, next) << i << "/" << count << " of " << height;
                EXPECT_GT(w.y1, w.y0);
                next = w.y1;
            }
            EXPECT_EQ(next, height);
        }
    }
    EXPECT_EQ(parseTile("3/4").index, 3);
    EXPECT_EQ(parseTile("3/4").count, 4);
}

TEST(WindowOptions, BadValuesAreErrorsNamingTheFlag) {
    const auto message = [](auto&& f) {
        try {
            f();
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message([] { parseCrop("0,1,0", 64, 48); }).find("--crop 0,1,0: expected X0,X1,Y0,Y1"), std::string::npos);
    EXPECT_NE(message([] { parseCrop("0,1.5,0,1", 64, 48); }).find("in [0, 1]"), std::string::npos);
    EXPECT_NE(message([] { parseCrop("0.5,0.5,0,1", 64, 48); }).find("not a non-empty part"), std::string::npos);
    EXPECT_NE(message([] { parsePixelBounds("0,65,0,1", 64, 48); }).find("of the 64x48 image"), std::string::npos);
    EXPECT_NE(message([] { parsePixelBounds("0,1.5,0,1", 64, 48); }).find("whole pixel numbers"), std::string::npos);
    EXPECT_NE(message([] { parsePixel("64,0", 64, 48); }).find("--pixel 64,0"), std::string::npos);
    EXPECT_NE(message([] { parsePixel("-1,0", 64, 48); }).find("--pixel -1,0"), std::string::npos);
    EXPECT_NE(message([] { parseTile("4/4"); }).find("I must be 0..3"), std::string::npos);
    EXPECT_NE(message([] { parseTile("1/0"); }).find("--tile 1/0"), std::string::npos);
    EXPECT_NE(message([] { parseTile("a/4"); }).find("expected I/N"), std::string::npos);
    EXPECT_NE(message([] { tileWindow({0, 49}, 64, 48); }).find("more tiles than the 48 rows"), std::string::npos);
}

}  // namespace
}  // namespace vkray::cli
