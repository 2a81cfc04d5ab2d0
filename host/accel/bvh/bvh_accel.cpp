#include "accel/bvh/bvh_accel.h"

#include "core/error.h"

namespace vkray::accel {

// Placeholder until the bvh builder lands in the next commits.
std::unique_ptr<BuiltAccel> buildBvhAccel(const Scene&, const AccelSpec& spec, const BuildOptions&) {
    throw Error("accelerator '" + spec.name + "' is not implemented yet");
}

}  // namespace vkray::accel
