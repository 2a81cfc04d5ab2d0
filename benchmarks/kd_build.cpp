// Build benchmark of the SAH kd-tree against two yardsticks on the same triangles, in the same run:
// Embree 3's BVH build at RTC_BUILD_QUALITY_HIGH (Wald, Woop, Benthin, Johnson and Ernst, "Embree:
// A Kernel Framework for Efficient CPU Ray Tracing", SIGGRAPH 2014) and one of vkray's BVH builds
// (--bvh, default `bvh`). The three builds alternate run by run, so a busy machine slows all of them
// alike; it prints the medians (min-max) after one warm-up of each, the kd build's ratio to each
// yardstick, the kd build's phases and the tree's shape. Beside the wall-clock times it prints the
// process's CPU time a build (all its threads), whose ratios hold when other processes take turns
// on the cores. A benchmark prints figures; it asserts nothing (docs/performance.md, "Method").
//
//   vkray_bench_kd_build [--runs N] [--threads N] [--bvh NAME] [--kd NAME] SCENE...
#include <time.h>

#include <cstdio>
#include <exception>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#ifdef VKRAY_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

#include "accel/accel.h"
#include "accel/accel_spec.h"
#include "bench/spread.h"
#include "core/timing.h"
#include "scene/scene_parser.h"

namespace {

using namespace vkray;

// Milliseconds of CPU time the process has used, all threads together.
double cpuMs() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

// Wall-clock and CPU milliseconds of f().
template <class F>
std::pair<double, double> timed(const F& f) {
    const auto start = Clock::now();
    const double cpu = cpuMs();
    f();
    const double cpuUsed = cpuMs() - cpu;
    return {msSince(start), cpuUsed};
}

struct Options {
    int runs = 5;
    int threads = 2;
    std::string bvh = "bvh";
    std::string kd = "kd-stack";
    std::vector<std::string> scenes;
};

Options parseArgs(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto next = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--runs") o.runs = std::max(1, std::stoi(next()));
        else if (a == "--threads") o.threads = std::max(1, std::stoi(next()));
        else if (a == "--bvh") o.bvh = next();
        else if (a == "--kd") o.kd = next();
        else o.scenes.push_back(a);
    }
    if (o.scenes.empty())
        throw std::runtime_error("usage: vkray_bench_kd_build [--runs N] [--threads N] [--bvh NAME] [--kd NAME] SCENE...");
    return o;
}

#ifdef VKRAY_HAVE_EMBREE
// Embree's BVH over the triangles as given, high quality, on its own `threads` workers: one build a
// call, the scene made and committed within the timing, the vertex array made before it.
class EmbreeBuild {
public:
    EmbreeBuild(const Scene& scene, int threads) : vertices_(9 * scene.triangles.size() + 1) {
        for (size_t t = 0; t < scene.triangles.size(); ++t) {
            const Triangle& tri = scene.triangles[t];
            const glm::vec3 p[3] = {tri.p0, tri.p1, tri.p2};
            for (int k = 0; k < 3; ++k)
                for (int c = 0; c < 3; ++c) vertices_[9 * t + 3 * k + c] = p[k][c];
        }
        indices_.resize(3 * scene.triangles.size());
        for (size_t i = 0; i < indices_.size(); ++i) indices_[i] = unsigned(i);
        device_ = rtcNewDevice(("threads=" + std::to_string(threads)).c_str());
        if (!device_) throw std::runtime_error("Embree: rtcNewDevice failed");
    }
    ~EmbreeBuild() { rtcReleaseDevice(device_); }
    EmbreeBuild(const EmbreeBuild&) = delete;
    EmbreeBuild& operator=(const EmbreeBuild&) = delete;

    RTCScene build() {
        RTCScene scene = rtcNewScene(device_);
        rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
        RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_HIGH);
        const size_t n = indices_.size() / 3;
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices_.data(), 0,
                                   3 * sizeof(float), 3 * n);
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices_.data(), 0,
                                   3 * sizeof(unsigned), n);
        rtcCommitGeometry(geom);
        rtcAttachGeometry(scene, geom);
        rtcReleaseGeometry(geom);
        rtcCommitScene(scene);
        if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw std::runtime_error("Embree: the build failed");
        return scene;
    }

private:
    std::vector<float> vertices_;  // one float over: Embree reads vertices 16 bytes at a time
    std::vector<unsigned> indices_;
    RTCDevice device_ = nullptr;
};
#endif

void printSpread(const char* what, const bench::Spread& s) {
    std::printf("  %-28s %9.1f ms (min %.1f, max %.1f)\n", what, s.median, s.min, s.max);
}

void benchScene(const std::string& file, const Options& o) {
    const Scene scene = loadScene(file);
    std::printf("%s: %zu triangles, %d thread(s), %d runs\n", file.c_str(), scene.triangles.size(), o.threads, o.runs);
    const accel::AccelSpec kdSpec = accel::resolveAccel(o.kd), bvhSpec = accel::resolveAccel(o.bvh);
    accel::BuildOptions options;
    options.threads = o.threads;
    std::vector<double> kdMs, bvhMs, embreeMs, kdCpu, bvhCpu, embreeCpu;
    std::map<std::string, std::vector<double>> phases;
    std::vector<accel::AccelStat> last;
#ifdef VKRAY_HAVE_EMBREE
    EmbreeBuild embree(scene, o.threads);
#endif
    for (int r = 0; r <= o.runs; ++r) {  // run 0: the warm-up
        std::unique_ptr<accel::BuiltAccel> kd, bvh;
        const auto [k, kCpu] = timed([&] { kd = accel::buildAccel(scene, kdSpec, options); });
        last = kd->stats();
        kd.reset();
        const auto [b, bCpu] = timed([&] { bvh = accel::buildAccel(scene, bvhSpec, options); });
        bvh.reset();
#ifdef VKRAY_HAVE_EMBREE
        RTCScene built = nullptr;
        const auto [e, eCpu] = timed([&] { built = embree.build(); });
        rtcReleaseScene(built);
        if (r > 0) {
            embreeMs.push_back(e);
            embreeCpu.push_back(eCpu);
        }
#endif
        if (r == 0) continue;
        kdMs.push_back(k);
        bvhMs.push_back(b);
        kdCpu.push_back(kCpu);
        bvhCpu.push_back(bCpu);
        for (const accel::AccelStat& s : last)
            if (s.key.starts_with("build_") && s.key.ends_with("_ms")) phases[s.key].push_back(s.value);
    }
    const bench::Spread kd = bench::spreadOf(kdMs), bvh = bench::spreadOf(bvhMs);
    printSpread(o.kd.c_str(), kd);
    printSpread(o.bvh.c_str(), bvh);
    const double kdC = bench::spreadOf(kdCpu).median, bvhC = bench::spreadOf(bvhCpu).median;
    std::printf("  %s / %s: %.2fx wall, %.2fx CPU (%.0f / %.0f ms)\n", o.kd.c_str(), o.bvh.c_str(),
                kd.median / bvh.median, kdC / bvhC, kdC, bvhC);
#ifdef VKRAY_HAVE_EMBREE
    const bench::Spread em = bench::spreadOf(embreeMs);
    const double emC = bench::spreadOf(embreeCpu).median;
    printSpread("Embree 3 BVH, HIGH quality", em);
    std::printf("  %s / Embree HIGH: %.2fx wall, %.2fx CPU (%.0f / %.0f ms)\n", o.kd.c_str(), kd.median / em.median,
                kdC / emC, kdC, emC);
#else
    std::printf("  Embree: not in this build (install libembree-dev)\n");
#endif
    for (const accel::AccelStat& s : last) {
        const auto p = phases.find(s.key);
        if (p != phases.end()) std::printf("  %-28s %9.1f ms (%s)\n", s.key.c_str(), bench::spreadOf(p->second).median, s.unit.c_str());
        else if (!s.key.ends_with("_ms")) std::printf("  %-28s %12.6g %s\n", s.key.c_str(), s.value, s.unit.c_str());
    }
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const Options o = parseArgs(argc, argv);
        for (const std::string& file : o.scenes) benchScene(file, o);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
