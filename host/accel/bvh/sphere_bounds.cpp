#include "accel/bvh/sphere_bounds.h"

#include <algorithm>
#include <cmath>

namespace vkray::bvh {
namespace {

// The float sphere centred at `centre` (rounded to float) that holds every double sphere of
// `holds`: its radius is the largest |centre - c| + r, computed in double from the float centre and
// rounded up to the next float.
template <size_t N>
Sphere roundedOut(const glm::dvec3& centre, const glm::dvec3 (&centres)[N], const double (&radii)[N]) {
    Sphere s;
    s.centre = glm::vec3(centre);
    const glm::dvec3 c(s.centre);
    double r = 0.0;
    for (size_t i = 0; i < N; ++i) r = std::max(r, glm::length(centres[i] - c) + radii[i]);
    float rf = float(r);
    if (double(rf) < r) rf = std::nextafter(rf, INFINITY);
    s.radius = rf;
    return s;
}

}  // namespace

Sphere triangleSphere(const Triangle& t) {
    const glm::dvec3 p[3] = {glm::dvec3(t.p0), glm::dvec3(t.p1), glm::dvec3(t.p2)};
    const double zero[3] = {0.0, 0.0, 0.0};
    // An angle of 90 degrees or more at vertex i: the opposite edge is a diameter.
    for (int i = 0; i < 3; ++i) {
        const glm::dvec3 &a = p[i], &b = p[(i + 1) % 3], &c = p[(i + 2) % 3];
        if (glm::dot(b - a, c - a) <= 0.0) return roundedOut(0.5 * (b + c), p, zero);
    }
    // Acute: the circumcentre (all three dot products positive, so the edges span a plane).
    const glm::dvec3 a = p[1] - p[0], b = p[2] - p[0], axb = glm::cross(a, b);
    const glm::dvec3 centre =
        p[0] + (glm::dot(a, a) * glm::cross(b, axb) + glm::dot(b, b) * glm::cross(axb, a)) / (2.0 * glm::dot(axb, axb));
    return roundedOut(centre, p, zero);
}

Sphere mergeSpheres(const Sphere& a, const Sphere& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    const glm::dvec3 ca(a.centre), cb(b.centre);
    const double ra = a.radius, rb = b.radius, d = glm::length(cb - ca);
    if (d + rb <= ra) return a;
    if (d + ra <= rb) return b;
    const double r = 0.5 * (d + ra + rb);
    const glm::dvec3 centre = ca + (cb - ca) * ((r - ra) / d);  // d > |ra - rb| >= 0 here
    const glm::dvec3 centres[2] = {ca, cb};
    const double radii[2] = {ra, rb};
    return roundedOut(centre, centres, radii);
}

}  // namespace vkray::bvh
