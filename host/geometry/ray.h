// A ray of the CPU reference renderer, in double precision (docs/shading.md: the CPU follows the
// shading model in double so that its images are the reference the float GPU kernel is checked
// against).
#pragma once

#include <glm/glm.hpp>

namespace vkray::geometry {

// Precondition everywhere a Ray is traced: `dir` is finite and not zero. Camera and secondary rays
// have unit directions, so `t` is a distance; intersection itself does not need a unit `dir`.
struct Ray {
    glm::dvec3 origin{0.0};
    glm::dvec3 dir{0.0, 0.0, -1.0};
};

}  // namespace vkray::geometry
