// The body of every render kernel (shaders/render_<accel>.comp): one invocation per pixel of one
// tile. Camera ray, closest hit, iterative Whitted shading over a small stack of pending rays (GLSL
// has no recursion), primary-hit AOVs. The kernel file also includes one accelerator, which
// defines traceClosest and traceAny (accelerator.glsl), before or after this file.
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
uvec2 pixelInTile() {
    const uint rows = gl_NumWorkGroups.y, half_ = (rows + 1) / 2, gy = gl_WorkGroupID.y;
    const uint blockRow = gy < half_ ? 2 * gy : 2 * (gy - half_) + 1;
    return uvec2(gl_GlobalInvocationID.x, blockRow * VKRAY_WORKGROUP_Y + gl_LocalInvocationID.y);
}

void main() {
    const uvec2 local = pixelInTile();
    const uvec2 imageSize = params.imageTile.xy;
    const uvec2 pixel = params.imageTile.zw + local;
    if (local.x >= VKRAY_TILE_SIZE || local.y >= VKRAY_TILE_SIZE ||
        any(greaterThanEqual(pixel, imageSize)))
        return;
    const uint outIndex = params.counts.z + local.y * params.counts.w + local.x;

    float depthAov = kInfinity;
    vec3 normalAov = vec3(0.0);
    int primAov = -1;
    vec3 radiance = vec3(0.0);

    // Depth-first: each ray pushes at most two children one level deeper and only below
    // MAX_DEPTH, so at most MAX_DEPTH rays are ever pending.
    PendingRay stack[MAX_DEPTH];
    stack[0] = PendingRay(params.eye.xyz, primaryDirection(pixel, imageSize), vec3(1.0), 1);
    int stackTop = 1;
    int rays = 0;
    for (; stackTop > 0 && rays < kMaxRaysPerPixel; ++rays) {
        --stackTop;
        const PendingRay ray = stack[stackTop];
        const Hit hit = traceClosest(ray.origin, ray.dir, kInfinity);
        if (hit.triangle < 0) continue;  // no background: a miss adds nothing
        const SurfacePoint s = surfaceAt(hit, ray.dir);
        if (rays == 0) {
            depthAov = hit.t;
            normalAov = s.normal;
            primAov = s.original;
        }
        const GpuMaterial m = loadMaterial(s.material);
        radiance += ray.weight * localShading(s, m, -ray.dir);
        if ((HAS_REFLECTION || HAS_REFRACTION) && ray.depth < MAX_DEPTH) {
            PendingRay reflected, refracted;
            secondaryRays(ray, s, m, reflected, refracted);
            if (worthTracing(refracted.weight)) stack[stackTop++] = refracted;
            if (worthTracing(reflected.weight)) stack[stackTop++] = reflected;
        }
    }

    const bool cutShort = gLoopCutShort || stackTop > 0;
    pixels[outIndex] = GpuPixel(radiance, depthAov, normalAov, primAov,
                                cutShort ? VKRAY_PIXEL_CUT_SHORT : 0u, uint(rays), gShadowRays,
                                gNodesVisited, gLeavesVisited, gTrianglesTested, gRestarts,
                                gCappedRays);
}

#endif
