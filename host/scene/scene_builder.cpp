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

SceneBuilder::SceneBuilder(Scene& scene, int64_t maxTriangles, MemoryCheck memory)
    : scene_(scene), maxTriangles_(maxTriangles), memory_(std::move(memory)), mayMove_(scene.triangles.empty()),
      lo_(std::numeric_limits<double>::infinity()), hi_(-std::numeric_limits<double>::infinity()) {
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
    if (mayMove_) world_.reserve(world_.size() + triangles);
    if (scene_.hasSmoothNormals()) scene_.normals.reserve(scene_.normals.size() + triangles);
}

std::optional<std::string> SceneBuilder::roomProblem(uint64_t more) const {
    const uint64_t have = scene_.triangles.size();
    if (more <= uint64_t(maxTriangles_) && have <= uint64_t(maxTriangles_) - more)
        return memory_ ? memory_(have + more) : std::nullopt;
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

bool SceneBuilder::append(const TriPoints& p, const TriPoints& exact, uint32_t material) {
    if (scene_.triangles.size() >= uint64_t(maxTriangles_)) throw Error(*roomProblem(1));
    if (!fitsFloat(p[0]) || !fitsFloat(p[1]) || !fitsFloat(p[2])) return false;
    scene_.triangles.push_back({glm::vec3(p[0]), glm::vec3(p[1]), glm::vec3(p[2]), material});
    if (!mayMove_) return true;
    for (const glm::dvec3& q : exact) {
        lo_ = glm::min(lo_, q);
        hi_ = glm::max(hi_, q);
    }
    if (glm::all(glm::lessThanEqual(lo_, glm::dvec3(0.0))) && glm::all(glm::greaterThanEqual(hi_, glm::dvec3(0.0)))) {
        // The bounds hold the world's origin and only grow: the local origin is 0 (localOrigin),
        // the floats just stored are final.
        mayMove_ = false;
        std::vector<WorldTriangle>().swap(world_);
        return true;
    }
    world_.push_back({exact, true});
    return true;
}

bool SceneBuilder::addFlat(const TriPoints& p, uint32_t material) { return addFlat(p, p, material); }

bool SceneBuilder::addSmooth(const TriPoints& p, const TriPoints& n, uint32_t material) {
    return addSmooth(p, p, n, material);
}

bool SceneBuilder::addShaded(const TriPoints& p, const std::optional<TriPoints>& n, uint32_t material) {
    const bool smooth = n && glm::length((*n)[0]) > 0.0 && glm::length((*n)[1]) > 0.0 && glm::length((*n)[2]) > 0.0;
    return smooth ? addSmooth(p, *n, material) : addFlat(p, material);
}

bool SceneBuilder::addFlat(const TriPoints& p, const TriPoints& exact, uint32_t material) {
    if (!append(p, exact, material)) return false;
    if (scene_.hasSmoothNormals()) {
        const Triangle& t = scene_.triangles.back();
        const glm::vec3 n = geometricNormal(t.p0, t.p1, t.p2);
        scene_.normals.push_back({n, n, n});
    }
    return true;
}

bool SceneBuilder::addSmooth(const TriPoints& p, const TriPoints& exact, const TriPoints& n, uint32_t material) {
    if (!append(p, exact, material)) return false;
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
    if (mayMove_) world_.back().flat = false;
    return true;
}

void SceneBuilder::setCamera(const Camera& camera, const glm::dvec3& eye, const glm::dvec3& centre) {
    scene_.camera = camera;
    scene_.camera.eye = glm::vec3(eye);
    scene_.camera.center = glm::vec3(centre);
    scene_.hasCamera = true;
    camera_.emplace(eye, centre);
}

void SceneBuilder::addLight(const Light& light, const glm::dvec3& vector) {
    scene_.lights.push_back(light);
    scene_.lights.back().vector = glm::vec3(vector);
    if (light.type == Light::Type::Point) pointLights_.emplace_back(scene_.lights.size() - 1, vector);
}

void SceneBuilder::finish() {
    if (mayMove_ && !world_.empty()) {
        const glm::dvec3 origin = localOrigin(lo_, hi_);
        if (origin != glm::dvec3(0.0)) rebase(origin);
    }
    mayMove_ = false;
    std::vector<WorldTriangle>().swap(world_);
}

// Every position again, from its double world value: subtracted in double, rounded to float once.
void SceneBuilder::rebase(const glm::dvec3& origin) {
    scene_.origin = origin;
    const auto local = [&](const glm::dvec3& p) { return glm::vec3(p - origin); };
    for (size_t i = 0; i < world_.size(); ++i) {
        Triangle& t = scene_.triangles[i];
        const WorldTriangle& w = world_[i];
        t.p0 = local(w.corners[0]);
        t.p1 = local(w.corners[1]);
        t.p2 = local(w.corners[2]);
        if (scene_.hasSmoothNormals() && w.flat) {
            const glm::vec3 n = geometricNormal(t.p0, t.p1, t.p2);
            scene_.normals[i] = {n, n, n};
        }
    }
    if (camera_) {
        scene_.camera.eye = local(camera_->first);
        scene_.camera.center = local(camera_->second);
    }
    for (const auto& [index, position] : pointLights_) scene_.lights[index].vector = local(position);
}

glm::dvec3 localOrigin(const glm::dvec3& lo, const glm::dvec3& hi) {
    if (!glm::all(glm::lessThanEqual(lo, hi))) return glm::dvec3(0.0);
    const glm::dvec3 centre = 0.5 * lo + 0.5 * hi;  // halves first: no overflow near the float limit
    const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    if (extent == 0.0) return centre;
    // The smallest power of two at least twice the extent.
    int exponent = std::ilogb(extent);
    if (std::ldexp(1.0, exponent) < extent) ++exponent;
    const double grid = std::ldexp(1.0, exponent + 1);
    glm::dvec3 origin;
    for (int k = 0; k < 3; ++k) {
        const double q = centre[k] / grid;  // exact: grid is a power of two
        const double whole = std::trunc(q);
        // Nearest, ties towards 0: an axis whose bounds end at 0 and span a power of two stays at 0.
        origin[k] = grid * (std::abs(q - whole) <= 0.5 ? whole : whole + std::copysign(1.0, q)) + 0.0;  // no -0
    }
    return origin;
}

}  // namespace vkray
