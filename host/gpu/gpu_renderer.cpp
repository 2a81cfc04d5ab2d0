#include "gpu/gpu_renderer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <optional>

#include "core/error.h"
#include "gpu/buffer.h"
#include "gpu/compute_kernel.h"
#include "gpu/scene_buffers.h"
#include "render_kernels.h"  // generated at build time from shaders/render_*.comp
#include "scene/camera.h"
#include "shared/gpu_layout.h"

namespace vkray::gpu {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

constexpr uint32_t kTilePixels = VKRAY_TILE_SIZE * VKRAY_TILE_SIZE;
// Few tiles per submission: progress is reported per submission, and read-back overlaps nothing
// anyway; 4 tiles = 16 MiB of GpuPixel.
constexpr uint32_t kMaxTilesPerSubmission = 4;

struct Tile {
    uint32_t x, y, width, height;
};

std::vector<Tile> splitIntoTiles(uint32_t width, uint32_t height) {
    std::vector<Tile> tiles;
    for (uint32_t y = 0; y < height; y += VKRAY_TILE_SIZE)
        for (uint32_t x = 0; x < width; x += VKRAY_TILE_SIZE)
            tiles.push_back({x, y, std::min<uint32_t>(VKRAY_TILE_SIZE, width - x),
                             std::min<uint32_t>(VKRAY_TILE_SIZE, height - y)});
    return tiles;
}

GpuFrameParams frameParams(const Scene& scene, const RenderOptions& options) {
    const CameraFrame cam = makeCameraFrame(scene.camera, options.width, options.height);
    GpuFrameParams p{};
    p.eye = vec4(glm::vec3(cam.eye), 0.0f);
    p.u = vec4(glm::vec3(cam.u), float(cam.tanX));
    p.v = vec4(glm::vec3(cam.v), float(cam.tanY));
    p.w = vec4(glm::vec3(cam.w), 0.0f);
    p.attenuation = vec4(scene.attenuation, 0.0f);
    p.imageTile = uvec4(uint32_t(options.width), uint32_t(options.height), 0u, 0u);
    p.counts = uvec4(uint32_t(scene.triangles.size()), uint32_t(scene.lights.size()), 0u,
                     uint32_t(VKRAY_TILE_SIZE));
    return p;
}

void readTile(const GpuPixel* src, const Tile& tile, Frame& frame, GpuRenderReport& rep) {
    for (uint32_t y = 0; y < tile.height; ++y)
        for (uint32_t x = 0; x < tile.width; ++x) {
            const GpuPixel& px = src[y * VKRAY_TILE_SIZE + x];
            const size_t i = frame.index(int(tile.x + x), int(tile.y + y));
            frame.color[i] = px.color;
            frame.depth[i] = px.depth;
            frame.normal[i] = px.normal;
            frame.primId[i] = px.primId;
            rep.raysTraced += px.rays;
            rep.shadowRays += px.shadowRays;
            rep.cappedRays += px.capped;
            rep.nodesVisited += px.nodes;
            rep.leavesVisited += px.leaves;
            rep.trianglesTested += px.triangles;
            rep.restarts += px.restarts;
            if (!rep.nodesPerPixel.empty()) rep.nodesPerPixel[i] = px.nodes;
            rep.pixelsCutShort += (px.flags & VKRAY_PIXEL_CUT_SHORT) != 0;
        }
}

const generated::RenderKernelSpirv* findKernel(const std::string& name) {
    for (const auto& k : generated::kRenderKernels)
        if (k.name == name) return &k;
    return nullptr;
}

}  // namespace

bool hasRenderKernel(const std::string& kernel) { return findKernel(kernel) != nullptr; }

KernelCache::KernelCache(const VulkanContext& ctx) : ctx_(ctx) {}
KernelCache::~KernelCache() = default;

ComputeKernel& KernelCache::kernel(const std::string& name, std::span<const uint32_t> spirv,
                                   const Specialization& spec) {
    auto& slot = kernels_[{name, spec.values}];
    if (!slot)
        slot = std::make_unique<ComputeKernel>(ctx_, spirv, VKRAY_BINDING_COUNT, sizeof(GpuFrameParams), spec);
    return *slot;
}

Frame renderOnGpu(const VulkanContext& ctx, const Scene& scene, const RenderOptions& options,
                  GpuRenderReport* report, const TileProgress& progress) {
    accel::BuildOptions buildOptions;
    buildOptions.threads = options.threads;
    const auto built = accel::buildAccel(scene, accel::parseAccel(options.accel), buildOptions);
    return renderOnGpu(ctx, scene, options, built->gpuData(), report, progress);
}

Frame renderOnGpu(const VulkanContext& ctx, const Scene& scene, const RenderOptions& options,
                  const accel::GpuAccelData& accel, GpuRenderReport* report, const TileProgress& progress,
                  KernelCache* kernels) {
    const generated::RenderKernelSpirv* spirv = findKernel(accel.kernel);
    if (!spirv) throw Error("internal: no render kernel shaders/render_" + accel.kernel + ".comp");
    GpuRenderReport local;
    GpuRenderReport& rep = report ? *report : local;
    rep = GpuRenderReport{};
    rep.kernel = accel.kernel;
    const GpuFrameParams baseParams = frameParams(scene, options);  // validates camera and size

    auto start = Clock::now();
    const PackedScene packed = packScene(scene, accel.triangleOrder);
    SceneBuffers sceneBuffers = uploadScene(ctx, packed);
    AccelBuffers accelBuffers = uploadAccel(ctx, accel);
    rep.accelBytes = accelBuffers.bytes;
    rep.bytesUploaded = sceneBuffers.bytes + accelBuffers.bytes;
    rep.uploadMs = msSince(start);

    start = Clock::now();
    rep.features = ShaderFeatures::forScene(scene, options.maxDepth);
    rep.features.countTraversal = options.countTraversal;
    std::optional<KernelCache> ownKernels;
    if (!kernels) kernels = &ownKernels.emplace(ctx);
    ComputeKernel& kernel = kernels->kernel(accel.kernel, spirv->code, rep.features.specialization());
    rep.pipelineMs = msSince(start);

    const std::vector<Tile> tiles = splitIntoTiles(uint32_t(options.width), uint32_t(options.height));
    const uint64_t tileBytes = uint64_t(kTilePixels) * sizeof(GpuPixel);
    const uint32_t perSubmission = uint32_t(std::clamp<uint64_t>(
        std::min<uint64_t>({tiles.size(), kMaxTilesPerSubmission,
                            ctx.info().maxStorageBufferRange / tileBytes}),
        1, kMaxTilesPerSubmission));
    Buffer pixels(ctx, perSubmission * tileBytes, vk::BufferUsageFlagBits::eStorageBuffer,
                  MemoryUse::Readback, "pixels");
    std::array<vk::Buffer, VKRAY_BINDING_COUNT> bindings{};
    bindings[VKRAY_BINDING_TRIANGLES] = sceneBuffers.triangles.handle();
    bindings[VKRAY_BINDING_NORMALS] = sceneBuffers.normals.handle();
    bindings[VKRAY_BINDING_MATERIALS] = sceneBuffers.materials.handle();
    bindings[VKRAY_BINDING_LIGHTS] = sceneBuffers.lights.handle();
    bindings[VKRAY_BINDING_PIXELS] = pixels.handle();
    bindings[VKRAY_BINDING_ACCEL_NODES] = accelBuffers.nodes.handle();
    bindings[VKRAY_BINDING_ACCEL_INDICES] = accelBuffers.indices.handle();
    bindings[VKRAY_BINDING_ACCEL_EXTRA] = accelBuffers.extra.handle();
    kernel.bindStorageBuffers(bindings);

    const bool timestamps = ctx.timestampValidBits() > 0;
    vk::raii::QueryPool queries{nullptr};
    if (timestamps)
        queries = vk::raii::QueryPool(ctx.device(), vk::QueryPoolCreateInfo{
                                                        .queryType = vk::QueryType::eTimestamp,
                                                        .queryCount = 2});
    const uint64_t validMask = ctx.timestampValidBits() >= 64
                                   ? ~uint64_t(0)
                                   : (uint64_t(1) << ctx.timestampValidBits()) - 1;

    Frame frame;
    frame.resize(options.width, options.height);
    if (options.countTraversal) rep.nodesPerPixel.assign(frame.color.size(), 0u);
    rep.tiles = uint32_t(tiles.size());
    rep.gpuMs = timestamps ? 0.0 : -1.0;
    start = Clock::now();
    for (size_t first = 0; first < tiles.size(); first += perSubmission) {
        const size_t count = std::min<size_t>(perSubmission, tiles.size() - first);
        OneShotCommands commands(ctx);
        const vk::raii::CommandBuffer& cmd = commands.begin();
        if (timestamps) {
            cmd.resetQueryPool(*queries, 0, 2);
            cmd.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries, 0);
        }
        for (size_t k = 0; k < count; ++k) {
            const Tile& t = tiles[first + k];
            GpuFrameParams p = baseParams;
            p.imageTile.z = t.x;
            p.imageTile.w = t.y;
            p.counts.z = uint32_t(k) * kTilePixels;
            kernel.dispatch(cmd, &p, (t.width + VKRAY_WORKGROUP_X - 1) / VKRAY_WORKGROUP_X,
                            (t.height + VKRAY_WORKGROUP_Y - 1) / VKRAY_WORKGROUP_Y);
        }
        if (timestamps) cmd.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *queries, 1);
        // The host reads the pixels once the fence signals: make the kernel's writes visible to it.
        vk::MemoryBarrier toHost{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                 .dstAccessMask = vk::AccessFlagBits::eHostRead};
        cmd.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eHost,
                            {}, toHost, nullptr, nullptr);
        commands.submitAndWait();
        ++rep.submissions;

        if (timestamps) {
            auto [result, stamps] = queries.getResults<uint64_t>(
                0, 2, 2 * sizeof(uint64_t), sizeof(uint64_t),
                vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
            if (result == vk::Result::eSuccess) {
                const uint64_t ticks = ((stamps[1] & validMask) - (stamps[0] & validMask)) & validMask;
                rep.gpuMs += double(ticks) * double(ctx.info().timestampPeriodNs) * 1e-6;
            }
        }
        const auto* src = static_cast<const GpuPixel*>(pixels.mapped());
        for (size_t k = 0; k < count; ++k) readTile(src + k * kTilePixels, tiles[first + k], frame, rep);
        if (progress) progress(uint32_t(first + count), uint32_t(tiles.size()));
    }
    rep.renderMs = msSince(start);
    ctx.checkValidation();
    if (rep.pixelsCutShort > 0) {
        const std::string remedy = accel.kernel == "brute"
                                       ? "an acceleration structure (--accel bvh), a smaller --maxdepth or "
                                         "fewer lights"
                                       : "a smaller --maxdepth or fewer lights";
        throw Error(std::to_string(rep.pixelsCutShort) + " pixels were cut short on '" + ctx.info().name +
                    "': its shader loops stop early (llvmpipe ends all loops of a pixel after 65535 "
                    "iterations in total); with --accel " + options.accel + " this scene of " +
                    std::to_string(scene.triangles.size()) + " triangles needs " + remedy +
                    ", or another device; no image was written");
    }
    return frame;
}

}  // namespace vkray::gpu
