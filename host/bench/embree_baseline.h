// The CPU yardstick of `vkray bench`: Embree 3 (Wald, Woop, Benthin, Johnson and Ernst, "Embree: A
// Kernel Framework for Efficient CPU Ray Tracing", SIGGRAPH 2014) tracing the same camera rays as the
// kernels' primary-only render, on all hardware threads, so every accelerator's primary-ray rate is
// also shown as a ratio to the best public CPU kernels on the same machine in the same run.
//
// Embree is optional at build time only (VKRAY_HAVE_EMBREE): a build without it reports the
// baseline as missing, with a note, rather than a made-up figure.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace vkray::bench {

// How the rays are handed to Embree.
enum class EmbreeQuery {
    Single,    // rtcIntersect1, one ray per call
    Packet16,  // rtcIntersect16, 4x4 pixel blocks
};

class EmbreeBaseline {
public:
    virtual ~EmbreeBaseline() = default;
    // Traces every camera ray of the image once (closest hit) with `threads` worker threads; returns
    // the wall-clock milliseconds.
    virtual double traceMs(EmbreeQuery query, int threads) = 0;
    // The triangle each camera ray hits (Scene::triangles index, -1 on a miss), top row first, from
    // the last traceMs call of that query.
    virtual const std::vector<int32_t>& hits() const = 0;
    // "Embree 3.13.5", for reports.
    virtual std::string version() const = 0;
};

// Whether this build has Embree; when not, makeEmbreeBaseline returns nullptr.
bool embreeAvailable();
// Why there is no baseline, for reports of a build without Embree.
const char* embreeMissingNote();

// Builds Embree's BVH over the scene (high quality, the triangles as given) for the camera rays of a
// width x height image of scene.camera (scene/camera.h, rounded to float). Throws vkray::Error when
// Embree reports an error.
std::unique_ptr<EmbreeBaseline> makeEmbreeBaseline(const Scene& scene, int width, int height);

// Embree's high-quality BVH over the scene's triangles (as given), built anew at each build() on
// `threads` workers from vertex and index arrays made once before: the build-time yardstick of
// vkray's builders (benchmarks/kd_build.cpp).
class EmbreeBuild {
public:
    virtual ~EmbreeBuild() = default;
    // One build, committed; throws vkray::Error when Embree reports an error.
    virtual void build() = 0;
    // Frees the last build's BVH (apart from build(), so that a timing of it leaves the free out).
    virtual void release() = 0;
};
// Null in a build without Embree (embreeAvailable()).
std::unique_ptr<EmbreeBuild> makeEmbreeBuild(const Scene& scene, int threads);

}  // namespace vkray::bench
