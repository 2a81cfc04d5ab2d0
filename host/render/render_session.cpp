#include "render/render_session.h"

#include <cstdint>
#include <future>
#include <optional>
#include <utility>

#include "core/error.h"
#include "core/timing.h"
#include "cpu/reference_renderer.h"
#include "gpu/kernel_cache.h"
#include "image/image_io.h"
#include "render/memory_budget.h"
#include "render/outputs.h"
#include "render/scene_checks.h"
#include "scene/camera.h"
#include "scene/scene_parser.h"

namespace vkray::render {
namespace {

Device deviceFor(const RenderRequest& request) {
    if (request.cpu || request.buildOnly) return Device();
    return Device(request.device, request.accel.family == accel::Family::Driver);
}

void fillSceneReport(const std::string& sceneFile, const Scene& scene, const RenderOptions& options,
                     RenderReport& report) {
    report.scene = sceneFile;
    report.options = options;
    report.triangles = scene.triangles.size();
    report.materials = scene.materials.size();
    report.lights = scene.lights.size();
    report.origin = {scene.origin.x, scene.origin.y, scene.origin.z};
}

}  // namespace

// A scene loaded, checked and settled: what it is rendered with and where it goes.
struct RenderSession::Loaded {
    Scene scene;
    SceneSettings settings;
    double loadMs = 0.0;
};

RenderSession::RenderSession(RenderRequest request)
    : request_(std::move(request)),
      files_(request_.saveAccel, request_.loadAccel, request_.accel, request_.cpu),
      device_(deviceFor(request_)) {}

RenderSession::Loaded RenderSession::load(const std::string& sceneFile) {
    const Clock::time_point t0 = Clock::now();
    ParseOptions parse;
    parse.progress = request_.progress.load;
    parse.warn = request_.warn;
    Loaded l{loadScene(sceneFile, withinMemory(memoryUseOf(request_), parse)), {}, 0.0};
    if (request_.progress.lineDone) request_.progress.lineDone();
    l.loadMs = msSince(t0);
    checkRenderable(l.scene, sceneFile);
    if (request_.warn)
        if (const auto unlit = unlitMaterialsWarning(l.scene, sceneFile)) request_.warn(*unlit);
    l.scene.camera = viewCamera(l.scene, request_.view);
    l.settings = request_.settings(sceneFile, l.scene);
    if (l.settings.background) l.scene.background = *l.settings.background;
    const std::filesystem::path& out = l.settings.output;
    if (!out.empty()) {
        checkColorImagePath(out);  // refuse a bad output before spending minutes on the render
        if (const auto it = written_.find(out); it != written_.end())
            throw Error(sceneFile + ": its image " + out.string() + " is also " + it->second +
                        "'s (give the scenes different 'output' names)");
        written_[out] = sceneFile;
    }
    return l;
}

// The device before the build: a missing or unknown device, or a scene too large for it or for the
// host's memory, fails before a long build.
void RenderSession::openDevice(const Scene& scene, RenderReport& report) {
    const Clock::time_point opening = Clock::now();
    if (device_.get()) {
        report.deviceMs = msSince(opening);
        const gpu::VulkanContext& ctx = device_.checkFits(scene, memoryUseOf(request_), &report.memory);
        report.device = ctx.info().name + " (" + ctx.info().driver + ")";
    } else {
        report.device = request_.buildOnly ? "none (--build-only)" : "CPU reference (double precision)";
        report.memory = checkSceneMemory(sizeOf(scene), memoryUseOf(request_), hostMemoryLimits());
    }
}

SceneRender RenderSession::render(const std::string& sceneFile) {
    const Clock::time_point t0 = Clock::now();
    Loaded l = load(sceneFile);
    const Scene& scene = l.scene;
    const RenderOptions& options = l.settings.options;
    SceneHashes hashes(sceneFile, scene);
    files_.checkScene(hashes);  // a structure file for another scene
    SceneRender result;
    RenderReport& report = result.report;
    report.loadMs = l.loadMs;
    openDevice(scene, report);
    report.accel = request_.accel.name;
    fillSceneReport(sceneFile, scene, options, report);
    if (request_.buildOnly) {  // the GPU's arrays, as a structure file to load holds them
        files_.prepare(scene, hashes, request_.accel, StructureNeeds{.gpuData = true, .threads = options.threads,
                                                                     .progress = request_.progress.build,
                                                                     .lineDone = request_.progress.lineDone},
                       report);
        report.buildOnly = true;
        report.totalMs = msSince(t0);
        return result;
    }

    result.frame = renderFrame(scene, options, hashes, report);
    // Only an EXR keeps the metadata: the scene file and geometry are hashed for those alone.
    const ImageMeta meta = anyExr(l.settings.output, request_.aovs)
                               ? outputMeta(sceneFile, scene, hashes, options, report, request_.tile)
                               : ImageMeta{};
    const Clock::time_point writing = Clock::now();
    writeOutputs(result.frame, l.settings.output, l.settings.encoding, request_.aovs, meta);
    report.writeMs = msSince(writing);
    report.output = l.settings.output.string();
    report.aovs = request_.aovs;
    report.totalMs = msSince(t0);
    if (request_.tracePixel) result.centreRay = tracePixel(scene, options, result.frame.x0, result.frame.y0);
    return result;
}

// With a device, the kernel's pipeline is created on a thread while the structure is built (the
// driver compiles it), unless an earlier scene of the session created it.
Frame RenderSession::renderFrame(const Scene& scene, const RenderOptions& options, SceneHashes& hashes,
                                 RenderReport& report) {
    gpu::KernelCache* kernels = device_.kernels();
    std::future<double> compiling;  // waits in its destructor
    const size_t pipelinesBefore = kernels ? kernels->size() : 0;
    if (kernels) {
        compiling = std::async(std::launch::async, [&] {
            return gpu::prepareKernel(scene, options, accel::traversalOf(request_.accel), *kernels);
        });
    }
    const StructureNeeds needs{.tracer = kernels == nullptr, .gpuData = kernels != nullptr, .threads = options.threads,
                               .progress = request_.progress.build, .lineDone = request_.progress.lineDone};
    const Structure structure = files_.prepare(scene, hashes, request_.accel, needs, report);
    const Clock::time_point t0 = Clock::now();
    if (!kernels) {
        Frame frame = renderReference(scene, options, *structure.tracer, request_.progress.rows);
        report.renderMs = msSince(t0);
        return frame;
    }
    const double preparedMs = compiling.get();
    const size_t prepared = kernels->size() - pipelinesBefore;
    Frame frame = renderOnDevice(scene, options, structure, report);
    report.gpu->pipelineMs += preparedMs;
    report.gpu->pipelinesCreated += uint32_t(prepared);
    report.renderMs = msSince(t0);
    return frame;
}

Frame RenderSession::renderOnDevice(const Scene& scene, const RenderOptions& options, const Structure& structure,
                                    RenderReport& report) {
    gpu::GpuRenderReport& rep = report.gpu.emplace();
    Frame frame = device_.render(scene, options, *structure.data, rep, request_.progress.tiles);
    if (rep.cappedRays > 0 && request_.warn)
        request_.warn(std::to_string(rep.cappedRays) +
                      " rays reached the traversal's iteration cap and were ended there; their pixels may be wrong");
    return frame;
}

}  // namespace vkray::render
