#include "bench/embree_baseline.h"

#include "core/error.h"

#ifdef VKRAY_HAVE_EMBREE

#include <embree3/rtcore.h>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/timing.h"
#include "scene/camera.h"

namespace vkray::bench {
namespace {

// Embree reports errors through a callback; the message is kept and thrown at the next check.
struct ErrorSink {
    std::string message;
};

void onEmbreeError(void* user, RTCError code, const char* text) {
    auto* sink = static_cast<ErrorSink*>(user);
    if (sink->message.empty()) sink->message = "Embree error " + std::to_string(int(code)) + ": " + (text ? text : "");
}

// The scene's triangles as Embree's arrays: three vertices each, in order, indexed 0, 1, 2, ...
void writeTriangles(const Scene& scene, float* vertices, unsigned* indices) {
    for (size_t t = 0; t < scene.triangles.size(); ++t) {
        const Triangle& tri = scene.triangles[t];
        const glm::vec3 p[3] = {tri.p0, tri.p1, tri.p2};
        for (int k = 0; k < 3; ++k) {
            for (int c = 0; c < 3; ++c) vertices[9 * t + 3 * k + c] = p[k][c];
            indices[3 * t + k] = unsigned(3 * t + k);
        }
    }
}

class Embree final : public EmbreeBaseline {
public:
    Embree(const Scene& scene, int width, int height)
        : camera_(makeCameraFrame(scene.camera, width, height)), eye_(camera_.eye) {
        hits_.assign(size_t(width) * size_t(height), -1);
        device_ = rtcNewDevice(nullptr);
        if (!device_) throw Error("Embree: cannot create a device (rtcNewDevice failed)");
        rtcSetDeviceErrorFunction(device_, onEmbreeError, &errors_);
        scene_ = rtcNewScene(device_);
        rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
        RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        const size_t n = scene.triangles.size();
        auto* vertices = static_cast<float*>(
            rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
        auto* indices = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
        check();
        writeTriangles(scene, vertices, indices);
        rtcCommitGeometry(geom);
        rtcAttachGeometry(scene_, geom);
        rtcReleaseGeometry(geom);
        rtcCommitScene(scene_);
        check();
        version_ = "Embree " + std::to_string(rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_VERSION_MAJOR)) + "." +
                   std::to_string(rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_VERSION_MINOR)) + "." +
                   std::to_string(rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_VERSION_PATCH));
    }
    ~Embree() override {
        if (scene_) rtcReleaseScene(scene_);
        if (device_) rtcReleaseDevice(device_);
    }
    Embree(const Embree&) = delete;
    Embree& operator=(const Embree&) = delete;

    double traceMs(EmbreeQuery query, int threads) override {
        tbb::task_arena arena(std::max(1, threads));
        const auto t0 = Clock::now();
        // 4x4 blocks: one packet of 16, or 16 single rays of neighbouring pixels.
        const tbb::blocked_range2d<int> blocks(0, (camera_.height + 3) / 4, 4, 0, (camera_.width + 3) / 4, 16);
        arena.execute([&] {
            tbb::parallel_for(blocks, [&](const tbb::blocked_range2d<int>& r) {
                for (int by = r.rows().begin(); by < r.rows().end(); ++by)
                    for (int bx = r.cols().begin(); bx < r.cols().end(); ++bx)
                        query == EmbreeQuery::Single ? traceBlock1(bx * 4, by * 4) : traceBlock16(bx * 4, by * 4);
            });
        });
        const double ms = msSince(t0);
        check();
        return ms;
    }

    const std::vector<int32_t>& hits() const override { return hits_; }
    std::string version() const override { return version_; }

private:
    void check() {
        if (!errors_.message.empty()) throw Error(errors_.message);
    }

    // The camera ray through pixel (x, y) (scene/camera.h), in the float Embree takes.
    glm::vec3 direction(int x, int y) const { return glm::vec3(primaryDirection(camera_, x, y)); }

    void traceBlock1(int x0, int y0) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (int y = y0; y < std::min(y0 + 4, camera_.height); ++y)
            for (int x = x0; x < std::min(x0 + 4, camera_.width); ++x) {
                RTCRayHit rh{};
                const glm::vec3 d = direction(x, y);
                rh.ray = {eye_.x, eye_.y, eye_.z, 0.0f, d.x, d.y, d.z, 0.0f,
                          std::numeric_limits<float>::infinity(), 0xffffffffu, 0, 0};
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(scene_, &context, &rh);
                hits_[size_t(y) * size_t(camera_.width) + size_t(x)] =
                    rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1 : int32_t(rh.hit.primID);
            }
    }

    void traceBlock16(int x0, int y0) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        alignas(64) RTCRayHit16 rh;
        alignas(64) int valid[16];
        for (int k = 0; k < 16; ++k) {
            const int x = x0 + k % 4, y = y0 + k / 4;
            valid[k] = x < camera_.width && y < camera_.height ? -1 : 0;
            const glm::vec3 d = valid[k] ? direction(x, y) : glm::vec3(0.0f, 0.0f, 1.0f);
            rh.ray.org_x[k] = eye_.x;
            rh.ray.org_y[k] = eye_.y;
            rh.ray.org_z[k] = eye_.z;
            rh.ray.dir_x[k] = d.x;
            rh.ray.dir_y[k] = d.y;
            rh.ray.dir_z[k] = d.z;
            rh.ray.tnear[k] = 0.0f;
            rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
            rh.ray.time[k] = 0.0f;
            rh.ray.mask[k] = 0xffffffffu;
            rh.ray.id[k] = unsigned(k);
            rh.ray.flags[k] = 0;
            rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect16(valid, scene_, &context, &rh);
        for (int k = 0; k < 16; ++k)
            if (valid[k])
                hits_[size_t(y0 + k / 4) * size_t(camera_.width) + size_t(x0 + k % 4)] =
                    rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID ? -1 : int32_t(rh.hit.primID[k]);
    }

    CameraFrame camera_;
    glm::vec3 eye_;
    ErrorSink errors_;
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::vector<int32_t> hits_;
    std::string version_;
};

class Build final : public EmbreeBuild {
public:
    Build(const Scene& scene, int threads)
        : vertices_(9 * scene.triangles.size() + 1), indices_(3 * scene.triangles.size()) {
        writeTriangles(scene, vertices_.data(), indices_.data());
        device_ = rtcNewDevice(("threads=" + std::to_string(std::max(1, threads))).c_str());
        if (!device_) throw Error("Embree: cannot create a device (rtcNewDevice failed)");
        rtcSetDeviceErrorFunction(device_, onEmbreeError, &errors_);
    }
    ~Build() override {
        release();
        rtcReleaseDevice(device_);
    }
    Build(const Build&) = delete;
    Build& operator=(const Build&) = delete;

    void build() override {
        release();
        RTCScene scene = scene_ = rtcNewScene(device_);
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
        if (!errors_.message.empty()) throw Error(errors_.message);
    }

    void release() override {
        if (scene_) rtcReleaseScene(scene_);
        scene_ = nullptr;
    }

private:
    std::vector<float> vertices_;  // one float over: Embree reads vertices 16 bytes at a time
    std::vector<unsigned> indices_;
    ErrorSink errors_;
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
};

}  // namespace

bool embreeAvailable() { return true; }
const char* embreeMissingNote() { return ""; }

std::unique_ptr<EmbreeBaseline> makeEmbreeBaseline(const Scene& scene, int width, int height) {
    return std::make_unique<Embree>(scene, width, height);
}

std::unique_ptr<EmbreeBuild> makeEmbreeBuild(const Scene& scene, int threads) {
    return std::make_unique<Build>(scene, threads);
}

}  // namespace vkray::bench

#else  // no Embree in this build

namespace vkray::bench {

bool embreeAvailable() { return false; }
const char* embreeMissingNote() {
    return "this vkray was built without Embree (install libembree-dev and rebuild for the CPU baseline)";
}
std::unique_ptr<EmbreeBaseline> makeEmbreeBaseline(const Scene&, int, int) { return nullptr; }
std::unique_ptr<EmbreeBuild> makeEmbreeBuild(const Scene&, int) { return nullptr; }

}  // namespace vkray::bench

#endif
