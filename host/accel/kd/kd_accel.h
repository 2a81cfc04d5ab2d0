// Entry point of the kd family for accel/accel.cpp: an SAH kd-tree (sah_kd_builder.h) walked by the
// traversal AccelSpec::kdTraversal names — kd-stack, kd-restart or kd-backtrack (kd_traversal.h on
// the CPU, shaders/render_kd_<traversal>.comp on the GPU). The spec's kd* fields override KdConfig's
// defaults when set. docs/kdtree.md describes the whole family.
#pragma once

#include <memory>

#include "accel/accel.h"

namespace vkray::accel {

std::unique_ptr<BuiltAccel> buildKdAccel(const Scene& scene, const AccelSpec& spec, const BuildOptions& options);

}  // namespace vkray::accel
