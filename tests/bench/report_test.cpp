// The report writers on the synthetic BenchResults of report_fixture.h. Checks what a reader relies
// on: every image embedded, nothing fetched from the network, every error point plotted, the Pareto
// front and the best delta marked, one table row per accelerator, the right winner with the right
// ratio, and the files writeBenchReport leaves behind.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/colormap.h"
#include "bench/report.h"
#include "bench/report_images.h"
#include "bench/report_plots.h"
#include "bench/report_tables.h"
#include "core/error.h"
#include "image/image_io.h"
#include "report_fixture.h"

namespace fs = std::filesystem;
using namespace vkray;
using namespace vkray::bench;
using namespace vkray::bench::fixture;

namespace {

// The text from `heading` to the next heading of the same level or above.
std::string section(const std::string& text, const std::string& heading) {
    const size_t start = text.find(heading);
    if (start == std::string::npos) return "";
    const size_t end = text.find("\n#", start + heading.size());
    return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

// ---- Formatting and helpers ---------------------------------------------------------------------

TEST(BenchReport, NumbersHaveSensiblePrecision) {
    EXPECT_EQ(formatNumber(0.042), "0.042");
    EXPECT_EQ(formatNumber(12.345), "12.3");
    EXPECT_EQ(formatNumber(1234.4), "1234");
    EXPECT_EQ(formatNumber(std::nan("")), "—");
    EXPECT_EQ(formatSpread({12.34, 11.9, 13.04}), "12.3 (11.9–13.0)");
    EXPECT_EQ(formatRatio(2.4), "2.40x");
    EXPECT_EQ(formatBytes(512), "512 B");
    EXPECT_EQ(formatBytes(123456), "120.6 KiB");
    EXPECT_EQ(formatBytes(5u << 20), "5.00 MiB");
    EXPECT_EQ(formatRmse(0.0), "0");
    EXPECT_EQ(formatRmse(1.234e-5), "1.23e-05");
    EXPECT_EQ(formatPsnr(std::nullopt), "identical");
    EXPECT_EQ(formatPercent(0.0025), "0.25 %");
}

TEST(BenchReport, Base64MatchesRfc4648) {
    auto b64 = [](const std::string& s) { return base64(std::vector<unsigned char>(s.begin(), s.end())); };
    EXPECT_EQ(b64(""), "");
    EXPECT_EQ(b64("f"), "Zg==");
    EXPECT_EQ(b64("fo"), "Zm8=");
    EXPECT_EQ(b64("foo"), "Zm9v");
    EXPECT_EQ(b64("foobar"), "Zm9vYmFy");
    EXPECT_EQ(base64({0xff, 0xfe, 0x00}), "//4A");
}

TEST(BenchReport, HeatmapScaleIgnoresAnOutlierPixel) {
    std::vector<uint32_t> v(1000, 10);
    v[500] = 100000;
    EXPECT_EQ(percentile(v, 99.0), 10u);
    EXPECT_EQ(percentile({1, 2, 3, 4}, 50.0), 2u);
    EXPECT_EQ(percentile({}, 99.0), 0u);

    SceneResult s = minimalScene();
    s.width = 40;  // the render stays 4x3: the counts take the scene's size
    s.height = 30;
    s.accels[0].nodesPerPixel.assign(1200, 10);
    s.accels[0].nodesPerPixel[3] = 5000;
    const HeatmapScale scale = heatmapScale(s);
    EXPECT_EQ(scale.max, 10.0);
    EXPECT_EQ(scale.largest, 5000u);
}

// ---- Tables and the verdict --------------------------------------------------------------------

TEST(BenchReport, WhoWinsNamesTheFastestWithItsRatio) {
    const std::string s = whoWins(fullScene());
    EXPECT_NE(s.find("bvh-hq traces 2.40x faster than kd-stack, the fastest kd traversal (1.0 ms against 2.4 ms)."),
              std::string::npos)
        << s;
    EXPECT_NE(s.find("Among the kd traversals, kd-stack is fastest, 1.25x faster than kd-restart, the slowest"),
              std::string::npos)
        << s;
}

TEST(BenchReport, WhoWinsWhenAKdTraversalBeatsTheBvh) {
    SceneResult scene = fullScene();
    scene.accels[2].traceMs = around(0.5);  // kd-stack
    const std::string s = whoWins(scene);
    EXPECT_NE(s.find("kd-stack traces 2.00x faster than bvh-hq, the fastest BVH"), std::string::npos) << s;
}

TEST(BenchReport, WhoWinsSaysWhatIsMissing) {
    EXPECT_EQ(whoWins(minimalScene()), "No BVH was run. kd-restart traces in 5.0 ms.");
    SceneResult none = minimalScene();
    none.accels.clear();
    EXPECT_EQ(whoWins(none), "No BVH or kd-tree accelerator has a trace time to compare.");
    SceneResult bvhOnly = fullScene();
    bvhOnly.accels.resize(2);
    EXPECT_NE(whoWins(bvhOnly).find("No kd-tree traversal was run. Among the BVHs, bvh-hq is fastest, 1.50x faster"),
              std::string::npos)
        << whoWins(bvhOnly);
}

TEST(BenchReport, TablesMarkTheParetoFrontAndTheBestDelta) {
    const SceneResult scene = fullScene();
    const Table errors = errorTable(scene);
    ASSERT_EQ(errors.rows.size(), scene.errorPoints.size());
    for (size_t i = 0; i < errors.rows.size(); ++i) {
        EXPECT_EQ(errors.marked[i], scene.errorPoints[i].pareto) << i;
        EXPECT_EQ(errors.rows[i].back(), scene.errorPoints[i].pareto ? "★" : "") << i;
    }
    EXPECT_FALSE(scene.errorPoints[1].pareto);  // kd-stack: slower than bvh-hq at the same error
    EXPECT_EQ(errors.rows[4][8], "identical");  // the CPU reference's PSNR

    const Table deltas = deltaSweepTable(scene);
    ASSERT_EQ(deltas.rows.size(), 3u);
    EXPECT_EQ(deltas.marked, (std::vector<bool>{false, true, false}));  // 8: 11.5 ms, the lowest total
    EXPECT_EQ(deltas.rows[1][0], "8 ★");
    EXPECT_EQ(deltas.rows[1][4], "11.5");
    EXPECT_EQ(deltas.rows[1][7], "51.0");  // tests per ray = nodes + triangles
}

TEST(BenchReport, AcceleratorTableExplainsEmptyRates) {
    const Table t = acceleratorTable(fullScene());
    ASSERT_EQ(t.rows.size(), 5u);
    EXPECT_EQ(t.rows[0][1], "9.0 (8.1–10.8)");  // the build with the most threads
    EXPECT_EQ(t.rows[0][5], "40.0");
    EXPECT_EQ(t.rows[0][6], "—¹");
    EXPECT_EQ(t.rows[0][7], "—²");
    EXPECT_NE(std::find(t.notes.begin(), t.notes.end(), "¹ within the noise"), t.notes.end());
    EXPECT_NE(std::find(t.notes.begin(), t.notes.end(), "² no reflective or refractive surfaces"), t.notes.end());
}

// The kd walks' yardstick: each tracer's camera-ray rate over bvh's, which is also the quotient of
// the two ratios to the scene's one Embree figure.
TEST(BenchReport, EmbreeTableGivesEachTracerOverBvh) {
    SceneResult scene = fullScene();
    scene.embree.version = "Embree 3.13.5";
    scene.embree.threads = 2;
    scene.embree.singleMs = around(10.0);
    scene.embree.packetMs = around(8.0);
    scene.accels[0].accel = "bvh";
    scene.accels[0].primaryOnlyMs = around(20.0);   // 0.5x Embree
    scene.accels[0].embreeSingleMs = around(9.0);   // its own interleaved runs: not the divisor
    scene.accels[2].primaryOnlyMs = around(30.0);   // kd-stack: 0.33x Embree, 0.67x bvh
    scene.accels[2].embreeSingleMs = around(14.0);
    scene.accels[3].primaryOnlyMs = around(40.0);   // kd-restart, without interleaved Embree times
    const Table t = embreeTable(scene);
    ASSERT_EQ(t.rows.size(), 2 + scene.accels.size());
    const size_t overEmbree = 3, overBvh = 4;
    ASSERT_EQ(t.columns.at(overEmbree), "vs Embree rtcIntersect1");
    ASSERT_EQ(t.columns.at(overBvh), "vs bvh");
    EXPECT_EQ(t.rows[0][overBvh], "—");  // Embree's own rows
    EXPECT_EQ(t.rows[2][overEmbree], "0.50x");
    EXPECT_EQ(t.rows[2][overBvh], "1.00x");
    EXPECT_EQ(t.rows[3][overEmbree], "—");  // bvh-fast: no camera-ray time
    EXPECT_EQ(t.rows[3][overBvh], "—");
    EXPECT_EQ(t.rows[4][overEmbree], "0.33x");
    EXPECT_EQ(t.rows[4][overBvh], "0.67x");
    EXPECT_EQ(t.rows[5][overEmbree], "0.25x");  // the same divisor, with or without its own runs
    EXPECT_EQ(t.rows[5][overBvh], "0.50x");
    EXPECT_FALSE(primaryVs(fullScene(), fullScene().accels[2], "bvh"));  // no bvh in the run
}

TEST(BenchReport, SignedChangesReadAsChanges) {
    EXPECT_EQ(formatChange(1.6444), "+164 %");
    EXPECT_EQ(formatChange(-0.2414), "−24 %");  // a minus sign, not a hyphen
    EXPECT_EQ(formatChange(0.025), "+2.5 %");
    EXPECT_EQ(formatChange(-0.0001), "0 %");
    EXPECT_EQ(formatChange(std::nan("")), "—");
}

TEST(BenchReport, ConcurrentBuildSaysFasterWithANegativeShare) {
    const Table t = concurrentBuildTable(fullScene());
    ASSERT_EQ(t.rows.size(), 5u);
    EXPECT_EQ(t.rows[2][1], "29.0 (26.1–34.8)");  // 9 + 20, one after the other
    EXPECT_EQ(t.rows[4][0], "both at once against the sum");
    EXPECT_EQ(t.rows[4][1], "7.0 ms faster than the 29.0 ms sum (−24 %)");  // 22 against 29
    EXPECT_TRUE(t.marked[4]);
    EXPECT_TRUE(concurrentBuildTable(minimalScene()).rows.empty());
}

TEST(BenchReport, ConcurrentBuildSaysSlowerWithAPositiveShare) {
    // The review's case: 7.4 ms lost on a 4.5 ms sum was printed "loss ... 7.4 (-163.35 % of the sum)".
    SceneResult scene = fullScene();
    scene.concurrent = ConcurrentBuild{"bvh-hq", "kd-stack", around(2.0), around(2.5), around(11.9)};
    const Table t = concurrentBuildTable(scene);
    ASSERT_EQ(t.rows.size(), 5u);
    EXPECT_EQ(t.rows[4][1], "7.4 ms slower than the 4.5 ms sum (+164 %)");
    EXPECT_FALSE(t.marked[4]);
    EXPECT_EQ(concurrentAgainstSum(4.5, 4.5), "as fast as the 4.5 ms sum (0 %)");
}

TEST(BenchReport, BuildScalingHasSpeedups) {
    const Table t = buildScalingTable(fullScene());
    EXPECT_EQ(t.columns, (std::vector<std::string>{"accel", "ms, 1 thread", "ms, 2 threads", "speed-up, 2 threads"}));
    ASSERT_EQ(t.rows.size(), 5u);
    EXPECT_EQ(t.rows[0], (std::vector<std::string>{"bvh-hq", "16.0", "9.0", "1.78x"}));
}

// ---- Markdown --------------------------------------------------------------------------------

TEST(BenchReport, MarkdownHasTheHeaderAndOneRowPerAccelerator) {
    const BenchResults r = results();
    const std::string md = benchMarkdown(r);
    for (const std::string& s : {r.device, r.driver, r.commandLine, r.startedAt, std::string("abc1234")})
        EXPECT_NE(md.find(s), std::string::npos) << s;
    for (const SceneResult& scene : r.scenes) {
        const std::string table = section(md.substr(md.find("## " + scene.name)), "### Accelerators");
        size_t rows = 0;
        for (const std::string& line : lines(table)) rows += line.rfind("| ", 0) == 0;
        EXPECT_EQ(rows, 2 + scene.accels.size()) << table;  // header, alignment, one per accelerator
        for (const AccelResult& a : scene.accels) EXPECT_EQ(count(table, "\n| " + a.accel + " |"), 1u) << a.accel;
        EXPECT_NE(md.find("**Who wins:** " + whoWins(scene)), std::string::npos);
    }
    const std::string errors = section(md, "### Error against run time");
    EXPECT_EQ(count(errors, "| ★ |"), 4u);
    EXPECT_NE(md.find("No AAC delta sweep was run for this scene."), std::string::npos);
    EXPECT_NE(md.find("¹ within the noise"), std::string::npos);
}

// ---- HTML ------------------------------------------------------------------------------------

TEST(BenchReport, HtmlEmbedsEveryImageAndFetchesNothing) {
    const std::string html = benchHtml(results());
    EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
    EXPECT_EQ(count(html, "src=\"data:image/png;base64,"), kExpectedImages);
    EXPECT_EQ(count(html, "src=\""), kExpectedImages);  // no other source of any kind
    EXPECT_EQ(html.find("<script"), std::string::npos);
    EXPECT_EQ(html.find("<link"), std::string::npos);
    EXPECT_EQ(html.find("url("), std::string::npos);
    // Base64 could spell "http" by chance: look at everything but the image data.
    const std::string text = std::regex_replace(html, std::regex("base64,[A-Za-z0-9+/=]*"), "base64,");
    std::string lower = text;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    EXPECT_EQ(lower.find("http"), std::string::npos);
    EXPECT_EQ(lower.find("//"), std::string::npos);  // no protocol-relative URL either
}

TEST(BenchReport, HtmlHasTheTablesPlotsAndVerdicts) {
    const BenchResults r = results();
    const std::string html = benchHtml(r);
    EXPECT_NE(html.find("<h2>beta&lt;&amp;&gt;</h2>"), std::string::npos);  // escaped, never raw
    EXPECT_EQ(html.find("beta<&>"), std::string::npos);
    EXPECT_NE(html.find(whoWins(r.scenes[0])), std::string::npos);
    EXPECT_EQ(count(html, "<svg class=\"plot error-plot\""), 2u);
    EXPECT_EQ(count(html, "<svg class=\"plot scaling-plot\""), 1u);  // the minimal scene has one thread count
    EXPECT_NE(html.find("one thread count only (2 threads)"), std::string::npos);
    EXPECT_EQ(count(html, "<svg class=\"plot delta-plot delta-build\""), 1u);
    EXPECT_EQ(count(html, "<svg class=\"plot delta-plot delta-trace\""), 1u);
    EXPECT_EQ(count(html, "<svg class=\"colour-bar\""), 4u);  // per scene: all rays, camera rays
    EXPECT_EQ(count(html, "<tr class=\"marked\">"), 4u + 1u + 1u + 1u);  // fronts (4 and 1), best delta, saving
    EXPECT_NE(html.find("image-rendering: pixelated"), std::string::npos);
    EXPECT_NE(html.find("width=\"256\""), std::string::npos);  // 8 px wide, shown 32 times larger
}

TEST(BenchReport, WideTablesScrollInTheirOwnBoxAndSpreadsWrap) {
    const std::string html = benchHtml(results());
    // Every table sits in a box that scrolls sideways, so a table wider than the page is never cut.
    EXPECT_EQ(count(html, "<div class=\"scroll\"><table>"), count(html, "<table>"));
    EXPECT_NE(html.find(".scroll { overflow-x: auto;"), std::string::npos);
    // A median with its spread puts the spread on a line of its own: the accelerator table's
    // bvh-hq build, 9.0 (8.1–10.8), is half as wide.
    EXPECT_NE(html.find("<td class=\"num\">9.0 <span class=\"spread\">(8.1–10.8)</span></td>"), std::string::npos);
    EXPECT_NE(html.find("td.num .spread { display: block;"), std::string::npos);
    // Text that is not a spread stays whole.
    EXPECT_NE(html.find("<td class=\"num\">7.0 ms faster than the 29.0 ms sum (−24 %)</td>"), std::string::npos);
}

TEST(BenchReport, DeltaSweepSaysWhichSahCostItShows) {
    const Table t = deltaSweepTable(fullScene());
    EXPECT_EQ(t.columns.back(), "SAH cost (BVH)");
    const bool explained = std::any_of(t.notes.begin(), t.notes.end(), [](const std::string& n) {
        return n.find("relative to the root's surface area, in units of Ct=1 a node and Ci=1 a triangle") !=
               std::string::npos;
    });
    EXPECT_TRUE(explained);
}

// The build and the trace of the sweep are three orders of magnitude apart (the review's case:
// build 0.15-0.5 ms, trace 230-315 ms): each gets a plot and a y axis of its own, so the build's
// changes show instead of lying flat on zero.
TEST(BenchReport, DeltaPlotGivesBuildAndTraceAxesOfTheirOwn) {
    SceneResult scene = fullScene();
    scene.deltas = {{4, 0.1, around(0.15), around(315.0), 40.0, 8.0, 70.0},
                    {8, 0.1, around(0.3), around(260.0), 42.0, 9.0, 72.0},
                    {20, 0.1, around(0.5), around(230.0), 38.0, 7.5, 68.0}};
    const std::string svg = deltaPlotSvg(scene);
    const size_t split = svg.find("<svg", 1);
    ASSERT_NE(split, std::string::npos);
    const std::string build = svg.substr(0, split), trace = svg.substr(split);
    EXPECT_NE(build.find("delta-build"), std::string::npos);
    EXPECT_NE(trace.find("delta-trace"), std::string::npos);
    // The build's circles span most of the plot's height: 0.15 ms at the bottom, 0.5 ms at the top.
    std::vector<double> ys;
    static const std::regex cy(R"re(<circle cx="[-0-9.]+" cy="([-0-9.]+)")re");
    for (auto it = std::sregex_iterator(build.begin(), build.end(), cy); it != std::sregex_iterator(); ++it)
        ys.push_back(std::stod((*it)[1]));
    ASSERT_EQ(ys.size(), 3u);
    EXPECT_GT(ys[0] - ys[2], 150.0) << build;  // SVG y grows downwards
    EXPECT_NE(build.find(">0.5</text>"), std::string::npos);  // its axis is in the build's range
    EXPECT_EQ(build.find(">300</text>"), std::string::npos);
    EXPECT_NE(trace.find(">300</text>"), std::string::npos);
}

TEST(BenchReport, ErrorPlotHasAMarkerPerPointAndEmphasisesTheFront) {
    const SceneResult scene = fullScene();
    const std::string svg = errorPlotSvg(scene);
    EXPECT_EQ(count(svg, "<g class=\"point"), scene.errorPoints.size());
    EXPECT_EQ(count(svg, "<g class=\"point emphasised\">"), 4u);
    EXPECT_NE(svg.find(">identical (0)</text>"), std::string::npos);  // the CPU reference's row
    for (const ErrorPoint& p : scene.errorPoints)
        EXPECT_NE(svg.find("<title>" + p.label + " (" + p.group + ")"), std::string::npos) << p.label;
    for (const std::string group : {"accelerator", "aac-delta", "maxdepth", "cpu-reference", "Pareto front"})
        EXPECT_NE(svg.find(">" + group + "</text>"), std::string::npos) << group;  // legend
}

TEST(BenchReport, ErrorPlotLabelsEveryPointWithItsConfiguration) {
    const SceneResult scene = fullScene();
    const std::string svg = errorPlotSvg(scene);
    for (const ErrorPoint& p : scene.errorPoints) {  // the front's and the others', drawn, not only on hover
        const std::regex label("class=\"label\"[^>]*>" + p.label + "</text>");
        EXPECT_EQ(std::distance(std::sregex_iterator(svg.begin(), svg.end(), label), std::sregex_iterator()), 1)
            << p.label;
    }
}

TEST(BenchReport, PlotsAreLeftOutWhenThereIsNothingToPlot) {
    const SceneResult scene = minimalScene();
    EXPECT_EQ(scalingPlotSvg(scene), "");
    EXPECT_EQ(deltaPlotSvg(scene), "");
    EXPECT_EQ(count(scalingPlotSvg(fullScene()), "<g class=\"point\">"), 5u * 2u);
    EXPECT_EQ(count(deltaPlotSvg(fullScene()), "<g class=\"point\">"), 3u * 2u);
}

// ---- Files -----------------------------------------------------------------------------------

TEST(BenchReport, WriteBenchReportWritesEveryFile) {
    const fs::path dir = fs::path(VKRAY_TEST_OUTPUT_DIR) / "bench_report" / "out";
    fs::remove_all(dir.parent_path());
    const BenchResults r = results();
    writeBenchReport(r, dir);  // creates both levels

    EXPECT_EQ(readText(dir / "bench.md"), benchMarkdown(r));
    EXPECT_EQ(readText(dir / "report.html"), benchHtml(r));
    const nlohmann::json json = nlohmann::json::parse(readText(dir / "bench.json"));
    EXPECT_FALSE(json.empty());

    size_t pngs = 0;
    for (const auto& entry : fs::directory_iterator(dir / "images")) {
        ASSERT_EQ(entry.path().extension(), ".png");
        const Image im = readImage(entry.path());
        EXPECT_TRUE((im.width == 8 && im.height == 6) || (im.width == 4 && im.height == 3)) << entry.path();
        ++pngs;
    }
    EXPECT_EQ(pngs, kExpectedImages);
    EXPECT_TRUE(fs::exists(dir / "images" / "alpha_reference.png"));
    EXPECT_TRUE(fs::exists(dir / "images" / "alpha_kd-restart_nodes.png"));
    EXPECT_TRUE(fs::exists(dir / "images" / "beta____kd-restart_diff.png"));

    // The heatmaps share the scene's scale, 0 to the 99th percentile of all accelerators (46 nodes,
    // kd-restart's most): 10 nodes of bvh-hq are viridis(10/46), 46 of kd-restart its top colour.
    auto levels = [](DisplayColor c) {  // as the PNG stores them: round(255 c)
        std::vector<float> out;
        for (float v : {c.r, c.g, c.b}) out.push_back(float(std::lround(255.0 * double(v))) / 255.0f);
        return out;
    };
    const Image heat = readImage(dir / "images" / "alpha_bvh-hq_nodes.png");
    EXPECT_EQ((std::vector<float>{heat.at(0, 0, 0), heat.at(0, 0, 1), heat.at(0, 0, 2)}), levels(viridis(10.0 / 46.0)));
    const Image kdHeat = readImage(dir / "images" / "alpha_kd-restart_nodes.png");
    EXPECT_EQ((std::vector<float>{kdHeat.at(6, 0, 0), kdHeat.at(6, 0, 1), kdHeat.at(6, 0, 2)}), levels(viridis(1.0)));
}

TEST(BenchReport, WriteBenchReportNamesAPathItCannotWrite) {
    const fs::path blocker = fs::path(VKRAY_TEST_OUTPUT_DIR) / "bench_report_blocker";
    fs::remove_all(blocker);
    std::ofstream(blocker) << "a file, not a directory";
    for (const fs::path& dir : {blocker, blocker / "sub"}) {
        try {
            writeBenchReport(results(), dir);
            ADD_FAILURE() << "no vkray::Error for " << dir;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(dir.string()), std::string::npos) << e.what();
        }
    }
}
