#include "gpu/gpu_renderer.h"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/timing.h"
#include "gpu/compute_kernel.h"
#include "gpu/kernel_bindings.h"
#include "gpu/kernel_registry.h"
#include "gpu/pixel_output.h"
#include "gpu/resumable_pass.h"
#include "gpu/scene_buffers.h"
#include "gpu/tile_pass.h"
#include "gpu/tile_records.h"
#include "scene/camera.h"
#include "shared/gpu_layout.h"

namespace vkray::gpu {
namespace {

// Sample s of every pixel (RenderOptions::spp): where in its pixel the camera ray goes.
void setSample(GpuFrameParams& p, int s) {
    const glm::vec2 offset = pixelSampleOffset(s);
    p.eye.w = offset.x;
    p.w.w = offset.y;
}

GpuFrameParams frameParams(const Scene& scene, const RenderOptions& options) {
    const CameraFrame cam = makeCameraFrame(scene.camera, options.width, options.height);
    GpuFrameParams p{};
    p.eye = vec4(glm::vec3(cam.eye), 0.0f);
    p.u = vec4(glm::vec3(cam.u), float(cam.tanX));
    p.v = vec4(glm::vec3(cam.v), float(cam.tanY));
    p.w = vec4(glm::vec3(cam.w), 0.0f);
    p.attenuation = vec4(scene.attenuation, 0.0f);
    p.background = glm::vec3(scene.background);
    p.imageTile = uvec4(uint32_t(options.width), uint32_t(options.height), 0u, 0u);
    setSample(p, 0);
    p.counts = uvec4(uint32_t(scene.triangles.size()), uint32_t(scene.lights.size()), 0u,
                     uint32_t(VKRAY_TILE_SIZE));
    return p;
}

// llvmpipe of Mesa 22.3 ends all loops of an invocation after 65535 iterations in total; the kernel
// flags such pixels, and an image with any of them is refused rather than written wrong.
void throwIfCutShort(const VulkanContext& ctx, const Scene& scene, accel::Traversal traversal, uint64_t pixels) {
    if (pixels == 0) return;
    const std::string remedy = traversal == accel::Traversal::Brute
                                   ? "an acceleration structure (--accel bvh), a smaller --maxdepth or fewer lights"
                                   : "a smaller --maxdepth or fewer lights";
    throw Error(std::to_string(pixels) + " pixels were cut short on '" + ctx.info().name +
                "': its shader loops stop early (llvmpipe of Mesa 22.3 ends all loops of a pixel after 65535 "
                "iterations in total); with the " + std::string(kernelName(traversal)) + " kernel this scene of " +
                std::to_string(scene.triangles.size()) + " triangles needs " + remedy +
                ", or another device; no image was written");
}

// The scene and the structure on the device, their arrays split over views of one size.
struct Uploaded {
    SceneBuffers scene;
    AccelBuffers accel;
    int viewBits = 0;
};

Uploaded upload(const VulkanContext& ctx, const Scene& scene, const accel::GpuAccelData& accel, GpuRenderReport& rep) {
    const auto start = Clock::now();
    const PackedScene packed = packScene(scene, accel.triangleOrder);
    const int viewBits = texelViewBits(ctx, texelArraySizes(packed, accel));
    Uploaded u{uploadScene(ctx, packed, viewBits), uploadAccel(ctx, accel, packed, viewBits), viewBits};
    rep.accelBytes = u.accel.bytes;
    if (u.accel.driver) rep.driverBuildMs = u.accel.driver->buildMs();
    rep.bytesUploaded = u.scene.bytes + u.accel.bytes;
    rep.uploadMs = msSince(start);
    return u;
}

// What the passes of one render share.
struct Pass {
    const VulkanContext& ctx;
    const Scene& scene;
    const RenderOptions& options;
    accel::Traversal traversal;
    KernelCache& kernels;
    const Uploaded& buffers;
    const PixelOutput& pixels;
    const GpuFrameParams& base;  // sample 0's
};

// One pass over the window's tiles for sample `s` into `out`: the plain kernel, then its resumable
// variant for the tiles it could not finish (or every tile, where the render is resumable from the
// start).
void renderSample(const Pass& pass, ComputeKernel& plain, std::span<const Tile> tiles, uint32_t perSubmission, int s,
                  Frame& out, GpuRenderReport& rep, const TileProgress& progress) {
    GpuFrameParams params = pass.base;
    setSample(params, s);
    const int spp = pass.options.spp;
    const TileProgress passProgress = !progress ? TileProgress() : [&](uint32_t done, uint32_t total) {
        progress(uint32_t(s) * total + done, uint32_t(spp) * total);
    };
    std::vector<Tile> unfinished;
    if (rep.resumedFromStart) unfinished.assign(tiles.begin(), tiles.end());
    else renderTiles(pass.ctx, plain, pass.pixels, tiles, perSubmission, params, out, rep, passProgress, unfinished);
    if (unfinished.empty()) return;
    ShaderFeatures resumable = rep.features;
    resumable.resumable = true;
    ComputeKernel& again = pass.kernels.kernel(pass.traversal, resumable);
    renderResumable(pass.ctx, again, resumable, pass.buffers.scene, pass.buffers.accel, pass.pixels, unfinished,
                    pass.options.maxDepth, params, out, rep, passProgress);
}

}  // namespace

Frame renderOnGpu(const VulkanContext& ctx, const Scene& scene, const RenderOptions& options,
                  const accel::GpuAccelData& accel, GpuRenderReport* report, const TileProgress& progress,
                  KernelCache* kernels) {
    GpuRenderReport local;
    GpuRenderReport& rep = report ? *report : local;
    rep = GpuRenderReport{};
    rep.kernel = std::string(kernelName(kernelTraversal(ctx, accel.traversal)));
    rep.packetWalk = accel::isPacketWalk(kernelTraversal(ctx, accel.traversal));
    const GpuFrameParams base = frameParams(scene, options);  // validates camera and size
    const Uploaded buffers = upload(ctx, scene, accel, rep);

    auto start = Clock::now();
    rep.features = renderFeatures(ctx, scene, options, accel.maxLeafTriangles, accel.kdShortStack);
    rep.features.texelViewBits = buffers.viewBits;
    std::optional<KernelCache> ownKernels;
    if (!kernels) kernels = &ownKernels.emplace(ctx);
    const size_t pipelinesBefore = kernels->size();
    ComputeKernel& kernel = kernels->kernel(accel.traversal, rep.features);
    rep.pipelineMs = msSince(start);

    const PixelWindow window = options.pixels();
    if (const auto problem = windowProblem(window, options.width, options.height)) throw Error(*problem);
    const std::vector<Tile> tiles = splitIntoTiles(window);
    const uint32_t perSubmission = tilesPerSubmission(ctx, tiles.size());
    const PixelOutput pixels(ctx, uint64_t(perSubmission) * kTilePixels * sizeof(GpuPixel));
    const ResumeBuffers noResume(ctx, 0, 0);
    bindBuffers(kernel, buffers.scene, buffers.accel, pixels, noResume);

    Frame frame;
    frame.resize(window, options.primaryAovs);
    if (options.countTraversal) rep.nodesPerPixel.assign(frame.color.size(), 0u);
    rep.lockstepLanes = std::max(1u, ctx.info().subgroupSize);
    start = Clock::now();
    rep.tiles = uint32_t(tiles.size());
    rep.gpuMs = ctx.timestampValidBits() > 0 ? 0.0 : -1.0;
    rep.resumedFromStart = resumableFromStart(ctx, scene, accel.traversal);
    // One pass over the image per sample (RenderOptions::spp): sample 0, the pixel centres, gives
    // the AOVs; the others only add their colour.
    const Pass pass{ctx, scene, options, accel.traversal, *kernels, buffers, pixels, base};
    Frame more;
    for (int s = 0; s < options.spp; ++s) {
        if (s == 1) more.resize(window, false);  // colour only: the AOVs are sample 0's
        renderSample(pass, kernel, tiles, perSubmission, s, s == 0 ? frame : more, rep, progress);
        if (s > 0)
            for (size_t i = 0; i < frame.color.size(); ++i) frame.color[i] += more.color[i];
    }
    if (options.spp > 1)
        for (glm::vec3& c : frame.color) c /= float(options.spp);
    rep.renderMs = msSince(start);
    rep.pipelinesCreated = uint32_t(kernels->size() - pipelinesBefore);
    ctx.checkValidation();
    throwIfCutShort(ctx, scene, accel.traversal, rep.pixelsCutShort);
    return frame;
}

}  // namespace vkray::gpu
