// Whitted shading with Blinn-Phong local terms, term for term as docs/shading.md states it (the CPU
// reference renderer, host/cpu/, follows the same page in double precision).
#ifndef VKRAY_SHADING_GLSL
#define VKRAY_SHADING_GLSL

#include "accelerator.glsl"
#include "bindings.glsl"
#include "constants.glsl"
#include "ray_offset.glsl"
#include "trace_status.glsl"
#include "triangle.glsl"

struct SurfacePoint {
    vec3 position;  // from barycentrics: more accurate than origin + t * dir far from the origin
    vec3 facing;    // Nf: geometric normal on the side the ray came from
    vec3 normal;    // N: shading normal, dot(N, Nf) >= 0
    bool front;     // the ray hit the side the geometric normal points to
    uint material;
    int original;   // triangle identity (docs/scene-format.md) for the primid AOV
    float offset;   // how far secondary rays start off the surface (ray_offset.glsl)
};

SurfacePoint surfaceAt(Hit hit, vec3 dir) {
    const GpuTriangle tri = loadTriangle(uint(hit.triangle));
    const vec3 p0 = tri.p0, p1 = tri.p1, p2 = tri.p2;
    const float b0 = 1.0 - hit.uv.x - hit.uv.y;
    SurfacePoint s;
    // P = b0 p0 + b1 p1 + b2 p2 written from p0 along the edges: rounding b1 and b2 then moves P
    // within the plane only, which keeps the origin offset small (ray_offset.glsl).
    const vec3 e1 = p1 - p0, e2 = p2 - p0;
    s.position = p0 + hit.uv.x * e1 + hit.uv.y * e2;
    s.offset = offsetDistance(s.position, e1, e2);
    const vec3 ng = normalize(cross(e1, e2));
    s.front = dot(dir, ng) < 0.0;
    s.facing = s.front ? ng : -ng;
    s.normal = ng;
    if (HAS_SMOOTH_NORMALS) {
        const GpuTriangleNormals tn = loadNormals(uint(hit.triangle));
        const vec3 interpolated = b0 * tn.n0.xyz + hit.uv.x * tn.n1.xyz + hit.uv.y * tn.n2.xyz;
        const float len = length(interpolated);
        if (len > 0.0) s.normal = interpolated / len;
    }
    if (dot(s.normal, s.facing) < 0.0) s.normal = -s.normal;
    s.material = tri.material;
    s.original = int(tri.original);
    return s;
}

// One light's Blinn-Phong term, before visibility; zero when the light is behind N or behind the
// surface side the ray came from.
vec3 blinnPhong(SurfacePoint s, GpuMaterial m, vec3 V, vec3 transmit, vec3 L, vec3 lightColor) {
    const float nDotL = dot(s.normal, L);
    if (nDotL <= 0.0 || dot(s.facing, L) <= 0.0) return vec3(0.0);
    const float nDotH = dot(s.normal, normalize(L + V));
    const float spec = nDotH > 0.0 ? pow(nDotH, m.shininess) : 0.0;
    return lightColor * ((1.0 - transmit) * m.diffuse * nDotL + m.specular.rgb * spec);
}

// Direction towards a light, its colour with attenuation, and the shadow ray that tests it.
struct LightSample {
    vec3 L;            // unit vector from the shaded point towards the light
    vec3 radiance;     // light colour, attenuated for point lights
    vec3 shadowDir;    // from the offset shadow-ray origin
    float shadowTmax;  // the light's distance from that origin; +inf for directional lights
};

LightSample sampleLight(GpuLight light, vec3 position, vec3 shadowOrigin) {
    LightSample ls;
    if (HAS_DIRECTIONAL_LIGHTS && (!HAS_POINT_LIGHTS || light.type == VKRAY_LIGHT_DIRECTIONAL)) {
        ls.L = normalize(light.vector);
        ls.radiance = light.color.rgb;
        ls.shadowDir = ls.L;
        ls.shadowTmax = kInfinity;
    } else {
        const vec3 toLight = light.vector - position;
        const float r = length(toLight);
        const vec3 att = params.attenuation.xyz;
        ls.L = toLight / r;
        ls.radiance = light.color.rgb / (att.x + att.y * r + att.z * r * r);
        const vec3 toLightFromOrigin = light.vector - shadowOrigin;
        ls.shadowTmax = length(toLightFromOrigin);
        ls.shadowDir = toLightFromOrigin / ls.shadowTmax;
    }
    return ls;
}

// Any-hit query of the accelerator's traceAny(), counted per pixel once it is done (a query cut
// short is traced again by the resumable variant, and counted then).
bool traceShadowRay(vec3 origin, vec3 dir, float tmax) {
    const bool blocked = traceAny(origin, dir, tmax);
    if (!gLoopCutShort) ++gShadowRays;
    return blocked;
}

// Emitted light and ambient: the local shading before any light (docs/shading.md, "Local shading").
vec3 unlitShading(GpuMaterial m) { return m.emission.rgb + (1.0 - m.transmit.rgb) * m.ambient; }

// Adds lights [light, lightCount) with their shadow rays to `color` (docs/shading.md, "Local
// shading"). In the resumable variant, returns false when the loop stopped early (its budget ran
// out, or a shadow ray was cut short); `light` is then the light to go on with (the lights before
// it are in `color`). The plain kernel always returns true: there a loop ended by the driver is
// caught by loopBudgetRanOut() (trace_status.glsl).
bool addLights(SurfacePoint s, GpuMaterial m, vec3 V, inout uint light, inout vec3 color) {
    if (!HAS_POINT_LIGHTS && !HAS_DIRECTIONAL_LIGHTS) return true;
    const vec3 shadowOrigin = offsetRayOrigin(s.position, s.facing, s.offset);
    const uint lightCount = params.counts.y;
    // Counted apart from `light` in the resumable variant, as testSlotsFrom() counts
    // (leaf_triangles.glsl): a test of the loop's own condition after it would be folded to true.
    const uint needed = light < lightCount ? lightCount - light : 0u;
    uint iterations = 0u;
    for (; budgetLeft() && light < lightCount; ++light) {
        const LightSample ls = sampleLight(loadLight(light), s.position, shadowOrigin);
        const vec3 term = blinnPhong(s, m, V, m.transmit.rgb, ls.L, ls.radiance);
        // Shadow rays only where the light would add something.
        if (any(greaterThan(term, vec3(0.0)))) {
            const bool blocked = traceShadowRay(shadowOrigin, ls.shadowDir, ls.shadowTmax);
            if (RESUMABLE && gLoopCutShort) return false;
            if (!blocked) color += term;
        }
        gProgress = true;
        if (RESUMABLE) ++iterations;
    }
    return !RESUMABLE || iterations >= needed;
}

// Unpolarised Fresnel reflectance of a dielectric; eta = n_incident / n_transmitted.
// Returns 1 on total internal reflection; cost receives the cosine of the refracted angle.
float fresnelDielectric(float cosi, float eta, out float cost) {
    const float sin2t = eta * eta * (1.0 - cosi * cosi);
    if (sin2t >= 1.0) {
        cost = 0.0;
        return 1.0;
    }
    cost = sqrt(1.0 - sin2t);
    const float rs = (eta * cosi - cost) / (eta * cosi + cost);
    const float rp = (cosi - eta * cost) / (cosi + eta * cost);
    return 0.5 * (rs * rs + rp * rp);
}

#endif
