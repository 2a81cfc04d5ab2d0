#include "accel/accel.h"

#include <exception>
#include <future>

#include "accel/bvh/bvh_accel.h"
#include "accel/bvh/morton.h"
#include "accel/kd/kd_accel.h"
#include "core/error.h"
#include "geometry/brute_force.h"

namespace vkray::accel {
namespace {

// `brute`: nothing to build; the kernel and the CPU tracer test every triangle.
class BruteAccel final : public BuiltAccel {
public:
    std::unique_ptr<geometry::Tracer> makeTracer(const Scene& scene) const override {
        return std::make_unique<geometry::BruteForceTracer>(scene);
    }
    GpuAccelData gpuData() const override { return GpuAccelData{}; }  // traversal "brute", no arrays
    std::vector<AccelStat> stats() const override { return {}; }
};

// `rayquery`: the driver builds its structure on the device for each render (gpu/driver_structure.h),
// over the triangle buffer in the order given here: the Morton order of the centroids. Lavapipe's
// builder (Mesa 24.1 to 25.0) splits the primitive range at its middle in the order it is handed, so
// its tree is only as good as that order: scene order made the bunny close-up 160 times slower to
// trace. A driver that sorts for itself (hardware ones do) loses nothing. It has no CPU traversal
// of its own: the CPU reference walks brute force, which answers as every vkray traversal does.
class DriverAccel final : public BuiltAccel {
public:
    DriverAccel(const DriverBuild& build, std::vector<uint32_t> order) : build_(build), order_(std::move(order)) {}
    std::unique_ptr<geometry::Tracer> makeTracer(const Scene& scene) const override {
        return std::make_unique<geometry::BruteForceTracer>(scene);
    }
    GpuAccelData gpuData() const override {
        GpuAccelData data;
        data.traversal = Traversal::RayQuery;
        data.driverBuild = build_;
        data.triangleOrder = order_;
        return data;
    }
    std::vector<AccelStat> stats() const override { return {}; }

private:
    DriverBuild build_;
    std::vector<uint32_t> order_;  // triangle slot k holds scene triangle order_[k]
};

}  // namespace

std::unique_ptr<BuiltAccel> buildAccel(const Scene& scene, const AccelSpec& spec,
                                       const BuildOptions& options) {
    switch (spec.family) {
    case Family::Brute: return std::make_unique<BruteAccel>();
    case Family::Driver: return std::make_unique<DriverAccel>(spec.driver, bvh::mortonOrder(scene.triangles));
    case Family::Bvh: return buildBvhAccel(scene, spec.bvh, spec.bvhWalk, options);
    case Family::Kd: return buildKdAccel(scene, spec.kd, spec.kdTraversal, spec.kdShortStack, options);
    }
    throw Error("accelerator '" + spec.name + "': unknown family");
}

Traversal traversalOf(const AccelSpec& spec) {
    switch (spec.family) {
    case Family::Brute: return Traversal::Brute;
    case Family::Driver: return Traversal::RayQuery;
    case Family::Bvh: return bvhTraversal(spec.bvh, spec.bvhWalk);
    case Family::Kd: return kdTraversal(spec.kdTraversal);
    }
    throw Error("accelerator '" + spec.name + "': unknown family");
}

std::vector<std::unique_ptr<BuiltAccel>> buildAccelsConcurrently(const Scene& scene,
                                                                 const std::vector<AccelSpec>& specs,
                                                                 const BuildOptions& options) {
    // std::async rather than one more oneTBB arena: each builder already runs its own arena of
    // options.threads workers, and oneTBB shares its workers between arenas, so the two builds
    // together never oversubscribe the machine.
    BuildOptions quiet = options;
    quiet.progress = {};  // two builds cannot share one progress line
    std::vector<std::future<std::unique_ptr<BuiltAccel>>> pending;
    for (const AccelSpec& spec : specs)
        pending.push_back(std::async(std::launch::async, [&scene, spec, quiet] { return buildAccel(scene, spec, quiet); }));
    std::vector<std::unique_ptr<BuiltAccel>> built;
    std::exception_ptr failure;
    for (auto& f : pending) {
        try {
            built.push_back(f.get());
        } catch (...) {
            if (!failure) failure = std::current_exception();
            built.emplace_back();
        }
    }
    if (failure) std::rethrow_exception(failure);
    return built;
}

}  // namespace vkray::accel
