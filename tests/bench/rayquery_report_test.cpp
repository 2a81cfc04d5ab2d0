// rayquery in the reports: named as the driver's own BVH and traversal where accelerators are listed,
// its build the driver's on the device (kept out of the CPU build scaling), and every accelerator's
// camera-ray rate over rayquery's ("x rayquery") in the primary-ray table, the console summary and
// bench.json, also after bench.json is read back and after `vkray bench --merge`. On synthetic
// results (report_fixture.h): no device needed.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/bench_json.h"
#include "bench/bench_merge.h"
#include "bench/bench_shard.h"
#include "bench/report.h"
#include "bench/report_tables.h"
#include "core/error.h"
#include "report_fixture.h"

namespace fs = std::filesystem;
using namespace vkray;
using namespace vkray::bench;
using namespace vkray::bench::fixture;

namespace {

const std::string kAbout =
    "rayquery: the driver's own BVH and traversal (VK_KHR_ray_query; in hardware on GPUs with ray-tracing units); "
    "its build is the driver's on the device";

// Camera rays: bvh 20 ms, kd-ropes 40 ms, rayquery 50 ms; Embree 10 ms.
AccelResult cameraAccel(const std::string& name, double cameraMs) {
    AccelResult a = makeAccel(name, 2.0 * cameraMs, oneAndTwoThreads(10.0, 6.0), 8, 6, 10);
    a.primaryOnlyMs = around(cameraMs);
    a.rayKinds[0].mraysPerSecond = mraysPerSecond(48.0, cameraMs);
    return a;
}

AccelResult rayQuery() {
    AccelResult a = cameraAccel("rayquery", 50.0);
    a.build = {{4, around(3.0)}};  // the driver's, at the run's most threads
    a.buildOnDevice = true;
    a.traversalCounted = false;  // the driver's traversal has no counters
    a.nodesPerRay = a.leavesPerRay = a.trianglesPerRay = a.primaryNodesPerRay = 0.0;
    a.nodesPerPixel.clear();
    a.primaryNodesPerPixel.clear();
    a.buildStats.clear();
    a.structureBytes = 98304;
    return a;
}

SceneResult sceneWith(const std::vector<std::string>& names) {
    SceneResult s = fullScene();
    s.accels.clear();
    for (const std::string& n : names)
        s.accels.push_back(n == "rayquery" ? rayQuery() : cameraAccel(n, n == "bvh" ? 20.0 : 40.0));
    s.embree.version = "Embree 3.13.5";
    s.embree.threads = 2;
    s.embree.agreement = 1.0;
    s.embree.singleSamples = {9.0, 10.0, 11.0};
    s.embree.packetSamples = {7.0, 8.0, 9.0};
    s.embree.singleMs = spreadOf(s.embree.singleSamples);
    s.embree.packetMs = spreadOf(s.embree.packetSamples);
    return s;
}

BenchResults oneScene(SceneResult s) {
    BenchResults r = results();
    r.scenes = {std::move(s)};
    return r;
}

bool anyContains(const std::vector<std::string>& texts, const std::string& part) {
    for (const std::string& t : texts)
        if (t.find(part) != std::string::npos) return true;
    return false;
}

// The "x rayquery" cell of each row, by tracer.
std::vector<std::pair<std::string, std::string>> rayQueryColumn(const Table& t) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& row : t.rows) out.emplace_back(row[0], row[5]);
    return out;
}

void expectRayQueryFigures(const BenchResults& r, const std::string& where) {
    const SceneResult& s = r.scenes[0];
    const Table e = embreeTable(s);
    ASSERT_EQ(e.columns.size(), 8u) << where;
    EXPECT_EQ(e.columns[4], "vs bvh") << where;
    EXPECT_EQ(e.columns[5], "x rayquery") << where;
    const std::vector<std::pair<std::string, std::string>> expected{{"Embree 3.13.5 rtcIntersect1", "—"},
                                                                    {"Embree 3.13.5 rtcIntersect16", "—"},
                                                                    {"bvh", "2.50x"},
                                                                    {"kd-ropes", "1.25x"},
                                                                    {"rayquery", "1.00x"}};
    EXPECT_EQ(rayQueryColumn(e), expected) << where;
    for (const auto& row : e.rows) EXPECT_EQ(row.size(), e.columns.size()) << where << ": " << row[0];
    EXPECT_TRUE(anyContains(e.notes, kAbout)) << where;
    EXPECT_TRUE(anyContains(acceleratorTable(s).notes, kAbout)) << where;

    const std::string summary = benchSummary(r);
    EXPECT_NE(summary.find("(0.500x Embree, 2.50x rayquery)"), std::string::npos) << where << "\n" << summary;
    EXPECT_NE(summary.find("(0.250x Embree, 0.50x bvh, 1.25x rayquery)"), std::string::npos) << where;
    EXPECT_NE(summary.find("(0.200x Embree, 0.40x bvh)\n"), std::string::npos) << where;  // rayquery's own line
    EXPECT_NE(summary.find("\n  " + kAbout), std::string::npos) << where;

    const nlohmann::json j = nlohmann::json::parse(benchJson(r))["scenes"][0]["accelerators"];
    ASSERT_EQ(j.size(), 3u) << where;
    EXPECT_DOUBLE_EQ(j[0]["primary_vs_rayquery"].get<double>(), 2.5) << where;
    EXPECT_DOUBLE_EQ(j[1]["primary_vs_rayquery"].get<double>(), 1.25) << where;
    EXPECT_EQ(j[0]["build_on"], "cpu") << where;
    EXPECT_EQ(j[2]["build_on"], "device") << where;
    EXPECT_FALSE(j[0].contains("about")) << where;
    EXPECT_EQ(j[2]["about"], accelAbout("rayquery")) << where;
    EXPECT_EQ(j[2]["structure_bytes"].get<uint64_t>(), 98304u) << where;
}

}  // namespace

TEST(RayQueryReport, NamedAndTheRatioToItInEveryPlace) {
    expectRayQueryFigures(oneScene(sceneWith({"bvh", "kd-ropes", "rayquery"})), "run");
    const BenchResults r = oneScene(sceneWith({"bvh", "kd-ropes", "rayquery"}));
    const std::string md = benchMarkdown(r), html = benchHtml(r);
    EXPECT_NE(md.find("| x rayquery |"), std::string::npos);
    EXPECT_NE(md.find(kAbout), std::string::npos);
    EXPECT_NE(html.find("<th>x rayquery</th>"), std::string::npos);
    EXPECT_EQ(accelAbout("bvh"), "");
    EXPECT_EQ(accelAbout("rayquery:rq-compact=0"), accelAbout("rayquery"));  // tuning does not change what it is
}

// No counters: its per-ray cells say "—", never a measured-looking 0.00; bench.json has null.
TEST(RayQueryReport, CountersNotMeasuredAreNotShownAsZero) {
    const BenchResults r = oneScene(sceneWith({"bvh", "rayquery"}));
    const std::string summary = benchSummary(r);
    const size_t line = summary.find("  rayquery");
    ASSERT_NE(line, std::string::npos) << summary;
    const std::string row = summary.substr(line, summary.find('\n', line) - line);
    EXPECT_NE(row.find("— nodes/ray"), std::string::npos) << row;
    EXPECT_EQ(perRayCell(r.scenes[0].accels[1], 0.0), "—");
    EXPECT_EQ(perRayCell(r.scenes[0].accels[0], 6.0), "6.00");
    const nlohmann::json j = nlohmann::json::parse(benchJson(r));
    EXPECT_TRUE(j["scenes"][0]["accelerators"][1]["per_ray"].is_null());
    EXPECT_TRUE(j["scenes"][0]["accelerators"][1]["per_primary_ray"].is_null());
    EXPECT_FALSE(j["scenes"][0]["accelerators"][0]["per_ray"].is_null());
}

TEST(RayQueryReport, WithoutRayQueryNoColumnNoteOrRatio) {
    const BenchResults r = oneScene(sceneWith({"bvh", "kd-ropes"}));
    const Table e = embreeTable(r.scenes[0]);
    EXPECT_EQ(e.columns, (std::vector<std::string>{"tracer", "camera rays ms", "Mrays/s", "vs Embree rtcIntersect1",
                                                   "vs bvh", "node steps a ray", "SIMD efficiency"}));
    EXPECT_FALSE(anyContains(e.notes, "rayquery"));
    EXPECT_EQ(benchSummary(r).find("rayquery"), std::string::npos);
    const nlohmann::json j = nlohmann::json::parse(benchJson(r))["scenes"][0]["accelerators"];
    EXPECT_TRUE(j[0]["primary_vs_rayquery"].is_null());
}

TEST(RayQueryReport, TheDriversBuildIsNotInTheCpuBuildScaling) {
    const SceneResult s = sceneWith({"bvh", "kd-ropes", "rayquery"});
    EXPECT_EQ(buildThreadCounts(s), (std::vector<int>{1, 2}));
    const Table t = buildScalingTable(s);
    ASSERT_EQ(t.rows.size(), 2u);
    for (const auto& row : t.rows) EXPECT_NE(row[0], "rayquery");
    // The accelerator table shows the driver's build as rayquery's build.
    const Table a = acceleratorTable(s);
    EXPECT_EQ(a.rows[2][0], "rayquery");
    EXPECT_EQ(a.rows[2][1], formatSpread(around(3.0)));
    EXPECT_EQ(a.rows[2][2], formatBytes(98304));
}

TEST(RayQueryReport, BenchJsonReadBackKeepsTheDeviceBuildAndTheRatios) {
    const fs::path dir = fs::path(VKRAY_TEST_OUTPUT_DIR) / "rayquery-report";
    fs::remove_all(dir);
    const BenchResults r = oneScene(sceneWith({"bvh", "kd-ropes", "rayquery"}));
    writeBenchReport(r, dir);
    const BenchResults back = readBenchReport(dir);
    ASSERT_EQ(back.scenes.size(), 1u);
    ASSERT_EQ(back.scenes[0].accels.size(), 3u);
    EXPECT_FALSE(back.scenes[0].accels[0].buildOnDevice);
    EXPECT_TRUE(back.scenes[0].accels[2].buildOnDevice);
    EXPECT_TRUE(back.scenes[0].accels[0].traversalCounted);
    EXPECT_FALSE(back.scenes[0].accels[2].traversalCounted);
    expectRayQueryFigures(back, "read back");
    EXPECT_EQ(benchSummary(back), benchSummary(r));

    // A report from before the field: a CPU build. A value that is neither: refused, naming it.
    nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "bench.json"));
    j["scenes"][0]["accelerators"][2].erase("build_on");
    j["scenes"][0]["accelerators"][1]["build_on"] = "gpu";
    std::ofstream(dir / "bench.json") << j.dump();
    try {
        readBenchReport(dir);
        ADD_FAILURE() << "build_on \"gpu\" was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("build_on\": \"gpu\""), std::string::npos) << e.what();
    }
    j["scenes"][0]["accelerators"][1].erase("build_on");
    std::ofstream(dir / "bench.json") << j.dump();
    EXPECT_FALSE(readBenchReport(dir).scenes[0].accels[2].buildOnDevice);
    fs::remove_all(dir);
}

// Two shards, rayquery in one of them: the merged report has the driver's build and every ratio to
// rayquery, as one run would.
TEST(RayQueryReport, MergedShardsKeepTheDeviceBuildAndTheRatios) {
    BenchSettings settings;
    settings.scenes = {"scenes/synthetic.scene"};
    settings.accels = {"bvh", "kd-ropes", "rayquery"};
    settings.repeat = 3;
    settings.threads = {1, 2};
    settings.maxDepthSweep = false;
    const std::vector<Configuration> list = configurationList(settings);
    const fs::path root = fs::path(VKRAY_TEST_OUTPUT_DIR) / "rayquery-merge";
    fs::remove_all(root);
    std::vector<fs::path> dirs;
    for (int i = 0; i < 2; ++i) {
        const SceneWork work = shardWork(settings, {i, 2})[0];
        SceneResult s = sceneWith(work.accels);
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
    ASSERT_EQ(merged.scenes[0].accels.size(), 3u);
    EXPECT_EQ(merged.scenes[0].accels[2].accel, "rayquery");
    EXPECT_TRUE(merged.scenes[0].accels[2].buildOnDevice);
    expectRayQueryFigures(merged, "merged");
    fs::remove_all(root);
}
