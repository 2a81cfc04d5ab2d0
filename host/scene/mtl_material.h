// MTL material -> vkray Material, after docs/scene-format.md ("OBJ/MTL materials"): Ka ambient,
// Kd diffuse, Ks specular, Ns shininess, Ke emission, Ni index of refraction, d dissolve,
// Tf transmission filter, illum 3/5 mirror, illum 4/6/7 glass.
#pragma once

#include <string>

#include <tiny_obj_loader.h>

#include "core/error.h"
#include "scene/scene.h"

namespace vkray {

// Choices where the MTL convention leaves room (each explained in the .cpp):
//  - transmit = (1 - d) * filter, filter = Tf when given, else white. A glass illum (4/6/7) with
//    d = 1 transmits fully (1 * filter).
//  - reflect = Ks for illum 3 and 5 (mirror), 0 otherwise: glass gets its reflection from the
//    Fresnel term, and Ks of a plastic is a highlight colour, not a mirror.
//  - ior = Ni; an opaque material with Ni <= 0 (some exporters write 0) gets 1, unused anyway.
// Throws vkray::Error at `where` (the scene line that loaded the OBJ), its message starting with
// `label` (e.g. "material 'glass' of 'models/x.obj'"), when Ns < 0, d is outside [0, 1], or a
// refracting material has Ni <= 0.
Material materialFromMtl(const tinyobj::material_t& mtl, const FileLoc& where, const std::string& label);

}  // namespace vkray
