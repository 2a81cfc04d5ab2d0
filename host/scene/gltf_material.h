// glTF 2.0 material (metallic-roughness, with KHR_materials_transmission, KHR_materials_ior and
// KHR_materials_emissive_strength) -> vkray's Whitted Material, after docs/scene-format.md ("glTF
// 2.0"). Whitted ray tracing has perfect mirrors and perfect refraction only, so the mapping keeps
// what a glossy-free renderer can show: a polished metal is a tinted mirror, a rough one a diffuse
// surface of its base colour, a transmissive material glass.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "core/error.h"
#include "scene/scene.h"

namespace tinygltf {
struct Material;
}

namespace vkray {

// The material extensions materialFromGltf reads: a file that requires one of them loads.
std::span<const std::string_view> gltfMaterialExtensions();

// With b = baseColorFactor.rgb, m = metallicFactor, r = roughnessFactor, t = transmissionFactor:
//   mirror weight  mw = m * (1 - r)          reflect  = mw * b
//   transmit       = t * (1 - m) * b         ior      = KHR_materials_ior's ior (default 1.5)
//   diffuse        = (1 - mw) * (1 - t * (1 - m)) * b
//   specular       = (0.04 * (1 - m) + m * b) * (1 - r)   (the Fresnel reflectance at normal incidence)
//   shininess      = 2 / max(r^4, 1e-4) - 2  (Blinn-Phong exponent of GGX alpha = r^2)
//   emission       = emissiveFactor * emissiveStrength
//   ambient        = the scene's ambient state (`sceneState`), which glTF has no notion of.
// Throws vkray::Error at `where`, its message starting with `label` ("material 'glass' (2) of
// 'car.gltf'"), when a factor is not a number or is outside its range: base colour, metallic,
// roughness and transmission outside [0, 1], a negative emission or strength, ior <= 0.
Material materialFromGltf(const tinygltf::Material& m, const Material& sceneState, const FileLoc& where,
                          const std::string& label);

}  // namespace vkray
