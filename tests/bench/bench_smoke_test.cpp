// The bench smoke test: the whole `vkray bench` pipeline on lavapipe at a small size,
// then a check that the report is complete — every figure present, finite and positive where it
// must be, every image in report.html and images/. Times are never compared with anything.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/bench_runner.h"
#include "bench/embree_baseline.h"
#include "bench/report.h"
#include "render/device.h"

namespace vkray::bench {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// The device of a run, opened as `vkray bench` opens one. A local of the test, not a static: its
// pipelines are destroyed before the process exits, as in vkray. Destroyed in a static destructor,
// after lavapipe's own exit handlers (Mesa 25), the driver leaks every pipeline's JIT code.
render::Device openDevice() {
    const char* dev = std::getenv("VKRAY_TEST_DEVICE");
    return render::Device(gpu::ContextOptions{.validation = true, .device = dev ? dev : ""});
}

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

size_t countOf(const std::string& text, const std::string& needle) {
    size_t n = 0;
    for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
    return n;
}

// A figure that must have been measured: a finite number > 0.
void expectPositive(const Json& j, const std::string& key, const std::string& where) {
    ASSERT_TRUE(j.contains(key)) << where << ": no " << key;
    ASSERT_TRUE(j[key].is_number()) << where << ": " << key << " = " << j[key].dump();
    const double v = j[key].get<double>();
    EXPECT_TRUE(std::isfinite(v) && v > 0.0) << where << ": " << key << " = " << v;
}

void expectPositiveSpread(const Json& j, const std::string& key, const std::string& where) {
    ASSERT_TRUE(j.contains(key)) << where << ": no " << key;
    for (const char* part : {"median", "min", "max"}) expectPositive(j[key], part, where + "." + key);
    EXPECT_LE(j[key]["min"].get<double>(), j[key]["median"].get<double>()) << where << "." << key;
    EXPECT_LE(j[key]["median"].get<double>(), j[key]["max"].get<double>()) << where << "." << key;
}

// An error figure: finite and >= 0 (an exact accelerator may match the reference exactly).
void expectError(const Json& e, const std::string& where) {
    for (const char* key : {"rmse", "max_error", "primary_hit_mismatch"}) {
        ASSERT_TRUE(e.contains(key) && e[key].is_number()) << where << ": " << key;
        const double v = e[key].get<double>();
        EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << where << ": " << key << " = " << v;
    }
    const double rmse = e["rmse"].get<double>();
    if (rmse > 0.0) expectPositive(e, "psnr_db", where);
    else EXPECT_TRUE(e["psnr_db"].is_null()) << where << ": PSNR of identical images";
}

// No NaN or infinity can hide in the file: the writer turns them into null, so any null must be a
// field allowed to be empty.
void expectNoStrayNulls(const Json& j, const std::string& path) {
    if (j.is_null()) {
        const bool allowed = path.ends_with(".psnr_db") || path.ends_with(".mrays_per_s") ||
                             path.ends_with(".concurrent_build") || path.ends_with(".embree_interleaved") ||
                             path.ends_with(".primary_vs_bvh") ||       // the run benches no bvh
                             path.ends_with(".primary_vs_rayquery") ||  // nor rayquery
                             path == "bench.failure";                  // a complete run
        EXPECT_TRUE(allowed) << "null at " << path;
        return;
    }
    if (j.is_number_float()) {
        EXPECT_TRUE(std::isfinite(j.get<double>())) << path;
    }
    if (j.is_object())
        for (const auto& [key, value] : j.items()) expectNoStrayNulls(value, path + "." + key);
    if (j.is_array())
        for (size_t i = 0; i < j.size(); ++i) expectNoStrayNulls(j[i], path + "[" + std::to_string(i) + "]");
}

void checkAccel(const Json& a, int width, int height) {
    const std::string where = a["accel"].get<std::string>();
    for (const Json& b : a["build"]) expectPositiveSpread(b, "ms", where + ".build");
    expectPositive(a, "structure_bytes", where);
    for (const char* key : {"trace_ms", "primary_only_ms", "depth_one_ms"}) expectPositiveSpread(a, key, where);
    expectPositive(a, "mrays_per_s", where);
    ASSERT_EQ(a["ray_kinds"].size(), 3u) << where;
    EXPECT_EQ(a["ray_kinds"][0]["rays"].get<uint64_t>(), uint64_t(width) * uint64_t(height)) << where;
    for (const Json& k : a["ray_kinds"]) {
        // cornell has every kind of ray: each must have been traced. Its rate is a difference of
        // two medians, which on a loaded machine can vanish into the noise: then the figure is
        // empty and the report says why, never a negative or made-up rate.
        const std::string kind = where + " " + k["kind"].get<std::string>();
        EXPECT_GT(k["rays"].get<uint64_t>(), 0u) << kind;
        if (k["mrays_per_s"].is_null())
            EXPECT_EQ(k.value("note", ""), "time difference within the noise") << kind;
        else
            expectPositive(k, "mrays_per_s", kind);
    }
    for (const char* key : {"nodes", "leaves", "triangles"}) expectPositive(a["per_ray"], key, where + ".per_ray");
    expectPositive(a["per_primary_ray"], "nodes", where + ".per_primary_ray");
    if (where == "kd-restart") expectPositive(a["per_ray"], "restarts", where);
    EXPECT_EQ(a["capped_rays"].get<uint64_t>(), 0u) << where;
    expectError(a["error"], where);
    // A GPU float render of cornell against the double reference: close, not exact.
    EXPECT_LT(a["error"]["rmse"].get<double>(), 0.05) << where;
}

TEST(BenchSmoke, ReportOnLavapipeIsComplete) {
    BenchOptions o;
    o.scenes = {std::string(VKRAY_SOURCE_DIR) + "/scenes/cornell.scene"};
    o.accels = {"bvh-fast", "kd-stack", "kd-restart", "kd-backtrack"};
    o.width = 48;
    o.height = 36;
    o.repeat = 3;
    o.threads = {1, 2};
    o.deltas = {4, 20};
    o.maxDepths = {1, 2};
    render::Device device = openDevice();
    const BenchResults results = runBench(device, o, "bench_smoke_test");
    const fs::path dir = fs::path(VKRAY_TEST_OUTPUT_DIR) / "bench-smoke";
    fs::remove_all(dir);
    writeBenchReport(results, dir);

    // bench.json: every figure.
    const Json j = Json::parse(readText(dir / "bench.json"));
    expectNoStrayNulls(j, "bench");
    EXPECT_EQ(j["complete"], true);
    EXPECT_EQ(j["missing_scenes"], Json::array());
    EXPECT_FALSE(j["device"]["name"].get<std::string>().empty());
    EXPECT_FALSE(j["vkray"]["revision"].get<std::string>().empty());
    EXPECT_EQ(j["command_line"], "bench_smoke_test");
    ASSERT_EQ(j["scenes"].size(), 1u);
    const Json& s = j["scenes"][0];
    EXPECT_EQ(s["triangles"].get<uint64_t>(), 552u);
    expectPositive(s["reference"], "build_ms", "reference");
    expectPositive(s["reference"], "render_ms", "reference");
    ASSERT_EQ(s["accelerators"].size(), o.accels.size());
    for (const Json& a : s["accelerators"]) {
        ASSERT_EQ(a["build"].size(), 2u);
        checkAccel(a, o.width, o.height);
    }
    // The CPU baseline on the same camera rays, interleaved with every accelerator's.
    if (embreeAvailable()) {
        const Json& e = s["embree"];
        for (const char* key : {"intersect1_mrays_per_s", "intersect16_mrays_per_s"}) expectPositive(e, key, "embree");
        EXPECT_GE(e["agreement_with_reference"].get<double>(), 0.98);
        // One figure, the median of every interleaved run of every accelerator, divides every ratio.
        const std::vector<double> runs = e["intersect1_samples_ms"].get<std::vector<double>>();
        ASSERT_EQ(runs.size(), size_t(o.repeat) * o.accels.size());
        const double median = spreadOf(runs).median;
        EXPECT_EQ(e["intersect1_ms"]["median"].get<double>(), median);
        for (const Json& a : s["accelerators"]) {
            expectPositiveSpread(a["embree_interleaved"], "intersect1_ms", "embree_interleaved");
            expectPositive(a["embree_interleaved"], "primary_vs_intersect1", a["accel"]);
            EXPECT_DOUBLE_EQ(a["embree_interleaved"]["primary_vs_intersect1"].get<double>(),
                             median / a["primary_only_ms"]["median"].get<double>())
                << a["accel"];
        }
    } else {
        EXPECT_FALSE(s["embree"]["note"].get<std::string>().empty());
    }
    ASSERT_EQ(s["aac_delta_sweep"].size(), 2u);
    for (const Json& d : s["aac_delta_sweep"]) {
        for (const char* key : {"build_ms", "trace_ms"}) expectPositiveSpread(d, key, "delta");
        for (const char* key : {"nodes_per_ray", "triangles_per_ray", "sah_cost", "aac_epsilon"})
            expectPositive(d, key, "delta");
    }
    ASSERT_TRUE(s["concurrent_build"].is_object());
    for (const char* key : {"bvh_alone_ms", "kd_alone_ms", "concurrent_ms"})
        expectPositiveSpread(s["concurrent_build"], key, "concurrent_build");
    // Points: 4 accelerators, 2 deltas, 2 depths, the CPU reference.
    ASSERT_EQ(s["error_vs_time"].size(), 9u);
    int pareto = 0;
    for (const Json& p : s["error_vs_time"]) {
        expectPositive(p, "total_ms", p["label"]);
        expectError(p["error"], p["label"]);
        pareto += p["pareto"].get<bool>();
    }
    EXPECT_GE(pareto, 1);
    // Fewer bounces than the scene's: a visibly different image.
    for (const Json& p : s["error_vs_time"]) {
        if (p["group"] == "maxdepth") {
            EXPECT_GT(p["error"]["rmse"].get<double>(), 0.01) << p["label"];
        }
    }

    // bench.md: one row per accelerator in its table.
    const std::string md = readText(dir / "bench.md");
    for (const std::string& a : o.accels) EXPECT_NE(md.find("| " + a + " |"), std::string::npos) << a;

    // report.html: self-contained, with the reference and per accelerator its image, difference
    // and two heatmaps (all rays, camera rays), and the plots.
    const std::string html = readText(dir / "report.html");
    EXPECT_EQ(countOf(html, "http://") + countOf(html, "https://"), 0u);
    EXPECT_EQ(countOf(html, "data:image/png;base64,"), 1 + 4 * o.accels.size());
    EXPECT_GE(countOf(html, "<svg"), 3u);
    EXPECT_EQ(countOf(html, "<svg class=\"plot bar-chart\""), 1u);
    size_t pngs = 0;
    for (const auto& e : fs::directory_iterator(dir / "images")) pngs += e.path().extension() == ".png";
    EXPECT_EQ(pngs, 1 + 4 * o.accels.size());
    // Camera rays alone visit fewer nodes a pixel than all the rays of a pixel of cornell (mirrors,
    // glass and shadow rays).
    for (const AccelResult& a : results.scenes[0].accels) {
        ASSERT_EQ(a.primaryNodesPerPixel.size(), size_t(o.width) * size_t(o.height)) << a.accel;
        uint64_t camera = 0, all = 0;
        for (size_t i = 0; i < a.nodesPerPixel.size(); ++i) {
            EXPECT_LE(a.primaryNodesPerPixel[i], a.nodesPerPixel[i]) << a.accel << " pixel " << i;
            camera += a.primaryNodesPerPixel[i];
            all += a.nodesPerPixel[i];
        }
        EXPECT_GT(camera, 0u) << a.accel;
        EXPECT_LT(camera, all) << a.accel;
    }
}

}  // namespace
}  // namespace vkray::bench
