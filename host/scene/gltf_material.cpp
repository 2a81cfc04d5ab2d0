#include "scene/gltf_material.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "scene/tinygltf_config.h"

namespace vkray {
namespace {

constexpr std::string_view kTransmission = "KHR_materials_transmission";
constexpr std::string_view kIor = "KHR_materials_ior";
constexpr std::string_view kEmissiveStrength = "KHR_materials_emissive_strength";
constexpr std::string_view kGltfMaterialExtensions[] = {kTransmission, kIor, kEmissiveStrength};

// Reads one factor, checks it and names it in the error.
class FactorReader {
public:
    FactorReader(const FileLoc& where, const std::string& label) : where_(where), label_(label) {}

    double in(double v, const std::string& name, double lo, double hi) const {
        if (!(v >= lo && v <= hi))
            throw Error(where_, label_ + ": " + name + " " + std::to_string(v) + " is outside [" + std::to_string(lo) +
                                    ", " + (std::isinf(hi) ? std::string("inf") : std::to_string(hi)) + "]");
        return v;
    }
    glm::vec3 rgb(const std::vector<double>& v, size_t size, const std::string& name, double hi) const {
        if (v.size() != size)
            throw Error(where_, label_ + ": " + name + " has " + std::to_string(v.size()) + " numbers, expected " +
                                    std::to_string(size));
        return glm::vec3(float(in(v[0], name, 0.0, hi)), float(in(v[1], name, 0.0, hi)), float(in(v[2], name, 0.0, hi)));
    }
    // The number `key` of extension `ext` of `m`, or `fallback` when either is absent.
    double extension(const tinygltf::Material& m, std::string_view ext, const char* key, double fallback, double lo,
                     double hi) const {
        const auto it = m.extensions.find(std::string(ext));
        if (it == m.extensions.end() || !it->second.Has(key)) return fallback;
        const tinygltf::Value& v = it->second.Get(key);
        if (!v.IsNumber()) throw Error(where_, label_ + ": " + std::string(ext) + "." + key + " is not a number");
        return in(v.GetNumberAsDouble(), std::string(ext) + "." + key, lo, hi);
    }

private:
    const FileLoc& where_;
    const std::string& label_;
};

}  // namespace

std::span<const std::string_view> gltfMaterialExtensions() { return kGltfMaterialExtensions; }

Material materialFromGltf(const tinygltf::Material& gm, const Material& sceneState, const FileLoc& where,
                          const std::string& label) {
    const FactorReader read(where, label);
    const tinygltf::PbrMetallicRoughness& pbr = gm.pbrMetallicRoughness;
    const glm::vec3 base = read.rgb(pbr.baseColorFactor, 4, "baseColorFactor", 1.0);
    const float metallic = float(read.in(pbr.metallicFactor, "metallicFactor", 0.0, 1.0));
    const float roughness = float(read.in(pbr.roughnessFactor, "roughnessFactor", 0.0, 1.0));
    const float transmission = float(read.extension(gm, kTransmission, "transmissionFactor", 0.0, 0.0, 1.0));
    const double ior = read.extension(gm, kIor, "ior", 1.5, 0.0, INFINITY);
    if (!(ior > 0.0)) throw Error(where, label + ": " + std::string(kIor) + ".ior must be positive");
    const float strength = float(read.extension(gm, kEmissiveStrength, "emissiveStrength", 1.0, 0.0, INFINITY));

    Material m;
    m.ambient = sceneState.ambient;
    const float mirror = metallic * (1.0f - roughness);
    const float transmit = transmission * (1.0f - metallic);  // metals do not transmit
    m.reflect = mirror * base;
    m.transmit = transmit * base;
    m.ior = transmit > 0.0f ? float(ior) : 1.0f;
    m.diffuse = (1.0f - mirror) * (1.0f - transmit) * base;
    m.specular = (glm::vec3(0.04f * (1.0f - metallic)) + metallic * base) * (1.0f - roughness);
    const float alpha2 = std::max(roughness * roughness * roughness * roughness, 1e-4f);
    m.shininess = 2.0f / alpha2 - 2.0f;
    m.emission = read.rgb(gm.emissiveFactor, 3, "emissiveFactor", INFINITY) * strength;
    if (!std::isfinite(m.emission.r + m.emission.g + m.emission.b))
        throw Error(where, label + ": the emission (emissiveFactor * emissiveStrength) is not finite");
    return m;
}

}  // namespace vkray
