#include "gpu/gpu_renderer.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/timing.h"
#include "gpu/buffer.h"
#include "gpu/compute_kernel.h"
#include "gpu/lockstep.h"
#include "gpu/pixel_output.h"
#include "gpu/scene_buffers.h"
#include "render_kernels.h"  // generated at build time from shaders/render_*.comp
#include "scene/camera.h"
#include "shared/gpu_layout.h"

namespace vkray::gpu {
namespace {

constexpr uint32_t kTilePixels = VKRAY_TILE_SIZE * VKRAY_TILE_SIZE;

// The render kernels' bindings (shared/gpu_layout.h): storage buffers, then arrays of texel views.
constexpr auto kBindings = [] {
    std::array<ComputeKernel::Binding, VKRAY_BINDING_COUNT> bindings{};
    for (uint32_t i = 0; i < VKRAY_BINDING_COUNT; ++i)
        bindings[i] = i < VKRAY_STORAGE_BINDING_COUNT
                          ? ComputeKernel::Binding{vk::DescriptorType::eStorageBuffer, 1}
                          : ComputeKernel::Binding{vk::DescriptorType::eUniformTexelBuffer, VKRAY_TEXEL_VIEWS};
    return bindings;
}();
// Tiles per submission. On a CPU device (lavapipe) few: a tile takes a good fraction of a second,
// progress is reported per submission, and read-back overlaps nothing anyway; 4 tiles = 16 MiB of
// GpuPixel. On a GPU a tile is far too small to fill the device (65,536 invocations), and each
// submission waits on its fence: as many tiles as 256 MiB of GpuPixel, so that 1920x1080 (40 tiles)
// is one submission.
constexpr uint32_t kMaxTilesPerSubmissionCpu = 4;
constexpr uint64_t kMaxBytesPerSubmission = uint64_t(256) << 20;

struct Tile {
    uint32_t x, y, width, height;
};

// A batch of compact records (render_main.glsl, "Pixel records"): its tiles' GpuPixelColor records,
// then a GpuTileCounts a tile, from this byte of the pixel buffer on.
vk::DeviceSize tileCountsOffset(size_t tiles) { return tiles * kTilePixels * sizeof(GpuPixelColor); }
static_assert(kTilePixels * sizeof(GpuPixelColor) % sizeof(GpuTileCounts) == 0,
              "the counts start at a whole GpuTileCounts of the buffer");

// The bytes of a batch of `tiles` the host reads, as the kernel of `features` writes them.
vk::DeviceSize batchBytes(size_t tiles, const ShaderFeatures& features) {
    return features.compactPixels() ? tileCountsOffset(tiles) + tiles * sizeof(GpuTileCounts)
                                    : tiles * kTilePixels * sizeof(GpuPixel);
}

// The window's pixels as tiles, in image coordinates.
std::vector<Tile> splitIntoTiles(const PixelWindow& window) {
    std::vector<Tile> tiles;
    for (uint32_t y = uint32_t(window.y0); y < uint32_t(window.y1); y += VKRAY_TILE_SIZE)
        for (uint32_t x = uint32_t(window.x0); x < uint32_t(window.x1); x += VKRAY_TILE_SIZE)
            tiles.push_back({x, y, std::min<uint32_t>(VKRAY_TILE_SIZE, uint32_t(window.x1) - x),
                             std::min<uint32_t>(VKRAY_TILE_SIZE, uint32_t(window.y1) - y)});
    return tiles;
}

// A tile as strips of at most `rows` rows (each dispatched as a tile of its own).
std::vector<Tile> splitIntoStrips(const Tile& tile, uint32_t rows) {
    std::vector<Tile> strips;
    for (uint32_t y = 0; y < tile.height; y += rows)
        strips.push_back({tile.x, tile.y + y, tile.width, std::min(rows, tile.height - y)});
    return strips;
}

// Calls f(record, x, y) for each pixel of `tile` (x, y within it), its record at `src` (GpuPixel or
// GpuPixelColor, VKRAY_TILE_SIZE a row).
template <class Record, class F>
void forEachRecord(const Record* src, const Tile& tile, F&& f) {
    for (uint32_t y = 0; y < tile.height; ++y)
        for (uint32_t x = 0; x < tile.width; ++x) f(src[y * VKRAY_TILE_SIZE + x], x, y);
}

// Pixels of `tile` (its records at `src`) with `flag` set.
template <class Record>
uint32_t countFlagged(const Record* src, const Tile& tile, uint32_t flag) {
    uint32_t n = 0;
    forEachRecord(src, tile, [&](const Record& r, uint32_t, uint32_t) { n += (r.flags & flag) != 0; });
    return n;
}

// Index in `frame` of pixel (x, y) of `tile`.
size_t frameIndex(const Frame& frame, const Tile& tile, uint32_t x, uint32_t y) {
    return frame.index(int(tile.x + x) - frame.x0, int(tile.y + y) - frame.y0);
}

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

// Reads the pixels of `tile` (image coordinates) into `frame` and `rep`: the fields the kernel of
// `features` writes.
void readTile(const GpuPixel* src, const Tile& tile, const ShaderFeatures& features, Frame& frame,
              GpuRenderReport& rep) {
    // Only a frame that keeps the AOVs gets them (the resumable variant writes them for itself).
    const bool aovs = frame.hasAovs(), counters = features.writesCounters();
    forEachRecord(src, tile, [&](const GpuPixel& px, uint32_t x, uint32_t y) {
        const size_t i = frameIndex(frame, tile, x, y);
        frame.color[i] = px.color;
        if (aovs) {
            frame.depth[i] = px.depth;
            frame.normal[i] = px.normal;
            frame.primId[i] = px.primId;
        }
        rep.raysTraced += px.rays;
        rep.shadowRays += px.shadowRays;
        rep.cappedRays += px.capped;
        if (counters) {
            rep.nodesVisited += px.nodes;
            rep.leavesVisited += px.leaves;
            rep.trianglesTested += px.triangles;
            rep.restarts += px.restarts;
            if (!rep.nodesPerPixel.empty()) rep.nodesPerPixel[i] += px.nodes;  // every sample's
        }
        rep.pixelsCutShort += (px.flags & VKRAY_PIXEL_CUT_SHORT) != 0;
    });
    if (counters)
        rep.lockstepNodes += lockstepNodes(tile.width, tile.height, rep.lockstepLanes,
                                           [&](uint32_t x, uint32_t y) { return src[y * VKRAY_TILE_SIZE + x].nodes; });
}

// Reads the compact records of `tile` (render_main.glsl, "Pixel records"), none of them cut short
// (those tiles go to the resumable variant), and its ray counts into `frame` and `rep`.
void readCompactTile(const GpuPixelColor* src, const GpuTileCounts& counts, const Tile& tile, Frame& frame,
                     GpuRenderReport& rep) {
    forEachRecord(src, tile,
                  [&](const GpuPixelColor& px, uint32_t x, uint32_t y) { frame.color[frameIndex(frame, tile, x, y)] = px.color; });
    const auto sum = [](uint32_t low, uint32_t high) { return uint64_t(high) << 32 | low; };
    rep.raysTraced += sum(counts.raysLow, counts.raysHigh);
    rep.shadowRays += sum(counts.shadowRaysLow, counts.shadowRaysHigh);
    rep.cappedRays += sum(counts.cappedLow, counts.cappedHigh);
}

// The position of a kernel's SPIR-V in the generated registry, -1 when it has none. An index rather
// than a pointer: comparing the address of a global with null is not a constant expression under
// AddressSanitizer.
constexpr int kernelIndex(accel::Kernel kernel) {
    for (size_t i = 0; i < std::size(generated::kRenderKernels); ++i)
        if (generated::kRenderKernels[i].name == accel::kernelName(kernel)) return int(i);
    return -1;
}

// Every accel::Kernel must have its shaders/render_<name>.comp, or the build fails here.
constexpr bool everyKernelHasSpirv() {
    for (accel::Kernel k : accel::kKernels)
        if (kernelIndex(k) < 0) return false;
    return true;
}
static_assert(everyKernelHasSpirv(), "an accel::Kernel has no shaders/render_<kernel>.comp");

// Two timestamps around each submission; their differences add up to the GPU time of a render.
class BatchTimer {
public:
    explicit BatchTimer(const VulkanContext& ctx) : ctx_(ctx) {
        const uint32_t bits = ctx.timestampValidBits();
        if (bits == 0) return;  // the queue has no timestamps: gpuMs stays -1
        mask_ = bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1;
        queries_ = vk::raii::QueryPool(ctx.device(), vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp,
                                                                             .queryCount = 2});
    }
    bool enabled() const { return mask_ != 0; }
    void begin(const vk::raii::CommandBuffer& cmd) const {
        if (!enabled()) return;
        cmd.resetQueryPool(*queries_, 0, 2);
        cmd.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries_, 0);
    }
    void end(const vk::raii::CommandBuffer& cmd) const {
        if (enabled()) cmd.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *queries_, 1);
    }
    // Milliseconds between the two stamps of the batch just waited for (0 when unavailable).
    double batchMs() const {
        if (!enabled()) return 0.0;
        auto [result, stamps] = queries_.getResults<uint64_t>(0, 2, 2 * sizeof(uint64_t), sizeof(uint64_t),
                                                              vk::QueryResultFlagBits::e64 |
                                                                  vk::QueryResultFlagBits::eWait);
        if (result != vk::Result::eSuccess) return 0.0;
        const uint64_t ticks = ((stamps[1] & mask_) - (stamps[0] & mask_)) & mask_;
        return double(ticks) * double(ctx_.info().timestampPeriodNs) * 1e-6;
    }

private:
    const VulkanContext& ctx_;
    uint64_t mask_ = 0;
    vk::raii::QueryPool queries_{nullptr};
};

// Tiles per submission: the device kind's limit above, and what one storage buffer holds.
uint32_t tilesPerSubmission(const VulkanContext& ctx, size_t tiles) {
    const uint64_t tileBytes = uint64_t(kTilePixels) * sizeof(GpuPixel);
    const uint64_t limit = ctx.info().type == "cpu" ? kMaxTilesPerSubmissionCpu : kMaxBytesPerSubmission / tileBytes;
    return uint32_t(std::max<uint64_t>(
        std::min<uint64_t>({tiles, limit, ctx.info().maxStorageBufferRange / tileBytes}), 1));
}

// Records the dispatches of `tiles` into `cmd`, each writing its own slice of the pixel buffer. An
// invocation of the kernel specialised with `features` renders features.invocationPixels() pixels,
// one in each of as many bands of the tile's 8x8 block rows: that many times fewer workgroup rows.
void recordBatch(const vk::raii::CommandBuffer& cmd, const ComputeKernel& kernel, const ShaderFeatures& features,
                 std::span<const Tile> tiles, const GpuFrameParams& base) {
    const uint32_t blockRows = features.invocationPixels();
    for (size_t k = 0; k < tiles.size(); ++k) {
        const Tile& t = tiles[k];
        GpuFrameParams p = base;
        p.imageTile.z = t.x;
        p.imageTile.w = t.y;
        p.counts.z = uint32_t(k) * kTilePixels;
        p.tileCounts = uint32_t(tileCountsOffset(tiles.size()) / sizeof(GpuTileCounts) + k);
        kernel.dispatch(cmd, &p, (t.width + VKRAY_WORKGROUP_X - 1) / VKRAY_WORKGROUP_X,
                        (t.height + VKRAY_WORKGROUP_Y * blockRows - 1) / (VKRAY_WORKGROUP_Y * blockRows));
    }
}

// The resumable variant's records (VKRAY_BINDING_RESUME, _RESUME_RAYS): for `pixels` pixels of
// `maxDepth` pending rays each, or one-element dummies for the plain kernel.
struct ResumeBuffers {
    Buffer records, rays;
    ResumeBuffers(const VulkanContext& ctx, uint64_t pixels, uint64_t maxDepth)
        : records(ctx, std::max<uint64_t>(pixels, 1) * sizeof(GpuPixelResume),
                  vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst,
                  MemoryUse::DeviceLocal, "resumable pixels"),
          rays(ctx, std::max<uint64_t>(pixels * maxDepth, 1) * sizeof(GpuPendingRay),
               vk::BufferUsageFlagBits::eStorageBuffer, MemoryUse::DeviceLocal, "resumable pixels' rays") {}
};

// A binding's VKRAY_TEXEL_VIEWS views: the array's, then its first again where it has fewer (the
// kernel reads only those that hold the array; the rest must still be valid descriptors).
std::vector<vk::BufferView> viewHandles(const TexelArray& array) {
    std::vector<vk::BufferView> views(VKRAY_TEXEL_VIEWS, array.views.front().handle());
    for (size_t v = 0; v < array.views.size(); ++v) views[v] = array.views[v].handle();
    return views;
}

void bindBuffers(ComputeKernel& kernel, const SceneBuffers& scene, const AccelBuffers& accel,
                 const PixelOutput& pixels, const ResumeBuffers& resume) {
    std::array<ComputeKernel::Resource, VKRAY_BINDING_COUNT> r{};
    r[VKRAY_BINDING_PIXELS].buffer = pixels.target().handle();
    r[VKRAY_BINDING_RESUME].buffer = resume.records.handle();
    r[VKRAY_BINDING_RESUME_RAYS].buffer = resume.rays.handle();
    r[VKRAY_BINDING_TRIANGLE_TEXELS].views = viewHandles(scene.triangles);
    r[VKRAY_BINDING_NODE_TEXELS].views = viewHandles(accel.nodes);
    r[VKRAY_BINDING_INDEX_TEXELS].views = viewHandles(accel.indices);
    r[VKRAY_BINDING_EXTRA_TEXELS].views = viewHandles(accel.extra);
    r[VKRAY_BINDING_NORMAL_TEXELS].views = viewHandles(scene.normals);
    r[VKRAY_BINDING_MATERIAL_TEXELS].views = viewHandles(scene.materials);
    r[VKRAY_BINDING_LIGHT_TEXELS].views = viewHandles(scene.lights);
    kernel.bind(r);
}

// Zeroes the GpuTileCounts of a batch of `tiles` before its dispatches add to them.
void zeroTileCounts(const vk::raii::CommandBuffer& cmd, const PixelOutput& pixels, size_t tiles) {
    cmd.fillBuffer(pixels.target().handle(), tileCountsOffset(tiles), tiles * sizeof(GpuTileCounts), 0u);
    const vk::MemoryBarrier filled{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                                   .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
    cmd.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, filled,
                        nullptr, nullptr);
}

// Reads a batch's records, as the kernel of `features` wrote them, into `frame` and `rep`; a tile with
// pixels cut short goes to `unfinished` instead.
void readBatch(const PixelOutput& pixels, std::span<const Tile> batch, const ShaderFeatures& features, Frame& frame,
               GpuRenderReport& rep, std::vector<Tile>& unfinished) {
    const auto* full = pixels.records<GpuPixel>();
    const auto* colors = pixels.records<GpuPixelColor>();
    const auto* counts = reinterpret_cast<const GpuTileCounts*>(pixels.records<std::byte>() + tileCountsOffset(batch.size()));
    const bool compact = features.compactPixels();
    for (size_t k = 0; k < batch.size(); ++k) {
        const size_t at = k * kTilePixels;
        const uint32_t cut = compact ? countFlagged(colors + at, batch[k], VKRAY_PIXEL_CUT_SHORT)
                                     : countFlagged(full + at, batch[k], VKRAY_PIXEL_CUT_SHORT);
        if (cut > 0) unfinished.push_back(batch[k]);
        else if (compact) readCompactTile(colors + at, counts[k], batch[k], frame, rep);
        else readTile(full + at, batch[k], features, frame, rep);
    }
}

// Dispatches the tiles, `perSubmission` at a time into `pixels`, and reads each batch into `frame`.
// A tile with pixels the driver's loop budget cut short is left for the resumable variant
// (renderResumable) and added to `unfinished`.
void renderTiles(const VulkanContext& ctx, const ComputeKernel& kernel, const PixelOutput& pixels,
                 std::span<const Tile> tiles, uint32_t perSubmission, const GpuFrameParams& base, Frame& frame,
                 GpuRenderReport& rep, const TileProgress& progress, std::vector<Tile>& unfinished) {
    const BatchTimer timer(ctx);
    for (size_t first = 0; first < tiles.size(); first += perSubmission) {
        const std::span<const Tile> batch = tiles.subspan(first, std::min<size_t>(perSubmission, tiles.size() - first));
        OneShotCommands commands(ctx);
        const vk::raii::CommandBuffer& cmd = commands.begin();
        if (rep.features.compactPixels()) zeroTileCounts(cmd, pixels, batch.size());
        timer.begin(cmd);
        recordBatch(cmd, kernel, rep.features, batch, base);
        timer.end(cmd);  // the kernels' time, not the copy's (PixelOutput)
        pixels.recordToHost(cmd, batchBytes(batch.size(), rep.features));
        commands.submitAndWait();
        ++rep.submissions;
        rep.gpuMs += timer.batchMs();
        readBatch(pixels, batch, rep.features, frame, rep, unfinished);
        if (progress) progress(uint32_t(first + batch.size()), uint32_t(tiles.size()));
    }
}

// Brute force over more triangles than one budget covers for a camera ray and its shadow rays (four
// triangles per loop pass) would run out on every tile of llvmpipe: such a render is resumable from
// the start, without a plain pass whose every tile would be rendered again.
bool resumableFromStart(const VulkanContext& ctx, const Scene& scene, accel::Kernel kernel) {
    const uint64_t passes = uint64_t(scene.triangles.size()) * (1 + scene.lights.size()) / 4;
    return ctx.info().loopBudget && kernel == accel::Kernel::Brute && passes > VKRAY_RESUMABLE_LOOP_BUDGET;
}

// Rows of a strip of the resumable variant: its records and pending-ray stacks must fit one storage
// buffer (VKRAY_TILE_SIZE pixels a row), in whole workgroup rows.
uint32_t resumeStripRows(const VulkanContext& ctx, int maxDepth) {
    const uint64_t perRow = uint64_t(VKRAY_TILE_SIZE) *
                            std::max<uint64_t>(sizeof(GpuPixelResume), uint64_t(maxDepth) * sizeof(GpuPendingRay));
    const uint64_t rows = ctx.info().maxStorageBufferRange / perRow / VKRAY_WORKGROUP_Y * VKRAY_WORKGROUP_Y;
    return uint32_t(std::clamp<uint64_t>(rows, VKRAY_WORKGROUP_Y, VKRAY_TILE_SIZE));
}

// Dispatches one strip with the resumable variant until none of its pixels is unfinished. Every
// dispatch either gets each unfinished pixel further or flags it cut short, so the loop ends.
void resumeStrip(const VulkanContext& ctx, const ComputeKernel& kernel, const ShaderFeatures& features,
                 const ResumeBuffers& resume, const PixelOutput& pixels, const Tile& strip, const GpuFrameParams& base,
                 GpuRenderReport& rep) {
    const BatchTimer timer(ctx);
    for (bool fresh = true;; fresh = false) {
        OneShotCommands commands(ctx);
        const vk::raii::CommandBuffer& cmd = commands.begin();
        if (fresh) {  // every record VKRAY_RESUME_FRESH
            cmd.fillBuffer(resume.records.handle(), 0, VK_WHOLE_SIZE, 0u);
            const vk::MemoryBarrier filled{
                .srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
            cmd.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {},
                                filled, nullptr, nullptr);
        }
        timer.begin(cmd);
        recordBatch(cmd, kernel, features, std::span<const Tile>(&strip, 1), base);
        timer.end(cmd);
        pixels.recordToHost(cmd, kTilePixels * sizeof(GpuPixel));
        commands.submitAndWait();
        ++rep.resumeDispatches;
        if (rep.gpuMs >= 0.0) rep.gpuMs += timer.batchMs();
        if (countFlagged(pixels.records<GpuPixel>(), strip, VKRAY_PIXEL_UNFINISHED) == 0) return;
    }
}

// Renders `tiles` again with `kernel`, the resumable variant of `features` (render_main.glsl,
// "Resumable pixels"), strip by strip, into `frame`.
void renderResumable(const VulkanContext& ctx, ComputeKernel& kernel, const ShaderFeatures& features,
                     const SceneBuffers& scene,
                     const AccelBuffers& accel, const PixelOutput& pixels, std::span<const Tile> tiles, int maxDepth,
                     const GpuFrameParams& base, Frame& frame, GpuRenderReport& rep, const TileProgress& progress) {
    const uint32_t rows = resumeStripRows(ctx, maxDepth);
    const ResumeBuffers resume(ctx, uint64_t(rows) * VKRAY_TILE_SIZE, uint64_t(maxDepth));
    bindBuffers(kernel, scene, accel, pixels, resume);
    rep.resumedTiles = uint32_t(tiles.size());
    rep.resumeRows = rows;
    for (size_t t = 0; t < tiles.size(); ++t) {
        for (const Tile& strip : splitIntoStrips(tiles[t], rows)) {
            resumeStrip(ctx, kernel, features, resume, pixels, strip, base, rep);  // the strip as a tile of its own
            readTile(pixels.records<GpuPixel>(), strip, features, frame, rep);
        }
        if (progress) progress(uint32_t(t + 1), uint32_t(tiles.size()));
    }
}

// llvmpipe ends all loops of an invocation after 65535 iterations in total; the kernel flags such
// pixels, and an image with any of them is refused rather than written wrong.
void throwIfCutShort(const VulkanContext& ctx, const Scene& scene, accel::Kernel kernel, uint64_t pixels) {
    if (pixels == 0) return;
    const std::string remedy = kernel == accel::Kernel::Brute
                                   ? "an acceleration structure (--accel bvh), a smaller --maxdepth or fewer lights"
                                   : "a smaller --maxdepth or fewer lights";
    throw Error(std::to_string(pixels) + " pixels were cut short on '" + ctx.info().name +
                "': its shader loops stop early (llvmpipe ends all loops of a pixel after 65535 iterations in "
                "total); with the " + std::string(accel::kernelName(kernel)) + " kernel this scene of " +
                std::to_string(scene.triangles.size()) + " triangles needs " + remedy +
                ", or another device; no image was written");
}

// With VKRAY_KERNEL_DIR set, render_<kernel>[_resumable][_split].spv (the variant's suffixes, as
// CMakeLists.txt names them) from that folder (docs/architecture.md, "Shaders"): a kernel edit is
// then timed against the built-in one without rebuilding vkray. Empty when unset.
std::vector<uint32_t> kernelFromDir(accel::Kernel kernel, KernelVariant variant) {
    const char* dir = std::getenv("VKRAY_KERNEL_DIR");
    if (!dir || !*dir) return {};
    const std::string suffix = std::string(variant.resumable ? "_resumable" : "") + (variant.splitViews ? "_split" : "");
    const std::filesystem::path file =
        std::filesystem::path(dir) / ("render_" + std::string(accel::kernelName(kernel)) + suffix + ".spv");
    std::ifstream in(file, std::ios::binary | std::ios::ate);
    if (!in) throw Error("VKRAY_KERNEL_DIR: cannot open " + file.string());
    const std::streamsize size = in.tellg();
    if (size <= 0 || size % 4 != 0)
        throw Error("VKRAY_KERNEL_DIR: " + file.string() + " is not SPIR-V (size " + std::to_string(size) + ")");
    std::vector<uint32_t> code(size_t(size) / 4);
    in.seekg(0);
    if (!in.read(reinterpret_cast<char*>(code.data()), size) || code[0] != 0x07230203u)
        throw Error("VKRAY_KERNEL_DIR: " + file.string() + " is not SPIR-V");
    std::fprintf(stderr, "vkray: kernel %s from %s\n", std::string(accel::kernelName(kernel)).c_str(),
                 file.c_str());
    return code;
}

}  // namespace

ShaderFeatures renderFeatures(const VulkanContext& ctx, const Scene& scene, const RenderOptions& options,
                              uint32_t maxLeafTriangles, uint32_t kdShortStack) {
    ShaderFeatures f = ShaderFeatures::forScene(scene, options.maxDepth);
    f.pixelsPerInvocation = int(ctx.info().pixelsPerInvocation);
    f.countTraversal = options.countTraversal;
    f.primaryAovs = options.primaryAovs;
    f.setMaxLeafTriangles(maxLeafTriangles);
    f.setKdShortStack(kdShortStack);
    return f;
}

double prepareKernel(const Scene& scene, const RenderOptions& options, accel::Kernel kernel, KernelCache& kernels) {
    const auto start = Clock::now();
    kernels.kernel(kernel, renderFeatures(kernels.context(), scene, options, 1));
    return msSince(start);
}

KernelCache::KernelCache(const VulkanContext& ctx) : ctx_(ctx) {}
KernelCache::~KernelCache() = default;

std::span<const uint32_t> KernelCache::spirv(accel::Kernel kernel, KernelVariant variant) {
    const std::pair key{kernel, variant.index()};
    auto it = spirvFromFiles_.find(key);
    if (it == spirvFromFiles_.end()) it = spirvFromFiles_.emplace(key, kernelFromDir(kernel, variant)).first;
    if (!it->second.empty()) return it->second;
    return generated::kRenderKernels[kernelIndex(kernel)].variants[variant.index()];
}

ComputeKernel& KernelCache::kernel(accel::Kernel kernel, const ShaderFeatures& features) {
    const Specialization spec = features.specialization();
    const KernelVariant variant = features.variant();
    auto& slot = kernels_[{{kernel, variant.index()}, spec.values}];
    if (!slot)
        slot = std::make_unique<ComputeKernel>(ctx_, spirv(kernel, variant), kBindings,
                                               sizeof(GpuFrameParams), spec);
    return *slot;
}

Frame renderOnGpu(const VulkanContext& ctx, const Scene& scene, const RenderOptions& options,
                  const accel::AccelSpec& spec, GpuRenderReport* report, const TileProgress& progress) {
    const auto built =
        accel::buildAccel(scene, spec, accel::BuildOptions{.threads = options.threads, .progress = {}});
    return renderOnGpu(ctx, scene, options, built->gpuData(), report, progress);
}

Frame renderOnGpu(const VulkanContext& ctx, const Scene& scene, const RenderOptions& options,
                  const accel::GpuAccelData& accel, GpuRenderReport* report, const TileProgress& progress,
                  KernelCache* kernels) {
    GpuRenderReport local;
    GpuRenderReport& rep = report ? *report : local;
    rep = GpuRenderReport{};
    rep.kernel = std::string(accel::kernelName(accel.kernel));
    const GpuFrameParams baseParams = frameParams(scene, options);  // validates camera and size

    auto start = Clock::now();
    const PackedScene packed = packScene(scene, accel.triangleOrder);
    const int viewBits = texelViewBits(ctx, texelArraySizes(packed, accel));
    SceneBuffers sceneBuffers = uploadScene(ctx, packed, viewBits);
    AccelBuffers accelBuffers = uploadAccel(ctx, accel, viewBits);
    rep.accelBytes = accelBuffers.bytes;
    rep.bytesUploaded = sceneBuffers.bytes + accelBuffers.bytes;
    rep.uploadMs = msSince(start);

    start = Clock::now();
    rep.features = renderFeatures(ctx, scene, options, accel.maxLeafTriangles, accel.kdShortStack);
    rep.features.texelViewBits = viewBits;
    std::optional<KernelCache> ownKernels;
    if (!kernels) kernels = &ownKernels.emplace(ctx);
    const size_t pipelinesBefore = kernels->size();
    ComputeKernel& kernel = kernels->kernel(accel.kernel, rep.features);
    rep.pipelineMs = msSince(start);

    const PixelWindow window = options.pixels();
    if (const auto problem = windowProblem(window, options.width, options.height)) throw Error(*problem);
    const std::vector<Tile> tiles = splitIntoTiles(window);
    const uint32_t perSubmission = tilesPerSubmission(ctx, tiles.size());
    const PixelOutput pixels(ctx, uint64_t(perSubmission) * kTilePixels * sizeof(GpuPixel));
    const ResumeBuffers noResume(ctx, 0, 0);
    bindBuffers(kernel, sceneBuffers, accelBuffers, pixels, noResume);

    Frame frame;
    frame.resize(window, options.primaryAovs);
    if (options.countTraversal) rep.nodesPerPixel.assign(frame.color.size(), 0u);
    rep.lockstepLanes = std::max(1u, ctx.info().subgroupSize);
    start = Clock::now();
    rep.tiles = uint32_t(tiles.size());
    rep.gpuMs = ctx.timestampValidBits() > 0 ? 0.0 : -1.0;
    rep.resumedFromStart = resumableFromStart(ctx, scene, accel.kernel);
    // One pass over the image per sample (RenderOptions::spp): sample 0, the pixel centres, gives
    // the AOVs; the others only add their colour.
    Frame pass;
    for (int s = 0; s < options.spp; ++s) {
        GpuFrameParams params = baseParams;
        setSample(params, s);
        Frame& out = s == 0 ? frame : pass;
        if (s == 1) pass.resize(window, false);  // colour only: the AOVs are sample 0's
        const TileProgress passProgress = !progress ? TileProgress() : [&](uint32_t done, uint32_t total) {
            progress(uint32_t(s) * total + done, uint32_t(options.spp) * total);
        };
        std::vector<Tile> unfinished;
        if (rep.resumedFromStart) unfinished = tiles;
        else renderTiles(ctx, kernel, pixels, tiles, perSubmission, params, out, rep, passProgress, unfinished);
        if (!unfinished.empty()) {
            ShaderFeatures resumable = rep.features;
            resumable.resumable = true;
            ComputeKernel& again = kernels->kernel(accel.kernel, resumable);
            renderResumable(ctx, again, resumable, sceneBuffers, accelBuffers, pixels, unfinished, options.maxDepth,
                            params, out, rep, passProgress);
        }
        if (s > 0)
            for (size_t i = 0; i < frame.color.size(); ++i) frame.color[i] += pass.color[i];
    }
    if (options.spp > 1)
        for (glm::vec3& c : frame.color) c /= float(options.spp);
    rep.renderMs = msSince(start);
    rep.pipelinesCreated = uint32_t(kernels->size() - pipelinesBefore);
    ctx.checkValidation();
    throwIfCutShort(ctx, scene, accel.kernel, rep.pixelsCutShort);
    return frame;
}

}  // namespace vkray::gpu
