// The pieces of the shading model of docs/shading.md, in double precision, one function per rule so
// each can be tested alone. Section names in the comments refer to that page. The model is Whitted's
// recursive ray tracer (T. Whitted, "An Improved Illumination Model for Shaded Display", CACM 23(6),
// 1980) with Blinn-Phong local shading (J. F. Blinn, "Models of Light Reflection for Computer
// Synthesized Pictures", SIGGRAPH 1977).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/ray.h"
#include "geometry/tracer.h"
#include "scene/scene.h"

namespace vkray::cpu {

// The far end of a ray that may go anywhere.
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The geometry the CPU renderer traces with (geometry/): named here as the renderer reads them.
using geometry::Hit;
using geometry::Ray;
using geometry::Tracer;

// "Notation": the hit point and its normals.
struct SurfacePoint {
    glm::dvec3 position;  // P = b0 p0 + b1 p1 + b2 p2 (from the vertices, not o + t d)
    glm::dvec3 geometricNormal;  // Ng = normalize(cross(p1 - p0, p2 - p0))
    glm::dvec3 facingNormal;     // Nf: Ng turned towards the side the ray came from
    glm::dvec3 normal;           // N: shading normal, dot(N, Nf) >= 0
    bool front = false;          // dot(d, Ng) < 0
    uint32_t material = 0;
    // What the rounding of `position` scales with (offsetScale() below); 1 for points made by hand.
    double offsetScale = 1.0;
};

// The surface at a hit of a ray with direction `dir`. Smooth triangles interpolate their vertex
// normals; an interpolation of zero length (opposed vertex normals) falls back to Ng.
SurfacePoint surfaceAt(const Scene& scene, const Hit& hit, const glm::dvec3& dir);

// "Ray origins", CPU rule: P + n * 1e-9 * scale. Pass n = Nf for reflection and shadow rays, n = -Nf
// for refraction. scale = offsetScale(): the magnitudes the rounding of P and of the triangle test
// scale with (Pharr, Jakob and Humphreys, PBR 3rd ed., 3.9); 1e-9 of it is far above double rounding
// and far below any feature a float scene can hold, at any scale (the GPU's float rule, with its
// reasons: shaders/include/ray_offset.glsl).
glm::dvec3 offsetRayOrigin(const glm::dvec3& p, const glm::dvec3& n, double scale);
// The same with scale = max(1, max|P_i|), for a point whose triangle is not known.
glm::dvec3 offsetRayOrigin(const glm::dvec3& p, const glm::dvec3& n);
// max|P_i| + max|e_i| over the coordinates of P and of the edge vectors e1 = p1 - p0, e2 = p2 - p0.
double offsetScale(const glm::dvec3& p, const glm::dvec3& e1, const glm::dvec3& e2);

// "Secondary rays": what light does at the interface between air and a dielectric.
struct Interface {
    double eta = 1.0;   // n_incident / n_transmitted
    double cosi = 1.0;  // cosine of the incident angle, clamped to [0, 1]
    double cost = 1.0;  // cosine of the refracted angle (0 on total internal reflection)
    double reflectance = 0.0;  // unpolarised Fresnel reflectance F; 1 on total internal reflection
    bool totalInternalReflection = false;
};
Interface dielectricInterface(double cosi, double eta);

// The unpolarised Fresnel reflectance alone: F = (rs^2 + rp^2) / 2, or 1 beyond the critical angle.
double fresnelDielectric(double cosi, double eta);

// d - 2 dot(d, N) N.
glm::dvec3 reflectedDirection(const glm::dvec3& d, const glm::dvec3& n);
// normalize(eta d + (eta cosi - cost) N); only meaningful without total internal reflection.
glm::dvec3 refractedDirection(const glm::dvec3& d, const glm::dvec3& n, const Interface& at);

// A child ray with its factor (Wr or Wt) before multiplication by the parent's weight.
struct SecondaryRay {
    Ray ray;
    glm::dvec3 factor{0.0};
};
struct SecondaryRays {
    SecondaryRay reflected;  // factor Wr = R (+ T F for a refractive material)
    SecondaryRay refracted;  // factor Wt = T (1 - F); zero when opaque or on total internal reflection
};
// Both children of a hit by a ray of unit direction d, with origins offset per "Ray origins".
SecondaryRays secondaryRays(const SurfacePoint& s, const Material& m, const glm::dvec3& d);

// "Local shading", one light before visibility and attenuation:
// C ⊙ [(1 - T) ⊙ Kd dot(N, L) + Ks pow(dot(N, H), shininess)], zero unless the light is in front
// of both N and Nf; the specular term is zero when dot(N, H) <= 0.
glm::dvec3 blinnPhong(const SurfacePoint& s, const Material& m, const glm::dvec3& V,
                      const glm::dvec3& L, const glm::dvec3& lightColor);

// att = 1 / (c + l r + q r^2) for a point light at distance r.
double pointLightAttenuation(const glm::dvec3& clq, double r);

// Lines of text that say what the shading of one pixel did, step by step (`vkray render --pixel`):
// filled only when a caller passes one, so renders pay a null check.
using ShadingLog = std::vector<std::string>;

// "x y z" of a vector, 6 significant digits: the log's numbers.
std::string logVector(const glm::dvec3& v);

// L_local: emission, (1 - T) ambient and every light with its attenuation and shadow ray; with
// `log`, one line for the constant terms and one for each light (its term, or why it adds nothing),
// indented for a ray of `depth`.
glm::dvec3 localShading(const Scene& scene, const Tracer& tracer, const SurfacePoint& s,
                        const glm::dvec3& V, ShadingLog* log = nullptr, int depth = 1);

}  // namespace vkray::cpu
