#include "accel/kd/kd_accel.h"

#include "core/error.h"

namespace vkray::accel {

// Placeholder until the kd builder lands in the next commits.
std::unique_ptr<BuiltAccel> buildKdAccel(const Scene&, const AccelSpec& spec, const BuildOptions&) {
    throw Error("accelerator '" + spec.name + "' is not implemented yet");
}

}  // namespace vkray::accel
