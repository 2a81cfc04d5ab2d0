// The report tests' synthetic results (report_fixture.h).
#include "report_fixture.h"

#include <algorithm>
#include <cmath>

namespace vkray::bench::fixture {

Image gradient(int w, int h, float shift) {
    Image im(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) im.at(x, y, c) = std::min(1.0f, shift + 0.1f * float(x + y + c));
    return im;
}

Spread around(double median) { return {median, 0.9 * median, 1.2 * median}; }

AccelResult makeAccel(const std::string& name, double traceMs, std::vector<ThreadTiming> build, int w, int h,
                      uint32_t nodeBase) {
    AccelResult a;
    a.accel = name;
    a.kernel = name;
    a.build = std::move(build);
    a.structureBytes = 123456;
    a.traceMs = around(traceMs);
    a.rayKinds = {{"primary", uint64_t(w * h), 40.0, ""},
                  {"shadow", uint64_t(2 * w * h), std::nullopt, "within the noise"},
                  {"secondary", 0, std::nullopt, "no reflective or refractive surfaces"}};
    a.mraysPerSecond = 12.5;
    a.nodesPerRay = 31.25;
    a.leavesPerRay = 3.5;
    a.trianglesPerRay = 7.25;
    a.error = {.rmse = 0.01, .psnr = 40.0, .maxError = 0.1, .primaryMismatch = 0.002};
    a.image = gradient(w, h, 0.1f);
    a.diff = gradient(w, h, 0.0f);
    for (int i = 0; i < w * h; ++i) {
        a.nodesPerPixel.push_back(nodeBase + uint32_t(i % 7));
        a.primaryNodesPerPixel.push_back(nodeBase / 2 + uint32_t(i % 3));
    }
    return a;
}

std::vector<ThreadTiming> oneAndTwoThreads(double oneMs, double twoMs) { return {{1, around(oneMs)}, {2, around(twoMs)}}; }

ErrorPoint errorPoint(const std::string& label, const std::string& group, double buildMs, double traceMs, double rmse) {
    ErrorPoint p;
    p.label = label;
    p.group = group;
    p.accel = "bvh-hq";
    p.maxDepth = 5;
    p.precision = group == "cpu-reference" ? "double (CPU)" : "float (GPU)";
    p.buildMs = buildMs;
    p.traceMs = traceMs;
    p.error.rmse = rmse;
    if (rmse > 0.0) p.error.psnr = 20.0 * std::log10(1.0 / rmse);
    return p;
}

SceneResult fullScene() {
    SceneResult s;
    s.file = "scenes/alpha.scene";
    s.name = "alpha";
    s.triangles = 69668;
    s.width = 8;
    s.height = 6;
    s.maxDepth = 5;
    s.referenceAccel = "bvh-hq";
    s.referenceBuildMs = 5.0;
    s.referenceRenderMs = 400.0;
    s.reference = gradient(8, 6, 0.1f);
    s.accels = {makeAccel("bvh-hq", 1.0, oneAndTwoThreads(16.0, 9.0), 8, 6, 10),
                makeAccel("bvh-fast", 1.5, oneAndTwoThreads(8.0, 5.0), 8, 6, 12),
                makeAccel("kd-stack", 2.4, oneAndTwoThreads(36.0, 20.0), 8, 6, 30),
                makeAccel("kd-restart", 3.0, oneAndTwoThreads(36.0, 20.0), 8, 6, 40),
                makeAccel("kd-backtrack", 2.8, oneAndTwoThreads(36.0, 20.0), 8, 6, 35)};
    s.deltas = {{4, 0.1, around(10.0), around(3.0), 40.0, 8.0, 70.0},
                {8, 0.1, around(8.0), around(3.5), 42.0, 9.0, 72.0},
                {20, 0.1, around(12.0), around(3.2), 38.0, 7.5, 68.0}};
    s.errorPoints = {errorPoint("bvh-hq", "accelerator", 9.0, 1.0, 0.01),
                     errorPoint("kd-stack", "accelerator", 20.0, 2.4, 0.01),
                     errorPoint("aac delta 8", "aac-delta", 8.0, 3.5, 0.008),
                     errorPoint("bvh maxdepth 1", "maxdepth", 9.0, 0.4, 0.2),
                     errorPoint("CPU double", "cpu-reference", 5.0, 400.0, 0.0)};
    markParetoFront(s.errorPoints);
    s.concurrent = ConcurrentBuild{"bvh-hq", "kd-stack", around(9.0), around(20.0), around(22.0)};
    return s;
}

// One accelerator, built at one thread count; no sweep, no concurrent build; a name to escape.
SceneResult minimalScene() {
    SceneResult s;
    s.file = "scenes/beta.scene";
    s.name = "beta<&>";
    s.triangles = 12;
    s.width = 4;
    s.height = 3;
    s.maxDepth = 2;
    s.referenceAccel = "kd-restart";
    s.reference = gradient(4, 3, 0.2f);
    s.accels = {makeAccel("kd-restart", 5.0, {{2, around(1.0)}}, 4, 3, 3)};
    s.errorPoints = {errorPoint("kd-restart", "accelerator", 1.0, 5.0, 0.03)};
    markParetoFront(s.errorPoints);
    return s;
}

BenchResults results() {
    BenchResults r;
    r.vkrayVersion = "0.1.0";
    r.revision = "abc1234";
    r.commandLine = "vkray bench scenes/alpha.scene scenes/beta.scene --repeat 3";
    r.startedAt = "2026-11-02T10:00:00Z";
    r.elapsedSeconds = 42.0;
    r.device = "llvmpipe (LLVM 15.0.6, 256 bits)";
    r.driver = "Mesa 22.3.6";
    r.deviceType = "cpu";
    r.vulkanApi = "1.3.230";
    r.hardwareThreads = 2;
    r.repeat = 3;
    r.threadCounts = {1, 2};
    r.scenes = {fullScene(), minimalScene()};
    return r;
}

size_t count(const std::string& haystack, const std::string& needle) {
    size_t n = 0;
    for (size_t at = haystack.find(needle); at != std::string::npos; at = haystack.find(needle, at + needle.size())) ++n;
    return n;
}

}  // namespace vkray::bench::fixture
