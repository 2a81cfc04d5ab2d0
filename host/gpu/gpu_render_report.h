// What a GPU render reports besides its Frame, and the progress it reports while running.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "gpu/shader_features.h"

namespace vkray::gpu {

struct GpuRenderReport {
    std::string kernel;          // shaders/render_<kernel>.comp (gpu::kernelName)
    ShaderFeatures features;
    uint32_t tiles = 0;          // dispatches of at most VKRAY_TILE_SIZE^2 pixels
    uint32_t submissions = 0;    // batches of tiles submitted together
    uint64_t bytesUploaded = 0;
    double uploadMs = 0.0;       // scene buffers, host clock
    double pipelineMs = 0.0;     // kernel specialisation and pipeline creation, host clock
    // Pipelines this render created in its KernelCache; 0 when every one it used was there already
    // (an earlier scene's: a render session keeps one cache for all its scenes).
    uint32_t pipelinesCreated = 0;
    double gpuMs = -1.0;         // sum of the batches' timestamp intervals; -1 without timestamps
    double renderMs = 0.0;       // dispatch to read-back done, host clock
    uint64_t accelBytes = 0;     // of bytesUploaded, the acceleration structure's (rayquery: the driver's)
    // rayquery: the driver's build of its structure on the device (GPU timestamps; part of
    // uploadMs); -1 without timestamps; absent for every other accelerator.
    std::optional<double> driverBuildMs;
    uint64_t raysTraced = 0;     // camera and secondary rays (closest hit)
    uint64_t shadowRays = 0;     // any-hit rays
    uint64_t cappedRays = 0;     // rays a traversal ended at its iteration cap (reported, not hidden)
    uint64_t pixelsCutShort = 0; // pixels whose loops the driver cut short (then renderOnGpu throws)
    // Tiles the plain kernel could not finish within the driver's loop budget, rendered again by the
    // resumable variant in strips of resumeRows rows, and that variant's dispatches.
    uint32_t resumedTiles = 0, resumeRows = 0, resumeDispatches = 0;
    bool resumedFromStart = false;  // every tile resumable at once (brute force beyond one budget)
    // Traversal work over all rays; filled only with RenderOptions::countTraversal.
    uint64_t nodesVisited = 0, leavesVisited = 0, trianglesTested = 0, restarts = 0;
    // The kernel walks camera rays as packets (accel::isPacketWalk): idleSteps are the steps lanes
    // took with their packet but sat out, their ray not entering the node; then the lock-step steps
    // below are nodesVisited + idleSteps, the steps the lanes' walks took, a packet's counted for
    // each of its lanes, and nodesVisited over them the lanes' use of their packets. Secondary and
    // shadow rays, and the resumable variant, walk one ray a lane and count no idle steps.
    // cameraRays: the closest-hit rays that were camera rays, one a pixel.
    bool packetWalk = false;
    uint64_t idleSteps = 0, cameraRays = 0;
    // The node steps the device's subgroups run in lock-step (lockstep.h): nodesVisited over this is
    // the SIMD efficiency. A lower bound where a pixel traces several rays (its lanes need not be
    // at the same ray); for a packet walk, its packets' steps (above). Filled only with
    // RenderOptions::countTraversal.
    uint64_t lockstepNodes = 0;
    uint32_t lockstepLanes = 0;  // the subgroup size it assumes
    // Nodes visited by all rays of each pixel, top row first (a traversal-cost heatmap); filled
    // only with RenderOptions::countTraversal.
    std::vector<uint32_t> nodesPerPixel;
};

using TileProgress = std::function<void(uint32_t tilesDone, uint32_t tilesTotal)>;

}  // namespace vkray::gpu
