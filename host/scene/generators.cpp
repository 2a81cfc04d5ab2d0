#include "scene/generators.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "scene/sphere.h"

namespace vkray {
namespace {

constexpr std::string_view kNames[] = {"spheres", "soup", "terrain", "burst"};

// SplitMix64 (Steele, Lea, Flood 2014): tiny, fast, and the same sequence everywhere.
class Random {
public:
    explicit Random(uint64_t seed) : state_(seed) {}
    uint64_t next() {
        uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double unit() { return double(next() >> 11) * 0x1.0p-53; }              // [0, 1)
    double range(double lo, double hi) { return lo + (hi - lo) * unit(); }  // [lo, hi)

private:
    uint64_t state_;
};

int64_t ceilDiv(int64_t a, int64_t b) { return (a + b - 1) / b; }

struct TerrainGrid {
    int64_t cellsX, cellsZ;
};

TerrainGrid terrainGrid(int64_t n) {
    const int64_t g = std::max<int64_t>(1, int64_t(std::ceil(std::sqrt(double(n) / 2.0))));
    return {g, std::max<int64_t>(1, ceilDiv(n, 2 * g))};
}

int sphereSteps(int64_t n) {
    const int s = int(std::lround(std::pow(double(n), 0.25) / 2.0));
    return std::clamp(s, kMinSphereSteps, 64);
}

// Appends one triangle given in generator space; false when it does not fit a float.
struct Emitter {
    const Transform& toWorld;
    uint32_t material;
    SceneBuilder& out;

    bool operator()(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) const {
        return out.addFlat({toWorld.point(a), toWorld.point(b), toWorld.point(c)}, material);
    }
};

// Spheres on a square grid of cells over x, z in [-1, 1], each with a random radius (up to 0.4 of
// its cell) and a random height, so the levels of a hierarchy see uneven clusters.
bool generateSpheres(int64_t n, Random& rng, const Emitter& emit) {
    const int steps = sphereSteps(n);
    const int64_t count = ceilDiv(n, sphereTriangleCount(steps));
    const int64_t columns = int64_t(std::ceil(std::sqrt(double(count))));
    const double cell = 2.0 * kGeneratedHalfWidth / double(columns);
    const double maxRadius = std::min(0.4 * cell, 0.5 * kGeneratedHeight);
    const std::vector<TriPoints> unit = unitSphereTriangles(steps);
    for (int64_t i = 0; i < count; ++i) {
        const double r = maxRadius * rng.range(0.5, 1.0);
        const double slack = 0.5 * cell - r;  // how far the centre may move inside its cell
        const glm::dvec3 centre(-kGeneratedHalfWidth + cell * (double(i % columns) + 0.5) + rng.range(-slack, slack),
                                rng.range(r, kGeneratedHeight - r),
                                -kGeneratedHalfWidth + cell * (double(i / columns) + 0.5) + rng.range(-slack, slack));
        for (const TriPoints& t : unit)
            if (!emit(centre + r * t[0], centre + r * t[1], centre + r * t[2])) return false;
    }
    return true;
}

// Random triangles in the volume, each about twice the spacing of N points in it across, so they
// overlap a lot (the hard case for bounding-volume builders) yet stay thin in any one place.
bool generateSoup(int64_t n, Random& rng, const Emitter& emit) {
    const double volume = 4.0 * kGeneratedHalfWidth * kGeneratedHalfWidth * kGeneratedHeight;
    const double reach = std::min(0.5 * kGeneratedHeight, 2.0 * std::cbrt(volume / double(n)));
    const glm::dvec3 lo(-kGeneratedHalfWidth + reach, reach, -kGeneratedHalfWidth + reach);
    const glm::dvec3 hi(kGeneratedHalfWidth - reach, kGeneratedHeight - reach, kGeneratedHalfWidth - reach);
    const auto inBox = [&](const glm::dvec3& a, const glm::dvec3& b) {
        return glm::dvec3(rng.range(a.x, b.x), rng.range(a.y, b.y), rng.range(a.z, b.z));
    };
    for (int64_t i = 0; i < n; ++i) {
        const glm::dvec3 c = inBox(lo, hi);
        const glm::dvec3 p0 = c + inBox(glm::dvec3(-reach), glm::dvec3(reach));
        const glm::dvec3 p1 = c + inBox(glm::dvec3(-reach), glm::dvec3(reach));
        const glm::dvec3 p2 = c + inBox(glm::dvec3(-reach), glm::dvec3(reach));
        if (!emit(p0, p1, p2)) return false;
    }
    return true;
}

// Diamond-square on a (2^k + 1)^2 grid: each pass sets the centres of the squares, then the
// midpoints of their edges, to the mean of their neighbours plus noise that shrinks by
// `roughness` a level (fractal terrain, Fournier, Fussell and Carpenter 1982).
std::vector<double> diamondSquare(int64_t size, Random& rng, double roughness) {
    std::vector<double> h(size_t(size * size), 0.0);
    const auto at = [&](int64_t x, int64_t z) -> double& { return h[size_t(z * size + x)]; };
    for (int64_t z : {int64_t(0), size - 1})
        for (int64_t x : {int64_t(0), size - 1}) at(x, z) = rng.range(-1.0, 1.0);
    double amplitude = 1.0;
    for (int64_t step = size - 1; step > 1; step /= 2, amplitude *= roughness) {
        const int64_t half = step / 2;
        for (int64_t z = half; z < size; z += step)
            for (int64_t x = half; x < size; x += step)
                at(x, z) = 0.25 * (at(x - half, z - half) + at(x + half, z - half) + at(x - half, z + half) +
                                   at(x + half, z + half)) +
                           amplitude * rng.range(-1.0, 1.0);
        for (int64_t z = 0; z < size; z += half)
            for (int64_t x = (z / half) % 2 == 0 ? half : 0; x < size; x += step) {
                // The four neighbours at `half`, fewer on the border.
                double sum = 0.0;
                int count = 0;
                const int64_t neighbours[4][2] = {{-half, 0}, {half, 0}, {0, -half}, {0, half}};
                for (const auto& [dx, dz] : neighbours)
                    if (x + dx >= 0 && x + dx < size && z + dz >= 0 && z + dz < size) {
                        sum += at(x + dx, z + dz);
                        ++count;
                    }
                at(x, z) = sum / count + amplitude * rng.range(-1.0, 1.0);
            }
    }
    return h;
}

// The terrain: the top-left (g + 1) x (h + 1) corner of a diamond-square field, heights scaled to
// [0, 0.5], centred over x, z in [-1, 1]; two triangles a cell facing +y, cells row by row.
bool generateTerrain(int64_t n, Random& rng, const Emitter& emit) {
    // Plain variables, not structured bindings: the lambda below captures them, which clang before
    // 16 (the fuzz build's clang 14) refuses.
    const TerrainGrid grid = terrainGrid(n);
    const int64_t gx = grid.cellsX, gz = grid.cellsZ;
    int64_t size = 3;
    while (size - 1 < std::max(gx, gz)) size = 2 * (size - 1) + 1;
    const std::vector<double> field = diamondSquare(size, rng, 0.55);
    const auto range = std::minmax_element(field.begin(), field.end());
    const double lowest = *range.first, span = *range.second > lowest ? *range.second - lowest : 1.0;
    const double cell = 2.0 * kGeneratedHalfWidth / double(std::max(gx, gz));
    const auto vertex = [&](int64_t x, int64_t z) {
        const double y = 0.5 * kGeneratedHeight * (field[size_t(z * size + x)] - lowest) / span;
        return glm::dvec3(cell * (double(x) - 0.5 * double(gx)), y, cell * (double(z) - 0.5 * double(gz)));
    };
    for (int64_t z = 0; z < gz; ++z)
        for (int64_t x = 0; x < gx; ++x) {
            const glm::dvec3 a = vertex(x, z), b = vertex(x + 1, z), c = vertex(x + 1, z + 1), d = vertex(x, z + 1);
            if (!emit(a, d, c) || !emit(a, c, b)) return false;
        }
    return true;
}

// N triangles around one centre, all with exactly that centroid (a stress case for builders: every
// Morton code of an AAC build is equal, Gu et al. 2013 section 4.1 then splits in the middle, and
// every triangle overlaps every other, the worst case for a kd-tree's clipping). Vertex offsets
// v0, v1 are multiples of 2^-(12 + k) with at most 11 significant bits and v2 = -(v0 + v1), so
// p0 + p1 + p2 and its division by 3 are exact in float: the builders' centroid (p0 + p1 + p2) / 3
// is the centre for every triangle, not just within rounding. Sizes vary over 2^-k, k in 0..7.
bool generateBurst(int64_t n, Random& rng, const Emitter& emit) {
    const glm::dvec3 centre(0.0, 0.5 * kGeneratedHeight, 0.0);
    const auto offset = [&](double unit) {
        const auto coordinate = [&] { return unit * double(int64_t(rng.next() % 2049) - 1024); };
        return glm::dvec3(coordinate(), coordinate(), coordinate());
    };
    for (int64_t i = 0; i < n; ++i) {
        const double unit = std::ldexp(0.25 * kGeneratedHalfWidth / 1024.0, -int(rng.next() % 8));
        glm::dvec3 v0, v1;
        do {  // no zero-area triangle (exact: the cross product of small integers times unit^2)
            v0 = offset(unit);
            v1 = offset(unit);
        } while (glm::cross(v0, v1) == glm::dvec3(0.0));
        if (!emit(centre + v0, centre + v1, centre - (v0 + v1))) return false;
    }
    return true;
}

}  // namespace

std::optional<GeneratorKind> generatorKindFromName(std::string_view name) {
    for (size_t i = 0; i < std::size(kNames); ++i)
        if (kNames[i] == name) return GeneratorKind(i);
    return std::nullopt;
}

std::string_view generatorName(GeneratorKind kind) { return kNames[size_t(kind)]; }

std::string generatorNames() {
    std::string all;
    for (std::string_view name : kNames) all += (all.empty() ? "" : ", ") + std::string(name);
    return all;
}

int64_t generatedTriangleCount(const GeneratorSpec& spec) {
    switch (spec.kind) {
        case GeneratorKind::Spheres: {
            const int64_t perSphere = sphereTriangleCount(sphereSteps(spec.triangles));
            return ceilDiv(spec.triangles, perSphere) * perSphere;
        }
        case GeneratorKind::Soup:
        case GeneratorKind::Burst:
            return spec.triangles;
        case GeneratorKind::Terrain: {
            const TerrainGrid g = terrainGrid(spec.triangles);
            return 2 * g.cellsX * g.cellsZ;
        }
    }
    return 0;
}

bool generateMesh(const GeneratorSpec& spec, const Transform& toWorld, uint32_t material, SceneBuilder& out) {
    out.reserve(size_t(generatedTriangleCount(spec)));
    Random rng(spec.seed);
    const Emitter emit{toWorld, material, out};
    switch (spec.kind) {
        case GeneratorKind::Spheres:
            return generateSpheres(spec.triangles, rng, emit);
        case GeneratorKind::Soup:
            return generateSoup(spec.triangles, rng, emit);
        case GeneratorKind::Terrain:
            return generateTerrain(spec.triangles, rng, emit);
        case GeneratorKind::Burst:
            return generateBurst(spec.triangles, rng, emit);
    }
    return true;
}

}  // namespace vkray
