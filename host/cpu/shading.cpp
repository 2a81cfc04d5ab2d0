#include "cpu/shading.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace vkray::cpu {

namespace {

glm::dvec3 d3(const glm::vec3& v) { return glm::dvec3(v); }

}  // namespace

SurfacePoint surfaceAt(const Scene& scene, const Hit& hit, const glm::dvec3& dir) {
    const Triangle& tri = scene.triangles[size_t(hit.triangle)];
    const glm::dvec3 p0 = d3(tri.p0), p1 = d3(tri.p1), p2 = d3(tri.p2);
    SurfacePoint s;
    // From the vertices rather than o + t d: its error is relative to the triangle, which is what
    // the origin offset is sized for (Waechter and Binder, Ray Tracing Gems, chapter 6).
    s.position = hit.b0 * p0 + hit.b1 * p1 + hit.b2 * p2;
    s.offsetScale = offsetScale(s.position, p1 - p0, p2 - p0);
    s.geometricNormal = glm::normalize(glm::cross(p1 - p0, p2 - p0));  // a hit is never degenerate
    s.front = glm::dot(dir, s.geometricNormal) < 0.0;
    s.facingNormal = s.front ? s.geometricNormal : -s.geometricNormal;
    s.normal = s.geometricNormal;
    if (scene.hasSmoothNormals()) {
        const TriangleNormals& n = scene.normals[size_t(hit.triangle)];
        const glm::dvec3 interpolated = hit.b0 * d3(n.n0) + hit.b1 * d3(n.n1) + hit.b2 * d3(n.n2);
        const double length = glm::length(interpolated);
        if (length > 0.0) s.normal = interpolated / length;
    }
    if (glm::dot(s.normal, s.facingNormal) < 0.0) s.normal = -s.normal;
    s.material = tri.material;
    return s;
}

glm::dvec3 offsetRayOrigin(const glm::dvec3& p, const glm::dvec3& n, double scale) {
    return p + n * (1e-9 * scale);
}

glm::dvec3 offsetRayOrigin(const glm::dvec3& p, const glm::dvec3& n) {
    const glm::dvec3 a = glm::abs(p);
    return offsetRayOrigin(p, n, std::max({1.0, a.x, a.y, a.z}));
}

double offsetScale(const glm::dvec3& p, const glm::dvec3& e1, const glm::dvec3& e2) {
    const glm::dvec3 a = glm::abs(p), e = glm::max(glm::abs(e1), glm::abs(e2));
    return std::max({a.x, a.y, a.z}) + std::max({e.x, e.y, e.z});
}

Interface dielectricInterface(double cosi, double eta) {
    Interface at;
    at.eta = eta;
    at.cosi = std::clamp(cosi, 0.0, 1.0);
    const double sin2t = eta * eta * (1.0 - at.cosi * at.cosi);
    if (sin2t >= 1.0) {
        at.cost = 0.0;
        at.reflectance = 1.0;
        at.totalInternalReflection = true;
        return at;
    }
    at.cost = std::sqrt(1.0 - sin2t);
    // Fresnel equations for s- and p-polarised light, divided through by the transmitted index.
    const double rs = (eta * at.cosi - at.cost) / (eta * at.cosi + at.cost);
    const double rp = (at.cosi - eta * at.cost) / (at.cosi + eta * at.cost);
    at.reflectance = (rs * rs + rp * rp) / 2.0;
    return at;
}

double fresnelDielectric(double cosi, double eta) { return dielectricInterface(cosi, eta).reflectance; }

glm::dvec3 reflectedDirection(const glm::dvec3& d, const glm::dvec3& n) {
    return d - 2.0 * glm::dot(d, n) * n;
}

glm::dvec3 refractedDirection(const glm::dvec3& d, const glm::dvec3& n, const Interface& at) {
    // Unit already when cosi = dot(-d, N); normalising absorbs rounding and the clamp of cosi.
    return glm::normalize(at.eta * d + (at.eta * at.cosi - at.cost) * n);
}

SecondaryRays secondaryRays(const SurfacePoint& s, const Material& m, const glm::dvec3& d) {
    SecondaryRays out;
    out.reflected.factor = d3(m.reflect);  // Wr = R for an opaque material
    if (m.refracts()) {
        // Air outside (index 1), `ior` inside; `front` says which side the ray comes from.
        const double ior = double(m.ior);
        const Interface at = dielectricInterface(glm::dot(-d, s.normal), s.front ? 1.0 / ior : ior);
        const glm::dvec3 T = d3(m.transmit);
        out.reflected.factor += T * at.reflectance;  // Wr = R + T F
        if (!at.totalInternalReflection) {
            out.refracted.factor = T * (1.0 - at.reflectance);  // Wt = T (1 - F)
            out.refracted.ray = Ray{offsetRayOrigin(s.position, -s.facingNormal, s.offsetScale),
                                    refractedDirection(d, s.normal, at)};
        }
    }
    out.reflected.ray = Ray{offsetRayOrigin(s.position, s.facingNormal, s.offsetScale), reflectedDirection(d, s.normal)};
    return out;
}

glm::dvec3 blinnPhong(const SurfacePoint& s, const Material& m, const glm::dvec3& V,
                      const glm::dvec3& L, const glm::dvec3& lightColor) {
    const double nDotL = glm::dot(s.normal, L);
    if (nDotL <= 0.0 || glm::dot(s.facingNormal, L) <= 0.0) return glm::dvec3(0.0);
    // L + V != 0 here: dot(Nf, L) > 0 >= dot(Nf, -V).
    const double nDotH = glm::dot(s.normal, glm::normalize(L + V));
    const double highlight = nDotH > 0.0 ? std::pow(nDotH, double(m.shininess)) : 0.0;
    return lightColor * ((1.0 - d3(m.transmit)) * d3(m.diffuse) * nDotL + d3(m.specular) * highlight);
}

double pointLightAttenuation(const glm::dvec3& clq, double r) {
    return 1.0 / (clq.x + clq.y * r + clq.z * r * r);
}

std::string logVector(const glm::dvec3& v) {
    char text[96];
    std::snprintf(text, sizeof text, "%.6g %.6g %.6g", v.x, v.y, v.z);
    return text;
}

glm::dvec3 localShading(const Scene& scene, const Tracer& tracer, const SurfacePoint& s,
                        const glm::dvec3& V, ShadingLog* log, int depth) {
    const Material& m = scene.materials[s.material];
    glm::dvec3 color = d3(m.emission) + (1.0 - d3(m.transmit)) * d3(m.ambient);
    const auto note = [&](const std::string& line) { log->push_back(std::string(size_t(2 * depth), ' ') + line); };
    if (log)
        note("emission " + logVector(d3(m.emission)) + ", ambient x (1 - T) " +
                       logVector((1.0 - d3(m.transmit)) * d3(m.ambient)));
    // Shadow rays leave from the side the ray came from; every triangle blocks (no caustics).
    const glm::dvec3 shadowOrigin = offsetRayOrigin(s.position, s.facingNormal, s.offsetScale);
    for (size_t k = 0; k < scene.lights.size(); ++k) {
        const Light& light = scene.lights[k];
        const glm::dvec3 C = d3(light.color);
        const bool point = light.type == Light::Type::Point;
        glm::dvec3 term(0.0), L(0.0);
        if (point) {
            const glm::dvec3 toLight = d3(light.vector) - s.position;
            const double r = glm::length(toLight);
            term = blinnPhong(s, m, V, toLight / r, C) * pointLightAttenuation(d3(scene.attenuation), r);
        } else {
            L = glm::normalize(d3(light.vector));
            term = blinnPhong(s, m, V, L, C);
        }
        const bool counts = term != glm::dvec3(0.0);  // no shadow ray where it cannot matter
        bool lit = false;
        if (counts && point) {
            // The shadow ray ends exactly at the light: direction and length from its own origin.
            const glm::dvec3 shadowPath = d3(light.vector) - shadowOrigin;
            const double shadowLength = glm::length(shadowPath);
            lit = !tracer.occluded(Ray{shadowOrigin, shadowPath / shadowLength}, shadowLength);
        } else if (counts) {
            lit = !tracer.occluded(Ray{shadowOrigin, L}, kInfinity);
        }
        if (lit) color += term;
        if (log)
            note("light " + std::to_string(k) + (point ? " (point)" : " (directional)") + ": " +
                           (!counts ? "behind the surface or no colour, no shadow ray"
                            : lit   ? "visible, adds " + logVector(term)
                                    : "blocked (shadow ray from " + logVector(shadowOrigin) + "), would add " +
                                        logVector(term)));
    }
    return color;
}

}  // namespace vkray::cpu
