// One Embree figure per scene: every accelerator's camera-ray ratio to Embree divides by the median
// of all the scene's interleaved Embree runs, so the ratios order the accelerators as their rates do
// in every place that shows them (the console summary, bench.md's and report.html's tables, the
// chart, bench.json), also after `vkray bench --merge` of shards that each ran a part of them.
// On synthetic results whose per-accelerator Embree runs drift as a loaded machine's do.
#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/bench_json.h"
#include "bench/bench_merge.h"
#include "bench/bench_shard.h"
#include "bench/report.h"
#include "bench/report_plots.h"
#include "bench/report_tables.h"
#include "report_fixture.h"

namespace fs = std::filesystem;
using namespace vkray;
using namespace vkray::bench;
using namespace vkray::bench::fixture;

namespace {

constexpr int kWidth = 640, kHeight = 480;
constexpr double kRays = double(kWidth) * double(kHeight);

struct Timed {
    std::string name;
    std::vector<double> cameraMs;   // its camera-ray renders
    std::vector<double> embreeMs;   // Embree rtcIntersect1 in the same repeats
};

// The drift of the user's report: bvh (2.89 Mrays/s) ran while Embree was fast and kd-stack
// (3.19 Mrays/s) while it was slow, so against its own Embree runs the faster kd-stack got the
// smaller ratio (0.377x against 0.442x).
const std::vector<Timed> kTimed = {
    {"bvh", {105.0, 106.3, 108.0}, {46.0, 47.0, 47.5}},
    {"kd-stack", {95.0, 96.3, 99.0}, {35.5, 36.3, 37.0}},
    {"bvh-fast", {120.0, 121.0, 125.0}, {40.0, 41.0, 43.0}},
    {"kd-restart", {180.0, 182.0, 190.0}, {52.0, 53.0, 55.0}},
};

AccelResult timedAccel(const Timed& t) {
    AccelResult a = makeAccel(t.name, 300.0, oneAndTwoThreads(10.0, 6.0), 8, 6, 10);
    a.primaryOnlyMs = spreadOf(t.cameraMs);
    a.rayKinds[0].mraysPerSecond = mraysPerSecond(kRays, a.primaryOnlyMs.median);
    a.embreeSingleMs = spreadOf(t.embreeMs);
    a.embreePacketMs = spreadOf(t.embreeMs);
    return a;
}

// A scene with the accelerators of `names`, its Embree figures pooled from their runs as the runner
// pools them.
SceneResult sceneOf(const std::vector<std::string>& names) {
    SceneResult s = fullScene();
    s.width = kWidth;
    s.height = kHeight;
    s.accels.clear();
    s.embree.version = "Embree 3.13.5";
    s.embree.threads = 2;
    s.embree.agreement = 0.999;
    for (const Timed& t : kTimed) {
        if (std::find(names.begin(), names.end(), t.name) == names.end()) continue;
        s.accels.push_back(timedAccel(t));
        s.embree.singleSamples.insert(s.embree.singleSamples.end(), t.embreeMs.begin(), t.embreeMs.end());
    }
    s.embree.packetSamples = s.embree.singleSamples;
    s.embree.singleMs = spreadOf(s.embree.singleSamples);
    s.embree.packetMs = spreadOf(s.embree.packetSamples);
    return s;
}

std::vector<std::string> allNames() {
    std::vector<std::string> out;
    for (const Timed& t : kTimed) out.push_back(t.name);
    return out;
}

// Accelerator name -> (rate, ratio), as one place shows them.
using Shown = std::map<std::string, std::pair<double, double>>;

// Every pair of accelerators: the higher rate has the higher ratio.
void expectRatiosOrderAsRates(const Shown& shown, const std::string& where) {
    ASSERT_EQ(shown.size(), kTimed.size()) << where;
    for (const auto& [a, x] : shown)
        for (const auto& [b, y] : shown)
            if (x.first > y.first) {
                EXPECT_GE(x.second, y.second) << where << ": " << a << " against " << b;
            }
}

Shown fromTable(const Table& t) {
    Shown out;
    for (const auto& row : t.rows)
        if (row[0].rfind("Embree", 0) != 0) out[row[0]] = {std::stod(row[2]), std::stod(row[3])};
    return out;
}

Shown fromJson(const nlohmann::json& scene) {
    Shown out;
    for (const auto& a : scene["accelerators"])
        out[a["accel"].get<std::string>()] = {a["ray_kinds"][0]["mrays_per_s"].get<double>(),
                           a["embree_interleaved"]["primary_vs_intersect1"].get<double>()};
    return out;
}

Shown fromConsole(const std::string& summary) {
    Shown out;
    static const std::regex line(R"(\n  (\S+) +build .*camera rays +([0-9.]+) Mrays/s \(([0-9.]+)x Embree)");
    for (auto it = std::sregex_iterator(summary.begin(), summary.end(), line); it != std::sregex_iterator(); ++it)
        out[(*it)[1]] = {std::stod((*it)[2]), std::stod((*it)[3])};
    return out;
}

Shown fromChart(const std::string& svg) {
    Shown out;
    static const std::regex bar(R"(<title>(\S+): camera rays ([0-9.]+) Mrays/s.*?, ([0-9.]+)x Embree)");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), bar); it != std::sregex_iterator(); ++it)
        out[(*it)[1]] = {std::stod((*it)[2]), std::stod((*it)[3])};
    return out;
}

BenchResults oneScene(SceneResult s) {
    BenchResults r = results();
    r.scenes = {std::move(s)};
    return r;
}

}  // namespace

TEST(EmbreeRatio, EveryRatioDividesByTheMedianOfAllTheScenesEmbreeRuns) {
    const SceneResult s = sceneOf(allNames());
    // 12 runs: the median is the mean of the 6th and 7th, 43.0 and 46.0 ms.
    ASSERT_EQ(s.embree.singleSamples.size(), 12u);
    EXPECT_DOUBLE_EQ(s.embree.singleMs.median, 44.5);
    for (const AccelResult& a : s.accels) {
        ASSERT_TRUE(primaryVsEmbree(s, a)) << a.accel;
        EXPECT_DOUBLE_EQ(*primaryVsEmbree(s, a), 44.5 / a.primaryOnlyMs.median) << a.accel;
    }
    // kd-stack is the fastest and has the highest ratio; against its own runs it had not.
    const AccelResult& bvh = s.accels[0];
    const AccelResult& kd = s.accels[1];
    ASSERT_GT(*kd.primaryMrays(), *bvh.primaryMrays());
    EXPECT_LT(kd.embreeSingleMs->median / kd.primaryOnlyMs.median, bvh.embreeSingleMs->median / bvh.primaryOnlyMs.median);
    EXPECT_GT(*primaryVsEmbree(s, kd), *primaryVsEmbree(s, bvh));
    // vs bvh is the quotient of the two ratios to Embree, and the quotient of the rates.
    EXPECT_DOUBLE_EQ(*primaryVs(s, kd, "bvh"), *primaryVsEmbree(s, kd) / *primaryVsEmbree(s, bvh));
    EXPECT_DOUBLE_EQ(*primaryVs(s, kd, "bvh"), *kd.primaryMrays() / *bvh.primaryMrays());
    // Without Embree there is no ratio, whatever the accelerator's own runs say.
    SceneResult none = s;
    none.embree = {};
    EXPECT_FALSE(primaryVsEmbree(none, kd));
}

TEST(EmbreeRatio, EveryPlaceOrdersTheRatiosAsTheRates) {
    const BenchResults r = oneScene(sceneOf(allNames()));
    const SceneResult& s = r.scenes[0];
    expectRatiosOrderAsRates(fromTable(embreeTable(s)), "embree table");
    expectRatiosOrderAsRates(fromJson(nlohmann::json::parse(benchJson(r))["scenes"][0]), "bench.json");
    expectRatiosOrderAsRates(fromConsole(benchSummary(r)), "console summary");
    expectRatiosOrderAsRates(fromChart(cameraRayChartSvg(s)), "camera-ray chart");
    // bench.md and report.html render the same table.
    const std::string md = benchMarkdown(r), html = benchHtml(r);
    EXPECT_NE(html.find("<h3>Primary rays against Embree</h3>"), std::string::npos);
    for (const auto& row : embreeTable(s).rows) {
        EXPECT_NE(md.find("| " + row[0] + " | " + row[1] + " | " + row[2] + " | " + row[3] + " |"), std::string::npos)
            << row[0];
        EXPECT_NE(html.find("<td class=\"num\">" + row[3] + "</td>"), std::string::npos) << row[0];
    }
}

// Two shards, each with some of the accelerators and the Embree runs interleaved with them: the
// merged report divides every ratio by the median of both shards' Embree runs.
TEST(EmbreeRatio, MergedShardsShareOneEmbreeFigure) {
    BenchSettings settings;
    settings.scenes = {"scenes/synthetic.scene"};
    settings.accels = allNames();
    settings.repeat = 3;
    settings.threads = {1, 2};
    settings.maxDepthSweep = false;
    const std::vector<Configuration> list = configurationList(settings);
    const fs::path root = fs::path(VKRAY_TEST_OUTPUT_DIR) / "embree-ratio-merge";
    fs::remove_all(root);
    std::vector<fs::path> dirs;
    std::vector<double> everyRun;
    for (int i = 0; i < 2; ++i) {
        const SceneWork work = shardWork(settings, {i, 2})[0];
        SceneResult s = sceneOf(work.accels);
        everyRun.insert(everyRun.end(), s.embree.singleSamples.begin(), s.embree.singleSamples.end());
        s.file = settings.scenes[0];
        s.errorPoints.clear();
        s.deltas.clear();
        s.concurrent.reset();
        if (work.concurrent) s.concurrent = fullScene().concurrent;
        for (const std::string& label : work.labels) s.configurations.push_back({label, i});
        BenchResults r = oneScene(s);
        r.settings = settings;
        r.shard = {i, 2};
        r.configurationCount = list.size();
        r.configurationHash = configurationHash(list);
        dirs.push_back(root / ("shard-" + std::to_string(i)));
        writeBenchReport(r, dirs.back());
    }
    const BenchResults merged = mergeBenchReports(dirs, "merge");
    ASSERT_EQ(merged.scenes.size(), 1u);
    const SceneResult& s = merged.scenes[0];
    ASSERT_EQ(s.accels.size(), kTimed.size());
    EXPECT_EQ(s.embree.singleSamples.size(), everyRun.size());
    EXPECT_DOUBLE_EQ(s.embree.singleMs.median, spreadOf(everyRun).median);
    EXPECT_DOUBLE_EQ(s.embree.singleMs.median, 44.5);
    for (const AccelResult& a : s.accels)
        EXPECT_DOUBLE_EQ(*primaryVsEmbree(s, a), 44.5 / a.primaryOnlyMs.median) << a.accel;

    writeBenchReport(merged, root / "merged");
    const nlohmann::json j = nlohmann::json::parse(benchJson(merged));
    EXPECT_DOUBLE_EQ(j["scenes"][0]["embree"]["intersect1_ms"]["median"].get<double>(), 44.5);
    expectRatiosOrderAsRates(fromJson(j["scenes"][0]), "merged bench.json");
    expectRatiosOrderAsRates(fromTable(embreeTable(s)), "merged embree table");
    expectRatiosOrderAsRates(fromConsole(benchSummary(merged)), "merged console summary");
    fs::remove_all(root);
}
