#include "accel/bvh/primitives.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "accel/bvh/sphere_bounds.h"
#include "core/parallel_alloc.h"

namespace vkray::bvh {
namespace {

struct BoundsPair {
    Aabb boxes, centroids;
};

}  // namespace

PrimitiveSet primitivesOf(std::span<const Triangle> triangles, bool spheres) {
    PrimitiveSet set;
    resizeForOverwrite(set.boxes, triangles.size());
    resizeForOverwrite(set.centroids, triangles.size());
    if (spheres) resizeFirstTouched(set.spheres, triangles.size());
    using Range = tbb::blocked_range<size_t>;
    const BoundsPair all = tbb::parallel_reduce(
        Range(0, triangles.size(), 4096), BoundsPair{},
        [&](const Range& r, BoundsPair acc) {
            for (size_t i = r.begin(); i < r.end(); ++i) {
                const Triangle& t = triangles[i];
                Aabb box;
                box.grow(t.p0);
                box.grow(t.p1);
                box.grow(t.p2);
                set.boxes[i] = box;
                set.centroids[i] = (t.p0 + t.p1 + t.p2) / 3.0f;
                if (spheres) set.spheres[i] = triangleSphere(t);
                acc.boxes.grow(box);
                acc.centroids.grow(set.centroids[i]);
            }
            return acc;
        },
        [](BoundsPair a, const BoundsPair& b) {
            a.boxes.grow(b.boxes);
            a.centroids.grow(b.centroids);
            return a;
        });
    set.bounds = all.boxes;
    set.centroidBounds = all.centroids;
    return set;
}

}  // namespace vkray::bvh
