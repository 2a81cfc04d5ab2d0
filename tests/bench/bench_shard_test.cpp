// `vkray bench --shard I/N` and `--merge` (bench_shard.h, bench_merge.h): the configuration list and
// its split, then a real run on lavapipe — unsharded and in 3 shards — whose merge must list exactly
// what the unsharded run lists, every figure the one its shard measured, and whose reader must give
// back every figure as written. The refusals of --merge, one by one. Times are never compared.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/bench_json.h"
#include "bench/bench_merge.h"
#include "bench/bench_runner.h"
#include "bench/bench_shard.h"
#include "bench/report.h"
#include "core/error.h"
#include "render/device.h"

namespace vkray::bench {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

std::vector<std::string> labelsOf(const std::vector<Configuration>& list, int scene) {
    std::vector<std::string> out;
    for (const Configuration& c : list)
        if (c.scene == scene) out.push_back(c.label);
    return out;
}

BenchSettings settingsOf(std::vector<std::string> accels) {
    BenchSettings s;
    s.scenes = {"a.scene", "b.scene"};
    s.accels = std::move(accels);
    s.repeat = 1;
    s.threads = {1};
    s.deltas = {4, 8};
    return s;
}

TEST(BenchShard, ConfigurationListInRunOrder) {
    const std::vector<Configuration> list = configurationList(settingsOf({"bvh", "kd-stack", "bvh-fast"}));
    ASSERT_EQ(list.size(), 16u);
    const std::vector<std::string> expected = {"reference",   "accel bvh",   "accel kd-stack",
                                               "accel bvh-fast", "concurrent bvh+kd-stack", "aac-delta 4",
                                               "aac-delta 8", "maxdepth-sweep"};
    EXPECT_EQ(labelsOf(list, 0), expected);
    EXPECT_EQ(labelsOf(list, 1), expected);

    BenchSettings noSweep = settingsOf({"bvh", "bvh-fast"});  // no kd-tree: no concurrent build
    noSweep.maxDepthSweep = false;
    noSweep.deltas.clear();
    EXPECT_EQ(labelsOf(configurationList(noSweep), 1),
              (std::vector<std::string>{"reference", "accel bvh", "accel bvh-fast"}));
}

TEST(BenchShard, HashFollowsTheList) {
    const BenchSettings s = settingsOf({"bvh", "kd-stack"});
    EXPECT_EQ(configurationHash(configurationList(s)), configurationHash(configurationList(s)));
    EXPECT_EQ(configurationHash(configurationList(s)).size(), 16u);
    EXPECT_NE(configurationHash(configurationList(s)), configurationHash(configurationList(settingsOf({"bvh"}))));
}

TEST(BenchShard, EveryConfigurationInExactlyOneShardRoundRobin) {
    const BenchSettings s = settingsOf({"bvh", "kd-stack", "kd-restart"});
    const std::vector<Configuration> list = configurationList(s);
    for (int n = 1; n <= 7; ++n) {
        std::vector<std::multiset<std::string>> seen(s.scenes.size());
        for (int i = 0; i < n; ++i) {
            const std::vector<SceneWork> work = shardWork(s, {i, n});
            for (size_t scene = 0; scene < work.size(); ++scene)
                for (const std::string& label : work[scene].labels) seen[scene].insert(label);
        }
        for (size_t scene = 0; scene < s.scenes.size(); ++scene) {
            const std::vector<std::string> all = labelsOf(list, int(scene));
            EXPECT_EQ(seen[scene], std::multiset<std::string>(all.begin(), all.end())) << n << " shards";
        }
    }
    // Shard 1 of 3 holds configurations 1, 4, 7, ... of the list.
    const std::vector<SceneWork> work = shardWork(s, {1, 3});
    EXPECT_EQ(work[0].labels, (std::vector<std::string>{"accel bvh", "concurrent bvh+kd-stack", "maxdepth-sweep"}));
    EXPECT_TRUE(work[0].concurrent);
    EXPECT_TRUE(work[0].maxDepthSweep);
    EXPECT_EQ(work[0].accels, std::vector<std::string>{"bvh"});
}

TEST(BenchShard, ParseShard) {
    EXPECT_EQ(parseShard("0/4").index, 0);
    EXPECT_EQ(parseShard("3/4").count, 4);
    for (const char* bad : {"4/4", "-1/4", "1/0", "a/b", "1", "1/4x", "", "/4", "1/"}) {
        try {
            parseShard(bad);
            ADD_FAILURE() << bad << " accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("--shard " + std::string(bad) + ": expected I/N"), std::string::npos)
                << e.what();
        }
    }
}

// ---- A real run, unsharded and in 3 shards ---------------------------------------------------

// One folder per process: CTest runs each test of this file in a process of its own, in parallel.
const fs::path kRoot = fs::path(VKRAY_TEST_OUTPUT_DIR) / ("bench-shards-" + std::to_string(getpid()));

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

Json readJson(const fs::path& p) { return Json::parse(readText(p)); }

class BenchShards : public ::testing::Test {
protected:
    static constexpr int kShards = 3;

    static void SetUpTestSuite() {
        const char* dev = std::getenv("VKRAY_TEST_DEVICE");
        render::Device device(gpu::ContextOptions{.validation = true, .device = dev ? dev : ""});
        BenchOptions o;
        o.scenes = {std::string(VKRAY_SOURCE_DIR) + "/scenes/objects.scene"};
        o.accels = {"bvh", "kd-stack"};
        o.width = 16;
        o.height = 12;
        o.repeat = 1;
        o.threads = {1};
        o.deltas = {8};
        fs::remove_all(kRoot);
        writeBenchReport(runBench(device, o, "unsharded"), kRoot / "all");
        for (int i = 0; i < kShards; ++i) {
            o.shard = {i, kShards};
            writeBenchReport(runBench(device, o, "shard"), shardDir(i));
        }
    }

    static void TearDownTestSuite() { fs::remove_all(kRoot); }

    static fs::path shardDir(int i) { return kRoot / ("shard-" + std::to_string(i)); }
    static std::vector<fs::path> shardDirs() { return {shardDir(0), shardDir(1), shardDir(2)}; }

    // A copy of shard 2 with its bench.json changed by `edit`.
    static fs::path tampered(const std::string& name, void (*edit)(Json&)) {
        const fs::path dir = kRoot / name;
        fs::remove_all(dir);
        fs::copy(shardDir(2), dir, fs::copy_options::recursive);
        Json j = readJson(dir / "bench.json");
        edit(j);
        std::ofstream(dir / "bench.json") << j.dump(2);
        return dir;
    }

    static std::string mergeError(const std::vector<fs::path>& dirs) {
        try {
            mergeBenchReports(dirs, "merge");
        } catch (const Error& e) {
            return e.what();
        }
        return "(merged)";
    }
};

// What a report lists, per scene: configurations, accelerator rows, delta rows, error points.
Json listing(const Json& report) {
    Json out = Json::array();
    for (const Json& s : report["scenes"]) {
        Json labels = Json::array(), accels = Json::array(), deltas = Json::array(), points = Json::array();
        for (const Json& c : s["configurations"]) labels.push_back(c["label"]);
        for (const Json& a : s["accelerators"]) accels.push_back(a["accel"]);
        for (const Json& d : s["aac_delta_sweep"]) deltas.push_back(d["aac_delta"]);
        for (const Json& p : s["error_vs_time"]) points.push_back(p["label"]);
        out.push_back({labels, accels, deltas, points, s["concurrent_build"].is_null()});
    }
    return out;
}

Json without(Json j, const char* key) {
    j.erase(key);
    return j;
}

TEST_F(BenchShards, MergeListsWhatTheUnshardedRunListsWithEachShardsFigures) {
    const fs::path out = kRoot / "merged";
    writeBenchReport(mergeBenchReports(shardDirs(), "merge"), out);
    const Json merged = readJson(out / "bench.json"), all = readJson(kRoot / "all" / "bench.json");
    EXPECT_EQ(listing(merged), listing(all));
    EXPECT_EQ(merged["configurations"], all["configurations"]);
    ASSERT_EQ(merged["shards"].size(), size_t(kShards));

    const Json& scene = merged["scenes"][0];
    ASSERT_EQ(scene["configurations"].size(), 6u);
    for (size_t k = 0; k < scene["configurations"].size(); ++k) {
        const Json& c = scene["configurations"][k];
        EXPECT_EQ(c["shard"].get<int>(), int(k % kShards)) << c.dump();  // round-robin
        const Json shard = readJson(shardDir(c["shard"].get<int>()) / "bench.json")["scenes"][0];
        const std::string label = c["label"].get<std::string>();
        if (label.starts_with("accel ")) {
            // primary_vs_bvh is a figure of two configurations, primary_vs_intersect1 one of the
            // accelerator and the scene's Embree figure over every shard: checked below.
            auto pick = [&](const Json& s) {
                for (const Json& a : s["accelerators"])
                    if (a["accel"] == label.substr(6)) {
                        Json j = without(without(a, "images"), "primary_vs_bvh");
                        if (j["embree_interleaved"].is_object()) j["embree_interleaved"].erase("primary_vs_intersect1");
                        return j;
                    }
                return Json();
            };
            EXPECT_FALSE(pick(scene).is_null()) << label;
            EXPECT_TRUE(pick(scene) == pick(shard)) << label;
        } else if (label.starts_with("concurrent ")) {
            EXPECT_EQ(scene["concurrent_build"], shard["concurrent_build"]);
        } else if (label.starts_with("aac-delta ")) {
            EXPECT_EQ(scene["aac_delta_sweep"][0], shard["aac_delta_sweep"][0]);
        } else if (label == "reference") {
            EXPECT_EQ(without(scene["reference"], "images"), without(shard["reference"], "images"));
        }
    }
    // kd-stack's rate over bvh's, which no shard holds both of, from the merged figures.
    const auto row = [&](const Json& s, const char* name) {
        for (const Json& a : s["accelerators"])
            if (a["accel"] == name) return a;
        return Json();
    };
    const Json bvh = row(scene, "bvh"), kd = row(scene, "kd-stack");
    ASSERT_FALSE(bvh.is_null() || kd.is_null());
    const double expected =
        bvh["primary_only_ms"]["median"].get<double>() / kd["primary_only_ms"]["median"].get<double>();
    ASSERT_TRUE(kd["primary_vs_bvh"].is_number());
    EXPECT_NEAR(kd["primary_vs_bvh"].get<double>(), expected, 1e-9 * expected);
    EXPECT_EQ(bvh["primary_vs_bvh"].get<double>(), 1.0);
    // One Embree figure: the median of every shard's Embree runs, the divisor of every ratio.
    if (scene["embree"].contains("version")) {
        std::vector<double> runs;
        for (int i = 0; i < kShards; ++i) {
            const Json e = readJson(shardDir(i) / "bench.json")["scenes"][0]["embree"];
            if (e.contains("intersect1_samples_ms"))
                for (const Json& v : e["intersect1_samples_ms"]) runs.push_back(v.get<double>());
        }
        ASSERT_EQ(runs.size(), 2u);  // two accelerators, --repeat 1
        const double median = 0.5 * (runs[0] + runs[1]);
        EXPECT_DOUBLE_EQ(scene["embree"]["intersect1_ms"]["median"].get<double>(), median);
        for (const Json& a : {bvh, kd})
            EXPECT_DOUBLE_EQ(a["embree_interleaved"]["primary_vs_intersect1"].get<double>(),
                             median / a["primary_only_ms"]["median"].get<double>())
                << a["accel"];
    }
    // Every error point, but for its Pareto mark (over the merged points), from its shard.
    std::vector<Json> shardPoints;
    for (int i = 0; i < kShards; ++i) {
        const Json report = readJson(shardDir(i) / "bench.json");
        for (const Json& q : report["scenes"][0]["error_vs_time"]) shardPoints.push_back(without(q, "pareto"));
    }
    for (const Json& p : scene["error_vs_time"])
        EXPECT_NE(std::find(shardPoints.begin(), shardPoints.end(), without(p, "pareto")), shardPoints.end()) << p.dump();
    // The pictures are the shards' pixels.
    const std::string bvhRender = "objects_bvh.png";
    const int bvhShard = 1;
    EXPECT_EQ(readText(out / "images" / bvhRender), readText(shardDir(bvhShard) / "images" / bvhRender));
    EXPECT_TRUE(fs::exists(out / "images" / "objects_kd-stack_nodes.png"));
    EXPECT_NE(readText(out / "bench.md").find("## Shards"), std::string::npos);
    EXPECT_NE(readText(out / "report.html").find("<section id=\"shards\">"), std::string::npos);
}

// A shard's report keeps its pictures' pixels (an unsharded one keeps only the PNGs), so writing
// what was read gives the same file, byte for byte, and the same pictures.
TEST_F(BenchShards, ReaderGivesBackEveryFigureAsWritten) {
    for (int i = 0; i < kShards; ++i) {
        const BenchResults r = readBenchReport(shardDir(i));
        EXPECT_TRUE(benchJson(r) == readText(shardDir(i) / "bench.json")) << shardDir(i);
    }
    const BenchResults bvh = readBenchReport(shardDir(1));  // accel bvh
    ASSERT_EQ(bvh.scenes.size(), 1u);
    ASSERT_EQ(bvh.scenes[0].accels.size(), 1u);
    EXPECT_EQ(bvh.scenes[0].accels[0].image.width, 16);
    EXPECT_EQ(bvh.scenes[0].accels[0].nodesPerPixel.size(), 16u * 12u);
    const BenchResults all = readBenchReport(kRoot / "all");
    ASSERT_EQ(all.scenes.size(), 1u);
    EXPECT_EQ(all.scenes[0].accels.size(), 2u);
    EXPECT_EQ(all.scenes[0].accels[0].image.width, 0);
}

TEST_F(BenchShards, MergeRefusesMissingDuplicateAndMismatchedShards) {
    EXPECT_EQ(mergeError({shardDir(0), shardDir(2)}), "missing shard 1 of 3");
    EXPECT_EQ(mergeError({shardDir(0)}), "missing shards 1, 2 of 3");
    EXPECT_EQ(mergeError({shardDir(0), shardDir(1), shardDir(1), shardDir(2)}),
              (shardDir(1) / "bench.json").string() + ": shard 1/3 given twice (also " +
                  (shardDir(1) / "bench.json").string() + ")");

    const fs::path version = tampered("other-version", [](Json& j) { j["vkray"]["version"] = "0.0.1"; });
    EXPECT_NE(mergeError({shardDir(0), shardDir(1), version}).find("other-version/bench.json: written by vkray 0.0.1"),
              std::string::npos);
    const fs::path repeat = tampered("other-repeat", [](Json& j) { j["settings"]["repeat"] = 5; });
    EXPECT_NE(mergeError({shardDir(0), shardDir(1), repeat}).find("other-repeat/bench.json: other settings: repeat is 5 here, 1"),
              std::string::npos);
    EXPECT_NE(mergeError({shardDir(0), shardDir(1), kRoot / "all"}).find("all/bench.json: shard 0/1 of a run in 1 shard"),
              std::string::npos);
    EXPECT_NE(mergeError({shardDir(0), kRoot / "nowhere"}).find("nowhere/bench.json: no such file"), std::string::npos);
    // A shard that stopped before its scene is finished: named with what it lacks, not merged.
    const fs::path stopped = tampered("stopped", [](Json& j) {
        j["complete"] = false;
        j["failure"] = "interrupted by SIGTERM";
        j["scenes"] = Json::array();
    });
    EXPECT_EQ(mergeError({shardDir(0), stopped}),
              "missing shard 1 of 3; shard 2/3 (" + (stopped / "bench.json").string() +
                  ") is incomplete: interrupted by SIGTERM; not measured: " + std::string(VKRAY_SOURCE_DIR) +
                  "/scenes/objects.scene; rerun it with --resume");
    const fs::path cut = tampered("cut", [](Json& j) { j["scenes"][0].erase("accelerators"); });
    EXPECT_NE(mergeError({shardDir(0), shardDir(1), cut}).find("cut/bench.json: no \"scenes[0].accelerators\""),
              std::string::npos);
}

}  // namespace
}  // namespace vkray::bench
