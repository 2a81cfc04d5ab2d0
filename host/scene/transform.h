// The current transform of the .scene format: an affine matrix (double precision, so a long chain
// of translate/rotate/scale adds no visible float error) and its normal matrix, kept together so
// a mesh of a million normals does not invert the matrix a million times.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace vkray {

class Transform {
public:
    Transform() = default;
    explicit Transform(const glm::dmat4& m) : m_(m), n_(glm::transpose(glm::inverse(glm::dmat3(m)))) {}

    // OpenGL order: the new transform applies first to the geometry (current = current * t),
    // as translate/rotate/scale do in CSE167 scene files.
    Transform then(const glm::dmat4& t) const { return Transform(m_ * t); }

    const glm::dmat4& matrix() const { return m_; }
    glm::dvec3 point(const glm::dvec3& p) const { return glm::dvec3(m_ * glm::dvec4(p, 1.0)); }
    // Normals transform by the inverse transpose (so they stay perpendicular under non-uniform
    // scaling); the result is renormalized. Not unit when `n` is zero.
    glm::dvec3 normal(const glm::dvec3& n) const {
        const glm::dvec3 t = n_ * n;
        const double len = glm::length(t);
        return len > 0.0 ? t / len : t;
    }

private:
    glm::dmat4 m_{1.0};
    glm::dmat3 n_{1.0};
};

}  // namespace vkray
