// Whitted shading with Blinn-Phong local terms, term for term as docs/shading.md states it (the CPU
// reference renderer, host/cpu/, follows the same page in double precision).
#ifndef VKRAY_SHADING_GLSL
#define VKRAY_SHADING_GLSL

#include "ray_offset.glsl"

#define kInfinity uintBitsToFloat(0x7F800000u)

struct SurfacePoint {
    vec3 position;  // from barycentrics: more accurate than origin + t * dir far from the origin
    vec3 facing;    // Nf: geometric normal on the side the ray came from
    vec3 normal;    // N: shading normal, dot(N, Nf) >= 0
    bool front;     // the ray hit the side the geometric normal points to
    uint material;
    int original;   // triangle identity (DESIGN.md) for the primid AOV
};

SurfacePoint surfaceAt(Hit hit, vec3 dir) {
    const GpuTriangle tri = triangles[hit.triangle];
    const vec3 p0 = tri.p0Material.xyz, p1 = tri.p1Original.xyz, p2 = tri.p2.xyz;
    const float b0 = 1.0 - hit.uv.x - hit.uv.y;
    SurfacePoint s;
    s.position = b0 * p0 + hit.uv.x * p1 + hit.uv.y * p2;
    const vec3 ng = normalize(cross(p1 - p0, p2 - p0));
    s.front = dot(dir, ng) < 0.0;
    s.facing = s.front ? ng : -ng;
    s.normal = ng;
    if (HAS_SMOOTH_NORMALS) {
        const GpuTriangleNormals tn = triangleNormals[hit.triangle];
        const vec3 interpolated = b0 * tn.n0.xyz + hit.uv.x * tn.n1.xyz + hit.uv.y * tn.n2.xyz;
        const float len = length(interpolated);
        if (len > 0.0) s.normal = interpolated / len;
    }
    if (dot(s.normal, s.facing) < 0.0) s.normal = -s.normal;
    s.material = floatBitsToUint(tri.p0Material.w);
    s.original = floatBitsToInt(tri.p1Original.w);
    return s;
}

// One light's Blinn-Phong term, before visibility; zero when the light is behind N or behind the
// surface side the ray came from.
vec3 blinnPhong(SurfacePoint s, GpuMaterial m, vec3 V, vec3 transmit, vec3 L, vec3 lightColor) {
    const float nDotL = dot(s.normal, L);
    if (nDotL <= 0.0 || dot(s.facing, L) <= 0.0) return vec3(0.0);
    const float nDotH = dot(s.normal, normalize(L + V));
    const float spec = nDotH > 0.0 ? pow(nDotH, m.ambientShininess.w) : 0.0;
    return lightColor * ((1.0 - transmit) * m.diffuseIor.rgb * nDotL + m.specular.rgb * spec);
}

// Emission, ambient and every light with its shadow ray (docs/shading.md, "Local shading").
vec3 localShading(SurfacePoint s, GpuMaterial m, vec3 V) {
    const vec3 transmit = m.transmit.rgb;
    vec3 color = m.emission.rgb + (1.0 - transmit) * m.ambientShininess.rgb;
    const vec3 shadowOrigin = offsetRayOrigin(s.position, s.facing);
    const uint lightCount = params.counts.y;
    for (uint i = 0; i < lightCount; ++i) {
        const GpuLight light = lights[i];
        const bool isPoint = light.vectorType.w < 0.5;
        if (HAS_POINT_LIGHTS && isPoint) {
            const vec3 toLight = light.vectorType.xyz - s.position;
            const float r = length(toLight);
            const vec3 att = params.attenuation.xyz;
            const vec3 term = blinnPhong(s, m, V, transmit, toLight / r, light.color.rgb) /
                              (att.x + att.y * r + att.z * r * r);
            if (term == vec3(0.0)) continue;
            const vec3 shadowDir = light.vectorType.xyz - shadowOrigin;
            const float shadowLength = length(shadowDir);
            if (!traceAny(shadowOrigin, shadowDir / shadowLength, shadowLength)) color += term;
        }
        if (HAS_DIRECTIONAL_LIGHTS && !isPoint) {
            const vec3 L = normalize(light.vectorType.xyz);
            const vec3 term = blinnPhong(s, m, V, transmit, L, light.color.rgb);
            if (term == vec3(0.0)) continue;
            if (!traceAny(shadowOrigin, L, kInfinity)) color += term;
        }
    }
    return color;
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
