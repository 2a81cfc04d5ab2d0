#include "scene/mtl_material.h"

namespace vkray {
namespace {

glm::vec3 rgb(const tinyobj::real_t* c) { return glm::vec3(c[0], c[1], c[2]); }

std::string number(float v) {
    std::string s = std::to_string(v);
    s.erase(s.find_last_not_of('0') + 1);  // "1.500000" -> "1.5"
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
}

}  // namespace

Material materialFromMtl(const tinyobj::material_t& mtl, const FileLoc& where, const std::string& label) {
    Material m;
    m.ambient = rgb(mtl.ambient);
    m.diffuse = rgb(mtl.diffuse);
    m.specular = rgb(mtl.specular);
    m.emission = rgb(mtl.emission);
    m.shininess = mtl.shininess;
    if (m.shininess < 0.0f) throw Error(where, label + ": Ns " + number(m.shininess) + " is negative");
    if (!(mtl.dissolve >= 0.0f && mtl.dissolve <= 1.0f))
        throw Error(where, label + ": d " + number(mtl.dissolve) + " is outside [0, 1]");

    const bool mirror = mtl.illum == 3 || mtl.illum == 5;
    const bool glass = mtl.illum == 4 || mtl.illum == 6 || mtl.illum == 7;
    // d is the opacity; Tf only tints what passes. Many exporters (3ds Max, the scenes of McGuire's
    // Computer Graphics Archive) write "Tf 1 1 1" for every opaque material, so Tf alone must not make
    // a material transparent. tinyobjloader leaves Tf at 0 0 0 when absent, which therefore reads as
    // "no filter". A hand-written glass (illum 4/6/7) rarely lowers d: it transmits fully.
    const float weight = (glass && mtl.dissolve == 1.0f) ? 1.0f : 1.0f - mtl.dissolve;
    const glm::vec3 tf = rgb(mtl.transmittance);
    const glm::vec3 filter = tf == glm::vec3(0.0f) ? glm::vec3(1.0f) : tf;
    m.transmit = weight * filter;

    m.reflect = mirror ? m.specular : glm::vec3(0.0f);

    if (m.refracts() && !(mtl.ior > 0.0f))
        throw Error(where,
                    label + ": Ni " + number(mtl.ior) + " must be positive for a transparent material");
    m.ior = mtl.ior > 0.0f ? mtl.ior : 1.0f;
    return m;
}

}  // namespace vkray
