// The body of every render kernel (shaders/render_<accel>.comp): one invocation per pixel of one
// tile (several on a CPU device: "Pixels per invocation" below). Camera ray, closest hit,
// iterative Whitted shading over a small stack of pending rays (GLSL has no recursion), primary-hit
// AOVs; in the resumable variant, across several dispatches. The kernel file also includes one
// accelerator, which defines traceClosest and traceAny (accelerator.glsl), before or after this file.
#ifndef VKRAY_RENDER_MAIN_GLSL
#define VKRAY_RENDER_MAIN_GLSL

#include "accelerator.glsl"
#include "bindings.glsl"
#include "camera.glsl"
#include "constants.glsl"
#include "ray_offset.glsl"
#include "shading.glsl"
#include "trace_status.glsl"
#include "triangle.glsl"

layout(local_size_x = VKRAY_WORKGROUP_X, local_size_y = VKRAY_WORKGROUP_Y) in;

// A ray waiting to be traced, with the product of the weights along its path (docs/shading.md).
struct PendingRay {
    vec3 origin;
    vec3 dir;
    vec3 weight;
    int depth;  // primary rays have depth 1
};

// Resumable pixels. llvmpipe of Mesa 22.3 ends every loop of an invocation once its loops together
// ran 65535 iterations (trace_status.glsl): brute force over many triangles, or a BVH over heavily
// overlapping ones, needs more for one pixel. The resumable variant (RESUMABLE, specialised by the
// host only for tiles the plain kernel could not finish) keeps its pending rays in a buffer
// instead of registers, counts its loops' passes itself (budgetLeft(), trace_status.glsl) and,
// when its own budget is spent, before the driver's, saves where the pixel is: the rays still to
// trace, or the hit whose lights are being shaded and the next light, and the interrupted
// traversal's position and best hit: brute force's next triangle, the BVH walk's node and slot. The host dispatches the tile again until every pixel is done; a pixel
// that got nothing done in a whole dispatch is flagged cut short, as the plain kernel does.
layout(std430, set = 0, binding = VKRAY_BINDING_RESUME) buffer Resume {
    GpuPixelResume resume[];
};
layout(std430, set = 0, binding = VKRAY_BINDING_RESUME_RAYS) buffer ResumeRays {
    GpuPendingRay resumeRays[];
};

// Pixel records. The host reads every pixel's colour and flags, the ray counts summed, and the
// primary-hit AOVs and traversal counters only where it asked for them. The full record (GpuPixel)
// takes a 64-byte cache line a pixel. Where neither AOVs nor counters are read, and not in the
// resumable variant (which reads its records back), the kernel writes the compact one instead
// (GpuPixelColor, four pixels a line) and adds its ray counts to the tile's GpuTileCounts, summed
// over the subgroup first: a pixel's first store then does not pay for a cache line of its own
// on lavapipe (docs/performance.md, "Kept changes and what they measured"), and a discrete GPU
// copies back a quarter of the bytes.
const bool COMPACT_PIXELS = !RESUMABLE && !PRIMARY_AOVS && !COUNT_TRAVERSAL;
layout(std430, set = 0, binding = VKRAY_BINDING_PIXELS) buffer CompactPixels {
    GpuPixelColor compactPixels[];
};
layout(std430, set = 0, binding = VKRAY_BINDING_PIXELS) buffer TileCounts {
    GpuTileCounts tileCounts[];
};
uvec3 gInvocationCounts = uvec3(0u);  // compact records: rays, shadow rays, capped rays of the invocation

// The pending rays: in registers, or in the resumable variant in this pixel's part of resumeRays
// (saving them then needs no loop of its own). An entry read or written at a per-lane index is a
// loop over the SIMD lanes per word on llvmpipe, and a pending ray is ten words (docs/performance.md,
// "What lavapipe charges for"), so the register stack is only ever indexed by constants:
//  - without refraction a hit spawns one ray at most, so one ray is ever pending: entry 0;
//  - with refraction and MAX_DEPTH <= kSelectedSlots, entry i is reached through a compare with
//    each slot's constant index: a store is a masked write of each slot, a load a chain of selects,
//    which llvmpipe runs as vector blends. Written out slot by slot rather than as a loop: lavapipe
//    unrolls such a loop during pipeline creation, which the written-out lines spare it. A slot
//    beyond MAX_DEPTH is never taken; its index folds to 0 so that every access stays in the array;
//  - deeper stacks are indexed per lane.
PendingRay gStack[MAX_DEPTH];
uint gRayBase = 0u;  // first resumeRays entry of this pixel

const int kSelectedSlots = 8;  // the slots VKRAY_STORE_SLOT and VKRAY_LOAD_SLOT name below: 0-7
const bool kSelectSlots = HAS_REFRACTION && MAX_DEPTH <= kSelectedSlots;

#define VKRAY_STORE_SLOT(j) if (MAX_DEPTH > j && i == j) gStack[MAX_DEPTH > j ? j : 0] = r;
#define VKRAY_LOAD_SLOT(j) if (MAX_DEPTH > j && i == j) r = gStack[MAX_DEPTH > j ? j : 0];

void storeRay(int i, PendingRay r) {
    if (RESUMABLE) {
        resumeRays[gRayBase + uint(i)] = GpuPendingRay(r.origin, r.depth, r.dir, 0.0, r.weight, 0.0);
    } else if (!HAS_REFRACTION) {
        gStack[0] = r;
    } else if (kSelectSlots) {
        VKRAY_STORE_SLOT(0) VKRAY_STORE_SLOT(1) VKRAY_STORE_SLOT(2) VKRAY_STORE_SLOT(3)
        VKRAY_STORE_SLOT(4) VKRAY_STORE_SLOT(5) VKRAY_STORE_SLOT(6) VKRAY_STORE_SLOT(7)
    } else {
        gStack[i] = r;
    }
}

PendingRay loadRay(int i) {
    if (RESUMABLE) {
        const GpuPendingRay g = resumeRays[gRayBase + uint(i)];
        return PendingRay(g.origin, g.dir, g.weight, g.depth);
    }
    if (!HAS_REFRACTION) return gStack[0];
    if (!kSelectSlots) return gStack[i];
    PendingRay r = gStack[0];
    VKRAY_LOAD_SLOT(1) VKRAY_LOAD_SLOT(2) VKRAY_LOAD_SLOT(3)
    VKRAY_LOAD_SLOT(4) VKRAY_LOAD_SLOT(5) VKRAY_LOAD_SLOT(6) VKRAY_LOAD_SLOT(7)
    return r;
}
#undef VKRAY_STORE_SLOT
#undef VKRAY_LOAD_SLOT

// What a pixel carries from ray to ray, and across dispatches in the resumable variant.
struct PixelTrace {
    vec3 radiance;
    float depth;  // AOVs of the primary hit
    vec3 normal;
    int primId;
    int stackTop;
    int rays;     // closest-hit rays traced
    // The hit being shaded when the budget ran out (stage VKRAY_RESUME_LIGHTS): the ray is
    // stack[stackTop], its lights from `light` on are still to add to `color`.
    Hit hit;
    uint light;
    vec3 color;
};

// Below this weight in every channel a secondary ray is not traced (docs/shading.md).
const float kMinWeight = 1.0 / 1024.0;
// Hang guard (lavapipe has no watchdog): far above the rays the weight cutoff lets a pixel spawn.
const int kMaxRaysPerPixel = 1 << 16;

bool worthTracing(vec3 weight) { return max(weight.r, max(weight.g, weight.b)) >= kMinWeight; }

// Reflected and refracted children of a hit (docs/shading.md, "Secondary rays"); a child whose
// weight is below the cutoff comes back with weight 0.
void secondaryRays(PendingRay ray, SurfacePoint s, GpuMaterial m, out PendingRay reflected,
                   out PendingRay refracted) {
    vec3 reflectWeight = m.reflect.rgb;
    refracted = PendingRay(vec3(0.0), vec3(0.0), vec3(0.0), ray.depth + 1);
    if (HAS_REFRACTION && any(greaterThan(m.transmit.rgb, vec3(0.0)))) {
        const float eta = s.front ? 1.0 / m.ior : m.ior;
        const float cosi = clamp(dot(-ray.dir, s.normal), 0.0, 1.0);
        float cost;
        const float F = fresnelDielectric(cosi, eta, cost);
        reflectWeight += m.transmit.rgb * F;
        if (F < 1.0)
            refracted = PendingRay(offsetRayOrigin(s.position, -s.facing, s.offset),
                                   normalize(eta * ray.dir + (eta * cosi - cost) * s.normal),
                                   ray.weight * m.transmit.rgb * (1.0 - F), ray.depth + 1);
    }
    reflected = PendingRay(offsetRayOrigin(s.position, s.facing, s.offset), reflect(ray.dir, s.normal),
                           ray.weight * reflectWeight, ray.depth + 1);
}

// Lavapipe splits a dispatch into contiguous runs of workgroups, one per worker thread, so a tile
// whose top rows are empty and bottom rows full leaves one thread idle. Interleaving workgroup rows
// (the first half of the groups takes even rows of blocks, the second half odd rows) gives every
// run the same mix; on other GPUs it only renames rows.
// Within a group, llvmpipe runs invocations 8 at a time in SIMD lanes (256-bit vectors), in the
// order of gl_LocalInvocationIndex, and a vector walks the union of its lanes' paths. So each run
// of 8 invocations takes a 4x2 block of pixels rather than a row of 8: rays closer together, fewer
// nodes their union visits (Aila and Laine 2009's SIMD efficiency). A 32-wide subgroup still covers
// 8x4 pixels.
#if VKRAY_WORKGROUP_X != 8 || VKRAY_WORKGROUP_Y != 8
#error "pixelInTile assumes 8x8 workgroups"
#endif
// The plain kernel's invocation renders PIXELS_PER_INVOCATION pixels (k = 0, 1, ...; "Pixels per
// invocation" below), one in each of as many bands of the tile's block rows, at the same place in
// each, so the interleaving above holds within every band; the resumable variant's one is k = 0.
layout(constant_id = VKRAY_SPEC_PIXELS_PER_INVOCATION) const uint PIXELS_PER_INVOCATION = 1u;

uvec2 pixelInTile(uint k) {
    const uint rows = gl_NumWorkGroups.y, half_ = (rows + 1) / 2, gy = gl_WorkGroupID.y;
    const uint blockRow = k * rows + (gy < half_ ? 2 * gy : 2 * (gy - half_) + 1);
    const uint lane = gl_LocalInvocationID.x, run = gl_LocalInvocationID.y;
    return uvec2(gl_WorkGroupID.x * 8u + (run & 1u) * 4u + (lane & 3u),
                 blockRow * 8u + (run >> 1u) * 2u + (lane >> 2u));
}

bool inImage(uvec2 local) {
    return local.x < VKRAY_TILE_SIZE && local.y < VKRAY_TILE_SIZE &&
           all(lessThan(params.imageTile.zw + local, params.imageTile.xy));
}

uint outputIndex(uvec2 local) { return params.counts.z + local.y * params.counts.w + local.x; }

// Shades the hit pt.hit of `ray` from light pt.light on (pt.color holds the lights before it) and
// pushes the ray's children. False when the lights could not all be added (the budget ran out):
// pt keeps where it stopped.
bool shadeAndSpawn(inout PixelTrace pt, PendingRay ray, SurfacePoint s, GpuMaterial m) {
    if (!addLights(s, m, -ray.dir, pt.light, pt.color)) return false;
    pt.radiance += ray.weight * pt.color;
    if ((HAS_REFLECTION || HAS_REFRACTION) && ray.depth < MAX_DEPTH) {
        PendingRay reflected, refracted;
        secondaryRays(ray, s, m, reflected, refracted);
        if (worthTracing(refracted.weight)) storeRay(pt.stackTop++, refracted);
        if (worthTracing(reflected.weight)) storeRay(pt.stackTop++, reflected);
    }
    return true;
}

// Traces the top pending ray (counted in pt.rays once its closest hit is found) and shades its hit.
// False where the resumable variant has to stop: `stage` says where to go on (the ray is still
// pending, or its hit's lights are half added).
bool traceNextRay(inout PixelTrace pt, out uint stage) {
    stage = VKRAY_RESUME_RAYS;
    const PendingRay ray = loadRay(pt.stackTop - 1);
    const bool cameraRay = pt.rays == 0;
    const Hit hit = tracePixelRay(cameraRay, ray.origin, ray.dir, kInfinity);
    if (RESUMABLE && gLoopCutShort) return false;  // the ray stays pending
    gProgress = true;
    --pt.stackTop;
    ++pt.rays;
    if (hit.triangle < 0) {  // a miss sees the background
        pt.radiance += ray.weight * params.background;
        return true;
    }
    const SurfacePoint s = surfaceAt(hit, ray.dir);
    if (cameraRay) {
        pt.depth = hit.t;
        pt.normal = s.normal;
        pt.primId = s.original;
    }
    const GpuMaterial m = loadMaterial(s.material);
    pt.hit = hit;
    pt.light = 0u;
    pt.color = unlitShading(m);
    stage = VKRAY_RESUME_LIGHTS;
    return shadeAndSpawn(pt, ray, s, m);  // false in the resumable variant only
}

bool raysPending(PixelTrace pt) { return pt.stackTop > 0 && pt.rays < kMaxRaysPerPixel; }

// Traces the pending rays, depth-first: each ray pushes at most two children one level deeper and
// only below MAX_DEPTH, so at most MAX_DEPTH rays are ever pending. Returns VKRAY_RESUME_DONE when
// none is left, else the stage to go on at (the plain kernel flags the pixel instead).
uint traceRays(inout PixelTrace pt) {
    while (budgetLeft() && raysPending(pt)) {
        uint stage;
        if (!traceNextRay(pt, stage)) return stage;
    }
    return pt.stackTop > 0 ? VKRAY_RESUME_RAYS : VKRAY_RESUME_DONE;
}

// A pixel from its camera ray.
PixelTrace freshPixel(uvec2 pixel, uvec2 imageSize) {
    PixelTrace pt;
    pt.radiance = vec3(0.0);
    pt.depth = kInfinity;
    pt.normal = vec3(0.0);
    pt.primId = -1;
    pt.stackTop = 1;
    pt.rays = 0;
    pt.hit = noHit(kInfinity);
    pt.light = 0u;
    pt.color = vec3(0.0);
    storeRay(0, PendingRay(params.eye.xyz, primaryDirection(pixel, imageSize), vec3(1.0), 1));
    return pt;
}

// Resumable variant: the pixel where the last dispatch left it; returns its stage.
uint resumePixel(uint resumeIndex, uint outIndex, uvec2 pixel, uvec2 imageSize, out PixelTrace pt) {
    const GpuPixelResume r = resume[resumeIndex];
    if (r.stage == VKRAY_RESUME_FRESH) {
        pt = freshPixel(pixel, imageSize);
        return VKRAY_RESUME_RAYS;
    }
    const GpuPixel px = pixels[outIndex];
    pt = PixelTrace(px.color, px.depth, px.normal, px.primId, int(r.stackTop), int(r.rays),
                    Hit(r.hitTuv.x, r.hitTuv.yz, r.hitTriangle, r.hitOriginal), r.light, r.color);
    gShadowRays = px.shadowRays;
    gNodesVisited = px.nodes;
    gLeavesVisited = px.leaves;
    gTrianglesTested = px.triangles;
    gWalkEvents = px.walkEvents;
    gCappedRays = px.capped;
    gResumeSlot = r.walkSlot;
    gResumeBest = Hit(r.walkTuv.x, r.walkTuv.yz, r.walkTriangle, r.walkOriginal);
    gResumeSteps = r.walkSteps;
    return r.stage;
}

// The pixel's record (GpuPixel). Only what the host reads: the primary-hit AOVs when it saves them,
// the traversal counters in the statistics variant, everything in the resumable variant, which
// reads its pixels back. On llvmpipe every word stored at a per-lane address is a loop over the
// SIMD lanes, so every word left out saves a loop (docs/performance.md, "What lavapipe charges
// for").
void storePixel(uint i, PixelTrace pt, uint flags) {
    if (COMPACT_PIXELS) {
        compactPixels[i] = GpuPixelColor(pt.radiance, flags);
        gInvocationCounts += uvec3(uint(pt.rays), gShadowRays, gCappedRays);
        return;
    }
    pixels[i].color = pt.radiance;
    pixels[i].flags = flags;
    pixels[i].rays = uint(pt.rays);
    pixels[i].shadowRays = gShadowRays;
    pixels[i].capped = gCappedRays;
    if (PRIMARY_AOVS || RESUMABLE) {
        pixels[i].depth = pt.depth;
        pixels[i].normal = pt.normal;
        pixels[i].primId = pt.primId;
    }
    if (COUNT_TRAVERSAL || RESUMABLE) {
        pixels[i].nodes = gNodesVisited;
        pixels[i].leaves = gLeavesVisited;
        pixels[i].triangles = gTrianglesTested;
        pixels[i].walkEvents = gWalkEvents;
    }
}

// The resumable variant: one pixel, from where the last dispatch left it.
void renderResumable() {
    const uvec2 local = pixelInTile(0u);
    const uvec2 imageSize = params.imageTile.xy;
    const uvec2 pixel = params.imageTile.zw + local;
    if (!inImage(local)) return;
    const uint outIndex = outputIndex(local);
    const uint resumeIndex = local.y * VKRAY_TILE_SIZE + local.x;
    gRayBase = resumeIndex * uint(MAX_DEPTH);
    PixelTrace pt;
    uint stage = resumePixel(resumeIndex, outIndex, pixel, imageSize, pt);
    if (stage == VKRAY_RESUME_DONE) return;
    if (stage == VKRAY_RESUME_LIGHTS) {  // the interrupted hit first
        const PendingRay ray = loadRay(pt.stackTop);
        const SurfacePoint s = surfaceAt(pt.hit, ray.dir);
        if (shadeAndSpawn(pt, ray, s, loadMaterial(s.material))) stage = VKRAY_RESUME_RAYS;
    }
    if (stage == VKRAY_RESUME_RAYS) stage = traceRays(pt);

    // Unfinished: it goes on in the next dispatch unless its subgroup got nothing done in this one,
    // or the pixel reached its ray cap. Flagged cut short when the driver's budget ran out all the
    // same (the variant's own budget keeps it from doing so).
    const bool unfinished = stage != VKRAY_RESUME_DONE;
    const bool progressed = subgroupProgress();  // every pixel of the subgroup says
    const bool cutShort = loopBudgetRanOut() || (unfinished && (!progressed || pt.rays >= kMaxRaysPerPixel));
    storePixel(outIndex, pt, cutShort ? VKRAY_PIXEL_CUT_SHORT : unfinished ? VKRAY_PIXEL_UNFINISHED : 0u);
    resume[resumeIndex] = GpuPixelResume(pt.color, cutShort ? VKRAY_RESUME_DONE : stage,
                                         vec3(pt.hit.t, pt.hit.uv), pt.hit.triangle,
                                         vec3(gResumeBest.t, gResumeBest.uv), gResumeBest.triangle,
                                         uint(pt.stackTop), uint(pt.rays), pt.light, gResumeSlot,
                                         gResumeBest.original, pt.hit.original, gResumeSteps, 0u);
}

// Pixels per invocation (the plain kernel). A pixel's rays are a loop, and llvmpipe runs the 8
// lanes of a SIMD vector through it until the vector's last ray, and pays for every invocation.
// On a CPU device an invocation therefore renders PIXELS_PER_INVOCATION pixels (pixelInTile), in
// one loop that traces one ray a pass; a lane whose pixel is done waits
// until every lane of its subgroup is done, then all start their next pixel's camera ray together.
// (Letting each lane start its next pixel at once keeps the lanes busier, but puts camera rays and
// reflection rays of different pixels in one vector, whose walk then covers both, which large
// scenes pay for; docs/performance.md, "Tried and dropped".) On a GPU PIXELS_PER_INVOCATION is 1 and this is the plain loop over one pixel.
void flagIfInImage(uint k) {
    const uvec2 local = pixelInTile(k);
    if (!inImage(local)) return;
    if (COMPACT_PIXELS) compactPixels[outputIndex(local)].flags = VKRAY_PIXEL_CUT_SHORT;
    else pixels[outputIndex(local)].flags = VKRAY_PIXEL_CUT_SHORT;
}

bool lastPixel(uint k) { return k + 1u == PIXELS_PER_INVOCATION || !inImage(pixelInTile(k + 1u)); }

void renderPixels() {
    const uvec2 imageSize = params.imageTile.xy;
    uvec2 local = pixelInTile(0u);
    if (!inImage(local)) return;
    PixelTrace pt = freshPixel(params.imageTile.zw + local, imageSize);
    bool stored = false;
    for (uint k = 0u;;) {
        const bool done = !raysPending(pt);
        if (done && !stored) {  // a ray still pending hit the ray cap (kMaxRaysPerPixel)
            storePixel(outputIndex(local), pt, gLoopCutShort || pt.stackTop > 0 ? VKRAY_PIXEL_CUT_SHORT : 0u);
            stored = true;
        }
        if (done && lastPixel(k)) break;
        const bool subgroupDone = subgroupAll(done);
        if (done) {
            if (!subgroupDone) continue;
            local = pixelInTile(++k);
            resetPixelCounters();
            pt = freshPixel(params.imageTile.zw + local, imageSize);  // its camera ray is pending
            stored = false;
        }
        uint stage;
        traceNextRay(pt, stage);  // always true in the plain kernel
    }
    // Where llvmpipe's loop budget ran out, the loop above may have ended early, leaving pixels
    // unwritten or written from stale values (trace_status.glsl): all of them are flagged, in code
    // without a loop (after the budget every loop ends after one pass).
    if (loopBudgetRanOut()) {
        flagIfInImage(0u);
        if (PIXELS_PER_INVOCATION > 1u) flagIfInImage(1u);
        if (PIXELS_PER_INVOCATION > 2u) flagIfInImage(2u);
        if (PIXELS_PER_INVOCATION > 3u) flagIfInImage(3u);
    }
}

#if VKRAY_MAX_PIXELS_PER_INVOCATION > 4
#error "renderPixels flags at most four pixels of an invocation"
#endif

// Compact records: the subgroup's ray counts into its tile's 64-bit sums (an atomic on the low word a
// count and subgroup; the high word takes the carry, seen in the low word's old value). A macro: GLSL
// passes no buffer member by reference.
#define VKRAY_ADD_COUNT(count, value)                                                  \
    {                                                                                  \
        const uint old = atomicAdd(tileCounts[params.tileCounts].count##Low, value);   \
        if (old + (value) < old) atomicAdd(tileCounts[params.tileCounts].count##High, 1u); \
    }
void addTileCounts() {
    const uvec3 sums = subgroupAdd(gInvocationCounts);
    if (subgroupElect()) {
        VKRAY_ADD_COUNT(rays, sums.x)
        VKRAY_ADD_COUNT(shadowRays, sums.y)
        VKRAY_ADD_COUNT(capped, sums.z)
    }
}
#undef VKRAY_ADD_COUNT

void main() {
    startLoopBudget();
    if (RESUMABLE) {
        renderResumable();
    } else {
        renderPixels();
        if (COMPACT_PIXELS) addTileCounts();
    }
}

#endif
