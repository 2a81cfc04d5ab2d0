#include "cpu/reference_renderer.h"

#include <mutex>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/error.h"
#include "core/worker_arena.h"
#include "geometry/brute_force.h"
#include "cpu/shading.h"
#include "cpu/whitted.h"
#include "scene/camera.h"

namespace vkray {

namespace {

// What the shading code indexes without checking.
void checkRenderable(const Scene& scene, const RenderOptions& options) {
    if (!scene.hasCamera) throw Error("the scene has no camera");
    if (options.maxDepth < 1)
        throw Error("maxdepth " + std::to_string(options.maxDepth) + " is below 1");
    if (options.spp < 1) throw Error("spp " + std::to_string(options.spp) + " is below 1");
    if (const auto problem = windowProblem(options.pixels(), options.width, options.height)) throw Error(*problem);
    if (scene.hasSmoothNormals() && scene.normals.size() != scene.triangles.size())
        throw Error("the scene has " + std::to_string(scene.normals.size()) + " normal triples for " +
                    std::to_string(scene.triangles.size()) + " triangles");
    for (size_t k = 0; k < scene.triangles.size(); ++k)
        if (scene.triangles[k].material >= scene.materials.size())
            throw Error("triangle " + std::to_string(k) + " uses material " +
                        std::to_string(scene.triangles[k].material) + " of " +
                        std::to_string(scene.materials.size()));
}

}  // namespace

Frame renderReference(const Scene& scene, const RenderOptions& options, const RenderProgress& progress) {
    checkRenderable(scene, options);  // before building anything over a scene we cannot render
    const geometry::BruteForceTracer tracer(scene);
    return renderReference(scene, options, tracer, progress);
}

Frame renderReference(const Scene& scene, const RenderOptions& options, const geometry::Tracer& tracer,
                      const RenderProgress& progress) {
    checkRenderable(scene, options);
    const CameraFrame camera = makeCameraFrame(scene.camera, options.width, options.height);
    const cpu::WhittedIntegrator integrator(scene, tracer, options.maxDepth);

    Frame frame;
    frame.resize(options.pixels(), options.primaryAovs);
    std::mutex progressMutex;
    int rowsDone = 0;

    // Every pixel is computed alone from the same inputs, so the image does not depend on how rows
    // are spread over threads.
    auto renderRows = [&](const tbb::blocked_range<int>& rows) {
        for (int j = rows.begin(); j != rows.end(); ++j) {
            for (int i = 0; i < frame.width; ++i) {
                const int x = frame.x0 + i, y = frame.y0 + j;  // in the whole image
                const cpu::PixelSample px = integrator.sample({camera.eye, primaryDirection(camera, x, y)});
                glm::dvec3 radiance = px.radiance;
                for (int s = 1; s < options.spp; ++s)
                    radiance += integrator.sample({camera.eye, primaryDirection(camera, x, y, pixelSampleOffset(s))}).radiance;
                const size_t k = frame.index(i, j);
                frame.color[k] = glm::vec3(radiance / double(options.spp));
                if (options.primaryAovs && px.primary.found()) {
                    frame.depth[k] = float(px.primary.t);  // the camera direction is unit length
                    frame.primId[k] = px.primary.triangle;
                    frame.normal[k] = glm::vec3(px.normal);
                }
            }
            if (progress) {
                const std::lock_guard lock(progressMutex);
                progress(++rowsDone, frame.height);
            }
        }
    };
    tbb::task_arena arena(arenaThreads(options.threads));
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<int>(0, frame.height), renderRows); });
    return frame;
}

std::vector<std::string> tracePixel(const Scene& scene, const RenderOptions& options, int x, int y) {
    checkRenderable(scene, options);
    if (windowProblem(PixelWindow{x, y, x + 1, y + 1}, options.width, options.height))
        throw Error("pixel " + std::to_string(x) + "," + std::to_string(y) + " is outside the " +
                    std::to_string(options.width) + "x" + std::to_string(options.height) + " image");
    const geometry::BruteForceTracer tracer(scene);
    const CameraFrame camera = makeCameraFrame(scene.camera, options.width, options.height);
    std::vector<std::string> log;
    const cpu::WhittedIntegrator integrator(scene, tracer, options.maxDepth, &log);
    const cpu::PixelSample px = integrator.sample({camera.eye, primaryDirection(camera, x, y)});
    log.push_back("radiance " + cpu::logVector(px.radiance));
    return log;
}

}  // namespace vkray
