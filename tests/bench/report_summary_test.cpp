// What the report says about the run as a whole and what report.html adds to bench.md: the warnings
// (too few repeats, a busy machine), the summary across scenes with its geometric means, the
// camera-ray bar chart, the two heatmaps side by side, and that report.html shows every table
// bench.md shows. On the synthetic results of report_fixture.h.
#include <cmath>
#include <filesystem>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/bench_json.h"
#include "bench/report.h"
#include "bench/report_images.h"
#include "bench/report_plots.h"
#include "bench/report_tables.h"
#include "bench/svg_bar_chart.h"
#include "bench/svg_plot.h"
#include "report_fixture.h"

namespace fs = std::filesystem;
using namespace vkray;
using namespace vkray::bench;
using namespace vkray::bench::fixture;

namespace {

bool anyContains(const std::vector<std::string>& texts, const std::string& part) {
    for (const std::string& t : texts)
        if (t.find(part) != std::string::npos) return true;
    return false;
}

// A scene whose accelerators trace camera rays in the given ms, with Embree rtcIntersect1 at
// `embreeMs` (0: no Embree).
SceneResult cameraScene(const std::string& name, double embreeMs,
                        const std::vector<std::pair<std::string, double>>& cameraMs) {
    SceneResult s = fullScene();
    s.name = name;
    s.accels.clear();
    for (const auto& [accelName, ms] : cameraMs) {
        AccelResult a = makeAccel(accelName, 2.0 * ms, oneAndTwoThreads(10.0, 6.0), 8, 6, 10);
        a.primaryOnlyMs = around(ms);
        a.rayKinds[0].mraysPerSecond = mraysPerSecond(double(s.width * s.height), ms);
        s.accels.push_back(a);
    }
    if (embreeMs > 0.0) {
        s.embree.version = "Embree 3.13.5";
        s.embree.threads = 2;
        s.embree.singleMs = around(embreeMs);
        s.embree.packetMs = around(0.8 * embreeMs);
    }
    return s;
}

BenchResults twoScenes(double embreeA, double embreeB) {
    BenchResults r = results();
    r.scenes = {cameraScene("alpha", embreeA, {{"bvh", 20.0}, {"kd-stack", 40.0}}),
                cameraScene("beta", embreeB, {{"bvh", 50.0}, {"kd-stack", 12.5}, {"kd-restart", 25.0}})};
    return r;
}

}  // namespace

// ---- Warnings --------------------------------------------------------------------------------

TEST(BenchWarnings, FewerThanThreeRepeatsAreNoise) {
    BenchResults r = results();
    EXPECT_TRUE(runWarnings(r).empty());  // --repeat 3, no load recorded
    for (int repeat : {1, 2}) {
        r.repeat = repeat;
        const std::vector<std::string> w = runWarnings(r);
        ASSERT_EQ(w.size(), 1u) << repeat;
        EXPECT_EQ(w[0], "--repeat " + std::to_string(repeat) +
                            ": spreads of fewer than 3 runs are noise; compare figures of --repeat 3 or more");
    }
    r.repeat = 1;
    const std::string warning = runWarnings(r)[0];
    EXPECT_NE(benchMarkdown(r).find("> **Warning:** " + warning + "\n"), std::string::npos);
    EXPECT_NE(benchHtml(r).find("<p class=\"warning\"><strong>Warning:</strong> " + escapeXml(warning) + "</p>"),
              std::string::npos);
    const nlohmann::json j = nlohmann::json::parse(benchJson(r));
    ASSERT_EQ(j["warnings"].size(), 1u);
    EXPECT_EQ(j["warnings"][0], warning);
}

TEST(BenchWarnings, ALoadAboveTheCoresAtTheStartOrTheEnd) {
    BenchResults r = results();
    r.hardwareThreads = 2;
    r.loadAverageStart = 1.9;
    r.loadAverageEnd = 2.0;  // all cores busy, none waiting: not above them
    EXPECT_TRUE(runWarnings(r).empty());
    r.loadAverageStart = 3.5;
    r.loadAverageEnd = 1.0;
    ASSERT_EQ(runWarnings(r).size(), 1u);
    EXPECT_NE(runWarnings(r)[0].find("the machine was busy: its 1-minute load average was 3.50 at the start and 1.00 "
                                     "at the end of the run, above its 2 cores"),
              std::string::npos)
        << runWarnings(r)[0];
    r.loadAverageStart = std::nullopt;  // a system without getloadavg
    r.loadAverageEnd = 2.5;
    EXPECT_TRUE(anyContains(runWarnings(r), "was 2.50 at the end of the run"));
    r.repeat = 1;
    EXPECT_EQ(runWarnings(r).size(), 2u);
}

TEST(BenchWarnings, LoadAveragesRoundTripAndAMergedReportWarnsPerShard) {
    const fs::path dir = fs::path(VKRAY_TEST_OUTPUT_DIR) / "bench-warnings";
    fs::remove_all(dir);
    BenchResults r = results();
    r.loadAverageStart = 0.25;
    r.loadAverageEnd = 7.5;
    writeBenchReport(r, dir);
    const BenchResults back = readBenchReport(dir);
    EXPECT_EQ(back.loadAverageStart.value_or(-1.0), 0.25);
    EXPECT_EQ(back.loadAverageEnd.value_or(-1.0), 7.5);
    EXPECT_EQ(runWarnings(back), runWarnings(r));
    fs::remove_all(dir);

    BenchResults merged = results();
    ShardInfo quiet, busy;
    quiet.shard = {0, 2};
    quiet.hardwareThreads = 8;
    quiet.loadAverageStart = 1.0;
    busy.shard = {1, 2};
    busy.node = "node-b";
    busy.hardwareThreads = 4;
    busy.loadAverageEnd = 6.0;
    merged.shards = {quiet, busy};
    merged.loadAverageEnd = 100.0;  // a merged report's own figures are not a run's
    const std::vector<std::string> w = runWarnings(merged);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0].rfind("shard 1/2 on node-b: the machine was busy", 0), 0u) << w[0];
}

// ---- The summary across scenes ---------------------------------------------------------------

TEST(BenchSummary, GeometricMeanOfTheRatiosToEmbree) {
    const BenchResults r = twoScenes(10.0, 25.0);
    const std::optional<Table> t = summaryTable(r);
    ASSERT_TRUE(t);
    EXPECT_EQ(t->title, "Camera rays across scenes: rate over Embree rtcIntersect1's");
    EXPECT_EQ(t->columns, (std::vector<std::string>{"accel", "alpha", "beta", "geometric mean"}));
    ASSERT_EQ(t->rows.size(), 3u);  // bvh, kd-stack, kd-restart: in order of first appearance
    // bvh: 10/20 and 25/50, mean 0.5; kd-stack: 10/40 and 25/12.5, mean sqrt(0.5).
    EXPECT_EQ(t->rows[0], (std::vector<std::string>{"bvh", "0.50x", "0.50x", "0.50x"}));
    EXPECT_EQ(t->rows[1], (std::vector<std::string>{"kd-stack", "0.25x", "2.00x", "0.71x ★"}));
    // A higher mean, but over one scene only: not the one marked.
    EXPECT_EQ(t->rows[2], (std::vector<std::string>{"kd-restart", "—", "1.00x", "1.00x (over 1 of 2 scenes)"}));
    EXPECT_EQ(t->marked, (std::vector<bool>{false, true, false}));
    EXPECT_TRUE(anyContains(t->notes, "over Embree rtcIntersect1"));
}

TEST(BenchSummary, FallsBackToBvhAndNeedsTwoScenes) {
    BenchResults r = twoScenes(10.0, 0.0);  // beta has no Embree figure: every ratio is to bvh
    const std::optional<Table> t = summaryTable(r);
    ASSERT_TRUE(t);
    EXPECT_EQ(t->title, "Camera rays across scenes: rate over bvh's");
    EXPECT_EQ(t->rows[1], (std::vector<std::string>{"kd-stack", "0.50x", "4.00x", "1.41x ★"}));
    EXPECT_TRUE(anyContains(t->notes, "over bvh's"));
    r.scenes[1].accels.erase(r.scenes[1].accels.begin());  // and no bvh there either
    ASSERT_TRUE(summaryTable(r));
    EXPECT_TRUE(summaryTable(r)->rows.empty());
    EXPECT_NE(summaryTable(r)->whenEmpty.find("neither Embree nor bvh"), std::string::npos);
    r.scenes.pop_back();
    EXPECT_FALSE(summaryTable(r));  // one scene: its own tables say it all
}

// ---- report.html against bench.md ----------------------------------------------------------

TEST(BenchHtml, ShowsEveryTableOfTheMarkdownAndTheSummary) {
    const BenchResults r = twoScenes(10.0, 25.0);
    const std::string md = benchMarkdown(r), html = benchHtml(r);
    static const std::regex heading("\n### ([^\n]+)\n");
    size_t tables = 0;
    for (auto it = std::sregex_iterator(md.begin(), md.end(), heading); it != std::sregex_iterator(); ++it, ++tables)
        EXPECT_NE(html.find("<h3>" + escapeXml((*it)[1].str()) + "</h3>"), std::string::npos) << (*it)[1];
    EXPECT_EQ(tables, 1 + 2 * sceneTables(r.scenes[0]).size());  // the summary, then each scene's
    EXPECT_NE(md.find("## Summary\n\n### Camera rays across scenes"), std::string::npos);
    EXPECT_NE(html.find("<section id=\"summary\">"), std::string::npos);
    EXPECT_NE(html.find("<a href=\"#summary\">Summary</a>"), std::string::npos);
    EXPECT_NE(html.find("<td class=\"num\">0.71x ★</td>"), std::string::npos);
    EXPECT_EQ(count(html, "<h3>Primary rays against Embree</h3>"), 2u);
    EXPECT_EQ(count(html, "<svg class=\"plot bar-chart\""), 2u);
}

TEST(BenchHtml, CameraRayChartHasABarPerAcceleratorAndEmbreeAsReference) {
    SceneResult s = twoScenes(10.0, 25.0).scenes[1];
    s.accels.push_back(makeAccel("bvh-fast", 3.0, oneAndTwoThreads(10.0, 6.0), 8, 6, 10));
    s.accels.back().rayKinds[0].mraysPerSecond = std::nullopt;  // no camera-ray rate: no bar
    s.accels.push_back(s.accels[0]);
    s.accels.back().accel = "octree";  // in no family this build knows: "other"
    const std::string svg = cameraRayChartSvg(s);
    EXPECT_EQ(count(svg, "<g class=\"bar\">"), 4u);
    EXPECT_EQ(count(svg, "<g class=\"reference\">"), 2u);  // rtcIntersect1 and rtcIntersect16
    EXPECT_NE(svg.find("<title>Embree 3.13.5 rtcIntersect1: "), std::string::npos);
    // kd-stack: 48 rays in 12.5 ms (11.25 to 15 ms), 2.00x Embree.
    EXPECT_NE(svg.find("<title>kd-stack: camera rays 0.0038 Mrays/s (0.0032–0.0043), 12.5 (11.2–15.0) ms, 2.00x "
                       "Embree rtcIntersect1</title>"),
              std::string::npos)
        << svg;
    EXPECT_NE(svg.find(">0.0038 · 2.00x Embree</text>"), std::string::npos);
    for (const std::string legend : {">BVH</text>", ">kd-tree</text>", ">other</text>"})
        EXPECT_NE(svg.find(legend), std::string::npos) << legend;
    s.accels.clear();
    EXPECT_EQ(cameraRayChartSvg(s), "");
}

TEST(BenchHtml, TheTwoHeatmapsSitSideBySideEachOnItsOwnScale) {
    const BenchResults r = results();
    const std::string html = benchHtml(r);
    for (const SceneResult& s : r.scenes)
        for (const AccelResult& a : s.accels) {
            const std::regex pair("<div class=\"pair\">\n<figure><img[^>]*alt=\"" + a.accel +
                                  ": nodes per pixel, all rays\"[^\n]*\n<figure><img[^>]*alt=\"" + a.accel +
                                  ": nodes per pixel, camera rays\"");
            EXPECT_TRUE(std::regex_search(html, pair)) << a.accel;
        }
    EXPECT_NE(html.find("Nodes visited per pixel by camera rays, one scale"), std::string::npos);
    // The fixture's camera rays visit about half the nodes of all rays: a scale of their own.
    const SceneResult& s = r.scenes[0];
    EXPECT_EQ(heatmapScale(s, HeatmapRays::All).max, 46.0);
    EXPECT_EQ(heatmapScale(s, HeatmapRays::Camera).max, 22.0);
}

TEST(SvgBarChart, DrawsWhatIsFiniteAndPositive) {
    BarChartOptions o;
    o.title = "t";
    o.swatches = {{"BVH", "#0072B2"}};
    const std::vector<Bar> bars = {{"a", 2.0, 1.5, 2.5, "2.0", "a: 2", "#0072B2"},
                                   {"b", 1.0, 1.0, 1.0, "1.0", "b: 1", "#0072B2"},   // no spread
                                   {"c", std::nan(""), 0.0, 0.0, "", "", "#0072B2"}};  // left out
    // A reference spread far beyond the bars (a baseline on a busy machine): the axis ends near the
    // bars, and its whisker is cut there, without a cap.
    const std::vector<ReferenceLine> refs = {{"E", 3.0, 2.8, 30.0, "#0000ff", true}, {"none", 0.0, 0.0, 0.0, "#222", true}};
    const std::string svg = svgBarChart(o, bars, refs);
    EXPECT_EQ(count(svg, "<g class=\"bar\">"), 2u);
    EXPECT_EQ(count(svg, "<g class=\"reference\">"), 1u);
    EXPECT_EQ(count(svg, "stroke=\"#222\" stroke-width=\"1.3\""), 3u);  // one error bar: the line and two caps
    EXPECT_EQ(count(svg, "stroke=\"#0000ff\" stroke-width=\"1.3\""), 2u);  // the whisker and its low cap
    EXPECT_NE(svg.find("stroke-dasharray=\"6 4\""), std::string::npos);
    EXPECT_NE(svg.find(">3</text>"), std::string::npos);
    EXPECT_EQ(svg.find(">30</text>"), std::string::npos);
    EXPECT_NE(svg.find(">a</text>"), std::string::npos);
    EXPECT_EQ(svg.find(">c</text>"), std::string::npos);
}
