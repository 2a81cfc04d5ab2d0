#include "scene/scene_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace vkray {
namespace {

std::array<float, 20> materialKey(const Material& m) {
    return {m.ambient.x,  m.ambient.y,  m.ambient.z,  m.diffuse.x,  m.diffuse.y,  m.diffuse.z, m.specular.x,
            m.specular.y, m.specular.z, m.emission.x, m.emission.y, m.emission.z, m.reflect.x, m.reflect.y,
            m.reflect.z,  m.transmit.x, m.transmit.y, m.transmit.z, m.shininess,  m.ior};
}

bool fitsFloat(const glm::dvec3& p) {
    const double limit = std::numeric_limits<float>::max();
    return std::abs(p.x) <= limit && std::abs(p.y) <= limit && std::abs(p.z) <= limit;
}

}  // namespace

bool SceneBuilder::MaterialLess::operator()(const Material& a, const Material& b) const {
    const auto ka = materialKey(a), kb = materialKey(b);
    return std::lexicographical_compare(ka.begin(), ka.end(), kb.begin(), kb.end());
}

SceneBuilder::SceneBuilder(Scene& scene, int64_t maxTriangles) : scene_(scene), maxTriangles_(maxTriangles) {
    for (size_t i = 0; i < scene_.materials.size(); ++i) index_.emplace(scene_.materials[i], uint32_t(i));
}

uint32_t SceneBuilder::material(const Material& m) {
    const auto [it, added] = index_.emplace(m, uint32_t(scene_.materials.size()));
    if (added) scene_.materials.push_back(m);
    return it->second;
}

glm::vec3 geometricNormal(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
    const glm::dvec3 c = glm::cross(glm::dvec3(p1) - glm::dvec3(p0), glm::dvec3(p2) - glm::dvec3(p0));
    const double len = glm::length(c);
    return len > 0.0 ? glm::vec3(c / len) : glm::vec3(0.0f, 0.0f, 1.0f);
}

void SceneBuilder::reserve(size_t triangles) {
    scene_.triangles.reserve(scene_.triangles.size() + triangles);
    if (scene_.hasSmoothNormals()) scene_.normals.reserve(scene_.normals.size() + triangles);
}

std::optional<std::string> SceneBuilder::roomProblem(uint64_t more) const {
    const uint64_t have = scene_.triangles.size();
    if (more <= uint64_t(maxTriangles_) && have <= uint64_t(maxTriangles_) - more) return std::nullopt;
    const uint64_t total = have + more >= have ? have + more : UINT64_MAX;  // saturating
    std::string msg = "the scene would have ";
    msg.append(std::to_string(total))
        .append(" triangles (")
        .append(std::to_string(have))
        .append(" so far), past the limit of ")
        .append(std::to_string(maxTriangles_));
    if (maxTriangles_ == kMaxSceneTriangles) msg.append(" (2^26) a scene may have");
    return msg;
}

bool SceneBuilder::append(const TriPoints& p, uint32_t material) {
    if (scene_.triangles.size() >= uint64_t(maxTriangles_)) throw Error(*roomProblem(1));
    if (!fitsFloat(p[0]) || !fitsFloat(p[1]) || !fitsFloat(p[2])) return false;
    scene_.triangles.push_back({glm::vec3(p[0]), glm::vec3(p[1]), glm::vec3(p[2]), material});
    return true;
}

bool SceneBuilder::addFlat(const TriPoints& p, uint32_t material) {
    if (!append(p, material)) return false;
    if (scene_.hasSmoothNormals()) {
        const Triangle& t = scene_.triangles.back();
        const glm::vec3 n = geometricNormal(t.p0, t.p1, t.p2);
        scene_.normals.push_back({n, n, n});
    }
    return true;
}

bool SceneBuilder::addSmooth(const TriPoints& p, const TriPoints& n, uint32_t material) {
    if (!append(p, material)) return false;
    // First smooth triangle: every earlier one was flat, give each its geometric normal.
    if (scene_.normals.empty()) {
        scene_.normals.reserve(scene_.triangles.capacity());
        for (size_t i = 0; i + 1 < scene_.triangles.size(); ++i) {
            const Triangle& t = scene_.triangles[i];
            const glm::vec3 g = geometricNormal(t.p0, t.p1, t.p2);
            scene_.normals.push_back({g, g, g});
        }
    }
    scene_.normals.push_back({glm::vec3(n[0]), glm::vec3(n[1]), glm::vec3(n[2])});
    return true;
}

}  // namespace vkray
