// What the stress tests (numerical stability, docs/stability.md) measure for one rendering against another:
// primary-hit agreement (primid AOV), image error, and the direction of the error (acne: the GPU
// darker than the reference, as when a shadow ray hits its own surface; leaks: brighter, as when a
// shadow ray starts beyond a thin occluder), plus the watertightness checks of closed meshes.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <glm/glm.hpp>

#include "../gpu/gpu_test_util.h"
#include "core/error.h"
#include "frame/frame.h"
#include "geometry/ray.h"
#include "geometry/ray_triangle.h"
#include "image/compare.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "scene/scene_builder.h"

namespace vkray::stress {

// A pixel counts as different when a channel of the 8-bit images differs by more than this
// (the bound of tests/gpu: float rounding moves some pixels by a few levels, never by 8).
inline constexpr double kBadLevel = 8.0 / 255.0;

struct Disagreement {
    size_t pixels = 0;
    size_t primIdMismatches = 0;  // pixels whose primary hit names another triangle (or hit vs miss)
    // Of those, explained by rounding (classifyMismatch): the exact ray hits both triangles at the
    // same distance (a tie: a shared edge, coplanar triangles), or it passes within rounding of the
    // edge of the triangle one of the renderers reports (a graze: either answer is right).
    size_t ties = 0, grazes = 0;
    size_t unexplained() const { return primIdMismatches - ties - grazes; }
    double rmse = 0.0, maxError = 0.0;  // of the quantised colour, in [0, 1] units
    int64_t badPixels = 0;              // some channel off by more than kBadLevel
    size_t darker = 0, brighter = 0;    // bad pixels darker / brighter (luminance) than the reference

    double mismatchFraction() const { return pixels ? double(primIdMismatches) / double(pixels) : 0.0; }
};

inline double luminance(const glm::vec3& c) {
    const glm::vec3 q = glm::clamp(c, glm::vec3(0.0f), glm::vec3(1.0f));
    return 0.2126 * q.r + 0.7152 * q.g + 0.0722 * q.b;
}

enum class Mismatch { Tie, Graze, Unexplained };

// Relative size of "within rounding" below: float rounding moves a hit about 1e-7 of the distances
// involved; 1e-5 leaves a margin and is still far below a pixel's footprint in these scenes.
inline constexpr double kRoundingReach = 1e-5;

// Why the primary hit of camera ray `ray` is triangle `got` in one renderer and `want` (at distance
// `wantDepth`) in the reference; -1 is a miss. Decided with the exact (double, watertight) test on
// triangles grown or shrunk about their centroid by kRoundingReach.
inline Mismatch classifyMismatch(const Scene& scene, const geometry::Ray& ray, int32_t got, int32_t want, double wantDepth) {
    const auto scaled = [&](int32_t id, double factor) {
        const Triangle& t = scene.triangles[size_t(id)];
        const glm::dvec3 c = (glm::dvec3(t.p0) + glm::dvec3(t.p1) + glm::dvec3(t.p2)) / 3.0;
        const auto move = [&](const glm::vec3& p) { return c + (glm::dvec3(p) - c) * factor; };
        return geometry::TriangleVertices{move(t.p0), move(t.p1), move(t.p2)};
    };
    const double inf = std::numeric_limits<double>::infinity();
    if (got >= 0 && want >= 0) {
        const auto hit = geometry::intersectTriangle(ray, scaled(got, 1.0 + kRoundingReach), 0.0, inf);
        if (hit && std::abs(hit->t - wantDepth) <= kRoundingReach * wantDepth) return Mismatch::Tie;
    }
    // A graze: the reference's triangle hit only just inside its edge (it misses when shrunk), or
    // the other renderer's triangle missed by the exact ray but hit when grown.
    if (want >= 0 && !geometry::intersectTriangle(ray, scaled(want, 1.0 - kRoundingReach), 0.0, inf))
        return Mismatch::Graze;
    if (got >= 0 && !geometry::intersectTriangle(ray, scaled(got, 1.0), 0.0, inf) &&
        geometry::intersectTriangle(ray, scaled(got, 1.0 + kRoundingReach), 0.0, inf))
        return Mismatch::Graze;
    return Mismatch::Unexplained;
}

// `a` measured against the reference `ref` (same size). With `scene` (the one both rendered), the
// primid mismatches are classified; without, none counts as explained.
inline Disagreement disagreement(const Frame& a, const Frame& ref, const Scene* scene = nullptr) {
    Disagreement d;
    d.pixels = ref.primId.size();
    const CameraFrame cam = scene ? makeCameraFrame(scene->camera, ref.width, ref.height) : CameraFrame{};
    for (int j = 0; j < ref.height; ++j)
        for (int i = 0; i < ref.width; ++i) {
            const size_t k = ref.index(i, j);
            if (a.primId[k] == ref.primId[k]) continue;
            ++d.primIdMismatches;
            if (!scene) continue;
            const geometry::Ray ray{cam.eye, primaryDirection(cam, i, j)};
            switch (classifyMismatch(*scene, ray, a.primId[k], ref.primId[k], double(ref.depth[k]))) {
                case Mismatch::Tie: ++d.ties; break;
                case Mismatch::Graze: ++d.grazes; break;
                case Mismatch::Unexplained: break;
            }
        }
    const Image qa = test::quantisedColor(a), qr = test::quantisedColor(ref);
    const CompareStats s = compareImages(qa, qr, kBadLevel);
    d.rmse = s.rmse;
    d.maxError = s.maxError;
    d.badPixels = s.badPixels;
    for (size_t k = 0; k < d.pixels; ++k) {
        double worst = 0.0;
        for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::abs(qa.data[3 * k + c] - qr.data[3 * k + c])));
        if (worst <= kBadLevel + kThresholdSlack) continue;
        (luminance(a.color[k]) < luminance(ref.color[k]) ? d.darker : d.brighter) += 1;
    }
    return d;
}

// Closed meshes: a ray that should hit but passes through a seam. Where every pixel must hit (the
// mesh fills the view, or the camera is inside it), a miss is a leak. Seen from outside a convex
// mesh around `centre`, the first hit must lie on a triangle whose plane separates the eye from the
// centre; a first hit on a far-side triangle went through the near side. Decided in double.
struct LeakCount {
    size_t misses = 0, farSide = 0;
    size_t total() const { return misses + farSide; }
};

inline LeakCount countLeaks(const Scene& scene, const Frame& f, bool everyPixelHits, const glm::dvec3* convexCentre) {
    LeakCount n;
    const glm::dvec3 eye(scene.camera.eye);
    for (int32_t id : f.primId) {
        if (id < 0) {
            n.misses += everyPixelHits ? 1 : 0;
            continue;
        }
        if (!convexCentre) continue;
        const Triangle& t = scene.triangles[size_t(id)];
        const glm::dvec3 p0(t.p0), normal = glm::cross(glm::dvec3(t.p1) - p0, glm::dvec3(t.p2) - p0);
        const double sideEye = glm::dot(normal, eye - p0), sideCentre = glm::dot(normal, *convexCentre - p0);
        if (!(sideEye * sideCentre < 0.0)) ++n.farSide;
    }
    return n;
}

// The whole scene mapped by p -> scale * p + offset (geometry, camera, point lights) in double, then
// stored as the loader stores a scene (SceneBuilder): relative to its local origin, each position
// rounded to float once, as the parser stores `scale`/`translate` applied to the file's vertices.
// Directions (directional lights, up) and attenuation stay: with the default attenuation (1 0 0)
// the image is the same in exact arithmetic. Normals are copied (a flat triangle's stays the
// geometric normal of the unmapped floats).
inline Scene mappedScene(const Scene& base, double scale, double offset) {
    Scene s = base;
    s.triangles.clear();
    s.normals.clear();
    s.lights.clear();
    const auto map = [&](const glm::vec3& p) { return glm::dvec3(p) * scale + glm::dvec3(offset); };
    SceneBuilder out(s);
    for (size_t i = 0; i < base.triangles.size(); ++i) {
        const Triangle& t = base.triangles[i];
        const TriPoints p{map(t.p0), map(t.p1), map(t.p2)};
        bool ok = false;
        if (base.hasSmoothNormals()) {
            const TriangleNormals& n = base.normals[i];
            ok = out.addSmooth(p, {glm::dvec3(n.n0), glm::dvec3(n.n1), glm::dvec3(n.n2)}, t.material);
        } else {
            ok = out.addFlat(p, t.material);
        }
        if (!ok) throw Error("mappedScene: a mapped vertex does not fit a float");
    }
    out.setCamera(base.camera, map(base.camera.eye), map(base.camera.center));
    for (const Light& l : base.lights)
        out.addLight(l, l.type == Light::Type::Point ? map(l.vector) : glm::dvec3(l.vector));
    out.finish();
    return s;
}

}  // namespace vkray::stress
