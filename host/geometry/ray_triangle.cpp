#include "geometry/ray_triangle.h"

#include <algorithm>
#include <cmath>
#include <utility>

// Watertightness rests on the edge functions being evaluated as plain round-to-nearest products and
// differences (see the comment in intersect()). GCC contracts a*b - c*d into an fma only with
// -ffp-contract=fast, which it does not use in ISO mode (-std=c++20, CMAKE_CXX_EXTENSIONS OFF).

namespace vkray::geometry {

namespace {
// 16 u, u = 2^-53 the unit roundoff of double: see intersect().
constexpr double kTNoise = 0x1p-49;
}  // namespace

double differenceOfProducts(double a, double b, double c, double d) {
    const double cd = c * d;
    const double cdError = std::fma(-c, d, cd);  // cd - c*d, exactly
    const double diff = std::fma(a, b, -cd);     // a*b - cd, rounded once
    return diff + cdError;
}

bool isDegenerate(const TriangleVertices& tri) {
    const glm::dvec3 e1 = tri[1] - tri[0], e2 = tri[2] - tri[0];
    return differenceOfProducts(e1.y, e2.z, e1.z, e2.y) == 0.0 &&
           differenceOfProducts(e1.z, e2.x, e1.x, e2.z) == 0.0 &&
           differenceOfProducts(e1.x, e2.y, e1.y, e2.x) == 0.0;
}

WatertightRay::WatertightRay(const Ray& ray) : origin_(ray.origin) {
    const glm::dvec3 a = glm::abs(ray.dir);
    kz_ = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    kx_ = (kz_ + 1) % 3;
    ky_ = (kx_ + 1) % 3;
    // Swapping x and y when the dominant component is negative keeps the winding of the projected
    // triangle, so the signs of the edge functions keep their meaning (paper, section 3).
    if (ray.dir[kz_] < 0.0) std::swap(kx_, ky_);
    sx_ = ray.dir[kx_] / ray.dir[kz_];
    sy_ = ray.dir[ky_] / ray.dir[kz_];
    sz_ = 1.0 / ray.dir[kz_];
}

std::optional<TriangleHit> WatertightRay::intersect(const TriangleVertices& tri, double tmin,
                                                    double tmax) const {
    // Vertices relative to the origin, sheared so the ray runs along +z through (0, 0).
    const glm::dvec3 A = tri[0] - origin_, B = tri[1] - origin_, C = tri[2] - origin_;
    const double ax = A[kx_] - sx_ * A[kz_], ay = A[ky_] - sy_ * A[kz_];
    const double bx = B[kx_] - sx_ * B[kz_], by = B[ky_] - sy_ * B[kz_];
    const double cx = C[kx_] - sx_ * C[kz_], cy = C[ky_] - sy_ * C[kz_];

    // 2D edge functions (twice the signed areas seen from the origin); U weights p0, V p1, W p2.
    // A shared vertex is transformed identically in both triangles, and round(ab) - round(cd) has
    // the sign of ab - cd whenever it is not zero (rounding is monotonic), so a non-zero result is
    // already exactly signed. Only an exact zero can hide a tiny value of either sign: recompute
    // then with an exactly signed difference of products (the paper falls back to double for float;
    // for double, Kahan's fma form plays that role).
    double U = cx * by - cy * bx;
    double V = ax * cy - ay * cx;
    double W = bx * ay - by * ax;
    if (U == 0.0 || V == 0.0 || W == 0.0) {
        U = differenceOfProducts(cx, by, cy, bx);
        V = differenceOfProducts(ax, cy, ay, cx);
        W = differenceOfProducts(bx, ay, by, ax);
    }
    // Inside (edges and vertices included) when no two edge functions have opposite signs; both
    // windings are accepted (no back-face culling: the shading model is two-sided).
    if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return std::nullopt;
    const double det = U + V + W;
    if (det == 0.0) return std::nullopt;  // parallel ray, or in the plane of the triangle

    const double az = sz_ * A[kz_], bz = sz_ * B[kz_], cz = sz_ * C[kz_];
    const double t = (U * az + V * bz + W * cz) / det;
    if (!(t > tmin && t < tmax)) return std::nullopt;  // NaN fails too
    // t must stand above its own rounding, a few ulps of the vertices' distances along the ray (the
    // deltaZ term of Pharr, Jakob and Humphreys, PBR 3rd ed., 3.9.6): a ray starting on (or a
    // rounding away from) the plane of a triangle would otherwise "hit" it at a t of pure rounding,
    // as shadow rays from a concave edge do with the face they were not pushed off. The GPU's float
    // test has the same rule (shaders/include/triangle.glsl).
    if (t <= kTNoise * std::max({std::abs(az), std::abs(bz), std::abs(cz)})) return std::nullopt;
    // Collinear vertices can still give a rounded det != 0; zero-area triangles never hit. Tested
    // last: only candidate hits pay for it.
    if (isDegenerate(tri)) return std::nullopt;
    return TriangleHit{t, U / det, V / det, W / det};
}

std::optional<TriangleHit> intersectTriangle(const Ray& ray, const TriangleVertices& tri, double tmin,
                                             double tmax) {
    return WatertightRay(ray).intersect(tri, tmin, tmax);
}

}  // namespace vkray::geometry
