// The current transform of the .scene format: an affine matrix (double precision, so a long chain
// of translate/rotate/scale adds no visible float error) and its normal matrix, kept together so
// a mesh of a million normals does not invert the matrix a million times.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace vkray {

class Transform {
public:
    Transform() = default;
    explicit Transform(const glm::dmat4& m) : m_(m), n_(normalMatrix(glm::dmat3(m))) {}

    // OpenGL order: the new transform applies first to the geometry (current = current * t),
    // as translate/rotate/scale do in CSE167 scene files.
    Transform then(const glm::dmat4& t) const { return Transform(m_ * t); }

    const glm::dmat4& matrix() const { return m_; }
    // False when the matrix or its normal matrix has an infinity or a NaN: scale factors that
    // multiply past 1e308, or down to 0 (a singular matrix has no inverse transpose).
    bool isFinite() const {
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (!std::isfinite(m_[c][r]) || (c < 3 && r < 3 && !std::isfinite(n_[c][r]))) return false;
        return true;
    }
    glm::dvec3 point(const glm::dvec3& p) const { return glm::dvec3(m_ * glm::dvec4(p, 1.0)); }
    // Normals transform by the inverse transpose (so they stay perpendicular under non-uniform
    // scaling); the result is renormalized. Not unit when `n` is zero.
    glm::dvec3 normal(const glm::dvec3& n) const {
        const glm::dvec3 t = n_ * n;
        const double len = glm::length(t);
        return len > 0.0 ? t / len : t;
    }

private:
    // The inverse transpose up to a positive factor (normal() renormalizes): of the matrix divided
    // by its largest entry, so that a uniformly tiny or huge scale (1e-120: a determinant of 1e-360)
    // does not underflow the determinant and make the inverse infinite.
    static glm::dmat3 normalMatrix(const glm::dmat3& a) {
        double largest = 0.0;
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r) largest = std::max(largest, std::abs(a[c][r]));
        return glm::transpose(glm::inverse(a / largest));  // 0/0 for a zero matrix: NaN, see isFinite
    }

    glm::dmat4 m_{1.0};
    glm::dmat3 n_{1.0};
};

}  // namespace vkray
