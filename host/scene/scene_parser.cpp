#include "scene/scene_parser.h"

#include <algorithm>
#include <cctype>
#include <iterator>
#include <optional>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "core/suggest.h"
#include "scene/generators.h"
#include "scene/mesh_file.h"
#include "scene/mesh_scene.h"
#include "scene/scene_builder.h"
#include "scene/scene_line.h"
#include "scene/sphere.h"
#include "scene/text_input.h"
#include "scene/transform.h"

namespace vkray {
namespace {

// The material commands' state. `reflect` is kept apart because, until a `reflect` line sets it,
// it follows the specular colour (the CSE167 convention; docs/scene-format.md).
struct MaterialState {
    Material base;
    std::optional<glm::vec3> reflect;

    Material resolve() const {
        Material m = base;
        m.reflect = reflect ? *reflect : base.specular;
        return m;
    }
};

class Parser {
public:
    Parser(Scene& scene, std::string file, std::filesystem::path baseDir, const ParseOptions& options)
        : file_(std::move(file)), baseDir_(std::move(baseDir)), out_(scene, options.maxTriangles, options.memoryProblem),
          readFile_(options.readFile ? options.readFile : fileSystemReader()), progress_(options.progress), warn_(options.warn),
          transforms_(1), exactTransforms_(1, glm::dmat4(1.0)) {}

    void parseLine(std::string_view text, int number);
    void finish() { out_.finish(); }

private:
    enum class Kind { Numbers, Integers, FileName, Nothing, Generator };
    struct Command {
        std::string_view name;
        size_t args;
        Kind kind;
        std::string_view usage;
        void (Parser::*run)(const SceneLine&);
        size_t optionalArgs = 0;  // trailing arguments that may be left out
    };
    static const Command kCommands[];

    Scene& scene() { return out_.scene(); }
    const Transform& transform() const { return transforms_.back(); }
    void then(const SceneLine& line, const glm::dmat4& m, const glm::dmat4& exact);
    glm::dvec3 exactPoint(const glm::dvec3& p) const { return glm::dvec3(exactTransforms_.back() * glm::dvec4(p, 1.0)); }
    uint32_t currentMaterial();
    void materialChanged() { materialIndex_.reset(); }
    void checkArgCount(const Command& c, const SceneLine& line) const;
    [[noreturn]] void unknownCommand(const SceneLine& line) const;
    uint32_t vertexIndex(const SceneLine& line, size_t arg, size_t count, const char* noun) const;
    void added(bool ok, const SceneLine& line) const;
    void checkRoom(uint64_t triangles, const SceneLine& line) const;

    void size(const SceneLine&);
    void output(const SceneLine& l) { scene().output = std::string(l.text(1)); }
    void maxdepth(const SceneLine&);
    void spp(const SceneLine&);
    void camera(const SceneLine&);
    void light(const SceneLine&);
    void attenuation(const SceneLine&);
    void background(const SceneLine&);
    void colour(const SceneLine&);
    void shininess(const SceneLine&);
    void refract(const SceneLine&);
    void maxCount(const SceneLine&);
    void vertex(const SceneLine& l) { vertices_.push_back({glm::dvec3(l.vec3(1)), l.dvec3(1)}); }
    void tri(const SceneLine&);
    void vertexNormal(const SceneLine&);
    void triNormal(const SceneLine&);
    void sphere(const SceneLine&);
    void sphereSteps(const SceneLine&);
    void translate(const SceneLine& l) {
        then(l, glm::translate(glm::dmat4(1.0), glm::dvec3(l.vec3(1))), glm::translate(glm::dmat4(1.0), l.dvec3(1)));
    }
    void rotate(const SceneLine&);
    void scale(const SceneLine&);
    void pushTransform(const SceneLine&);
    void popTransform(const SceneLine&);
    void geo(const SceneLine&);
    void generate(const SceneLine&);

    std::string file_;
    std::filesystem::path baseDir_;
    SceneBuilder out_;
    FileReader readFile_;
    std::function<void(const std::string&)> progress_;
    std::function<void(const std::string&)> warn_;
    MaterialState material_;
    std::optional<uint32_t> materialIndex_;
    std::vector<Transform> transforms_;  // back() is current; the first entry is never popped
    // The same stack from the arguments read in double: what Position::exact goes through.
    std::vector<glm::dmat4> exactTransforms_;
    // A position as read in float (how scenes near the world's origin are stored) and in double
    // (how a far one is: SceneBuilder::addFlat).
    struct Position {
        glm::dvec3 read, exact;
    };
    std::vector<Position> vertices_;
    std::vector<std::pair<Position, glm::dvec3>> normalVertices_;  // position, normal
    int sphereSteps_ = kDefaultSphereSteps;
};

const Parser::Command Parser::kCommands[] = {
    {"size", 2, Kind::Integers, "width height", &Parser::size},
    {"output", 1, Kind::FileName, "", &Parser::output},
    {"maxdepth", 1, Kind::Integers, "depth", &Parser::maxdepth},
    {"spp", 1, Kind::Integers, "camera rays per pixel", &Parser::spp},
    {"camera", 10, Kind::Numbers, "eye xyz, centre xyz, up xyz, fovy", &Parser::camera},
    {"point", 6, Kind::Numbers, "x y z r g b", &Parser::light},
    {"directional", 6, Kind::Numbers, "x y z r g b", &Parser::light},
    {"attenuation", 3, Kind::Numbers, "constant linear quadratic", &Parser::attenuation},
    {"background", 3, Kind::Numbers, "r g b", &Parser::background},
    {"ambient", 3, Kind::Numbers, "r g b", &Parser::colour},
    {"diffuse", 3, Kind::Numbers, "r g b", &Parser::colour},
    {"specular", 3, Kind::Numbers, "r g b", &Parser::colour},
    {"emission", 3, Kind::Numbers, "r g b", &Parser::colour},
    {"reflect", 3, Kind::Numbers, "r g b", &Parser::colour},
    {"shininess", 1, Kind::Numbers, "s", &Parser::shininess},
    {"refract", 4, Kind::Numbers, "ior tr tg tb", &Parser::refract},
    {"maxverts", 1, Kind::Integers, "n", &Parser::maxCount},
    {"maxvertnorms", 1, Kind::Integers, "n", &Parser::maxCount},
    {"vertex", 3, Kind::Numbers, "x y z", &Parser::vertex},
    {"tri", 3, Kind::Integers, "vertex indices i j k", &Parser::tri},
    {"vertexnormal", 6, Kind::Numbers, "x y z nx ny nz", &Parser::vertexNormal},
    {"trinormal", 3, Kind::Integers, "vertexnormal indices i j k", &Parser::triNormal},
    {"sphere", 4, Kind::Numbers, "x y z radius", &Parser::sphere},
    {"spheresteps", 1, Kind::Integers, "n", &Parser::sphereSteps},
    {"translate", 3, Kind::Numbers, "x y z", &Parser::translate},
    {"rotate", 4, Kind::Numbers, "axis x y z, degrees", &Parser::rotate},
    {"scale", 3, Kind::Numbers, "x y z", &Parser::scale},
    {"pushTransform", 0, Kind::Nothing, "", &Parser::pushTransform},
    {"popTransform", 0, Kind::Nothing, "", &Parser::popTransform},
    {"geo", 1, Kind::FileName, "", &Parser::geo},
    {"obj", 1, Kind::FileName, "", &Parser::geo},
    {"generate", 2, Kind::Generator, "kind triangles [seed]", &Parser::generate, 1},
};

void Parser::parseLine(std::string_view text, int number) {
    std::vector<Token> tokens = tokenize(text);
    if (tokens.empty()) return;  // blank or comment
    const SceneLine line(file_, number, std::move(tokens));
    for (const Command& c : kCommands) {
        if (c.name == line.command()) {
            checkArgCount(c, line);
            (this->*c.run)(line);
            return;
        }
    }
    unknownCommand(line);
}

void Parser::checkArgCount(const Command& c, const SceneLine& line) const {
    const size_t most = c.args + c.optionalArgs;
    if (line.argCount() >= c.args && line.argCount() <= most) return;
    const bool one = c.args == 1;
    std::string expected;
    switch (c.kind) {
        case Kind::Numbers:
            expected = std::to_string(c.args) + (one ? " number" : " numbers");
            break;
        case Kind::Integers:
            expected = std::to_string(c.args) + (one ? " integer" : " integers");
            break;
        case Kind::FileName:
            expected = "1 file name";
            break;
        case Kind::Nothing:
            expected = "no arguments";
            break;
        case Kind::Generator:
            expected = std::to_string(c.args) + " to " + std::to_string(most) + " arguments";
            break;
    }
    const std::string usage = c.usage.empty() ? "" : " (" + std::string(c.usage) + ")";
    line.fail("expected " + expected + " after '" + std::string(c.name) + "'" + usage + ", got " +
                  std::to_string(line.argCount()),
              line.argCount() > most ? most + 1 : 0);
}

void Parser::unknownCommand(const SceneLine& line) const {
    const auto lower = [](std::string_view s) {
        std::string r(s);
        std::transform(r.begin(), r.end(), r.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        return r;
    };
    for (const Command& c : kCommands)
        if (lower(c.name) == lower(line.command()))
            line.fail("unknown command " + quoted(line.command()) + " (did you mean '" + std::string(c.name) +
                      "'? commands are case-sensitive)");
    std::vector<std::string_view> names;
    for (const Command& c : kCommands) names.push_back(c.name);
    if (const std::optional<std::string> near = closestName(line.command(), names))
        line.fail("unknown command " + quoted(line.command()) + " (did you mean '" + *near + "'?)");
    line.fail("unknown command " + quoted(line.command()) + " (the commands are listed in docs/scene-format.md)");
}

uint32_t Parser::currentMaterial() {
    if (!materialIndex_) materialIndex_ = out_.material(material_.resolve());
    return *materialIndex_;
}

uint32_t Parser::vertexIndex(const SceneLine& line, size_t arg, size_t count, const char* noun) const {
    const int64_t i = line.integer(arg);
    if (i < 0 || uint64_t(i) >= count) {
        const std::string defined =
            count == 0 ? std::string("none defined yet")
                       : std::to_string(count) + " defined, valid 0.." + std::to_string(count - 1);
        line.fail(std::string(noun) + " index " + std::to_string(i) + " out of range (" + defined + ")", arg);
    }
    return uint32_t(i);
}

void Parser::added(bool ok, const SceneLine& line) const {
    if (!ok) line.fail("the transformed geometry does not fit a 32-bit float (coordinates overflow)");
}

// Asked before a line makes its triangles: a sphere or a generated mesh past the limit is refused
// before any time or memory goes into it.
void Parser::checkRoom(uint64_t triangles, const SceneLine& line) const {
    if (const auto problem = out_.roomProblem(triangles)) line.fail(*problem);
}

void Parser::then(const SceneLine& line, const glm::dmat4& m, const glm::dmat4& exact) {
    const Transform next = transform().then(m);
    // Scale factors are each finite and non-zero, but a chain of them can still multiply past what
    // a double holds; the normals would then be NaN (or the points infinite) without a word.
    if (!next.isFinite())
        line.fail("the transform overflows or becomes singular in double precision (scale factors that "
                  "multiply past 1e308 or below 1e-308, or axes scaled too unevenly)");
    transforms_.back() = next;
    exactTransforms_.back() = exactTransforms_.back() * exact;
}

void Parser::pushTransform(const SceneLine& line) {
    if (transforms_.size() > kMaxTransformDepth)
        line.fail("pushTransform nested more than " + std::to_string(kMaxTransformDepth) +
                  " deep (is a popTransform missing?)");
    transforms_.push_back(transform());
    exactTransforms_.push_back(exactTransforms_.back());
}

void Parser::size(const SceneLine& line) {
    const int64_t w = line.integer(1), h = line.integer(2);
    if (const auto problem = imageSizeProblem(w, h))
        line.fail(*problem, w < 1 || w > kMaxImageSide ? 1 : 2);
    scene().width = int(w);
    scene().height = int(h);
}

void Parser::maxdepth(const SceneLine& line) {
    const int64_t d = line.integer(1);
    if (d < 1 || d > kMaxDepthLimit)
        line.fail("maxdepth " + std::to_string(d) + " is outside 1.." + std::to_string(kMaxDepthLimit), 1);
    scene().maxDepth = int(d);
}

void Parser::spp(const SceneLine& line) {
    const int64_t n = line.integer(1);
    if (n < 1 || n > kMaxSamplesPerPixel)
        line.fail("spp " + std::to_string(n) + " is outside 1.." + std::to_string(kMaxSamplesPerPixel), 1);
    scene().spp = int(n);
}

void Parser::camera(const SceneLine& line) {
    const glm::dvec3 eye = line.dvec3(1), centre = line.dvec3(4);
    Camera c{glm::vec3(eye), glm::vec3(centre), line.vec3(7), line.number(10)};
    if (!(c.fovyDegrees > 0.0f && c.fovyDegrees < 180.0f))
        line.fail("camera fovy " + excerpt(line.text(10)) + " is outside (0, 180) degrees", 10);
    const glm::dvec3 back = eye - centre;
    if (glm::length(back) == 0.0) line.fail("camera eye and look-at centre coincide", 1);
    const glm::dvec3 up(c.up);
    // The same test as makeCameraFrame (camera.cpp), reported here with the line.
    if (glm::length(glm::cross(up, glm::normalize(back))) <= 1e-9 * glm::length(up) || glm::length(up) == 0.0)
        line.fail("camera up vector is zero or parallel to the viewing direction", 7);
    out_.setCamera(c, eye, centre);
}

void Parser::light(const SceneLine& line) {
    Light l;
    l.type = line.command() == "point" ? Light::Type::Point : Light::Type::Directional;
    const glm::dvec3 vector = line.dvec3(1);
    l.color = line.vec3(4);
    if (l.type == Light::Type::Directional && glm::vec3(vector) == glm::vec3(0.0f))
        line.fail("directional light direction is the zero vector", 1);
    out_.addLight(l, vector);
}

void Parser::attenuation(const SceneLine& line) {
    const glm::vec3 a = line.vec3(1);
    if (a.x < 0.0f || a.y < 0.0f || a.z < 0.0f || a == glm::vec3(0.0f))
        line.fail("attenuation needs non-negative coefficients, not all zero", 1);
    scene().attenuation = a;
}

void Parser::background(const SceneLine& line) {
    const glm::vec3 c = line.vec3(1);
    if (c.r < 0.0f || c.g < 0.0f || c.b < 0.0f) line.fail("background needs non-negative r g b", 1);
    scene().background = c;
}

void Parser::colour(const SceneLine& line) {
    const glm::vec3 c = line.vec3(1);
    const std::string_view name = line.command();
    if (name == "ambient")
        material_.base.ambient = c;
    else if (name == "diffuse")
        material_.base.diffuse = c;
    else if (name == "specular")
        material_.base.specular = c;
    else if (name == "emission")
        material_.base.emission = c;
    else
        material_.reflect = c;  // "reflect"
    materialChanged();
}

void Parser::shininess(const SceneLine& line) {
    const float s = line.number(1);
    if (s < 0.0f) line.fail("shininess " + excerpt(line.text(1)) + " is negative", 1);
    material_.base.shininess = s;
    materialChanged();
}

void Parser::refract(const SceneLine& line) {
    const float ior = line.number(1);
    if (!(ior > 0.0f)) line.fail("index of refraction " + excerpt(line.text(1)) + " must be positive", 1);
    material_.base.ior = ior;
    material_.base.transmit = line.vec3(2);
    materialChanged();
}

void Parser::maxCount(const SceneLine& line) {
    // Only a size hint in CSE167 files; vertices beyond it are accepted.
    const int64_t n = line.integer(1);
    if (n < 0) line.fail(std::string(line.command()) + " " + std::to_string(n) + " is negative", 1);
    if (line.command() == "maxverts")
        vertices_.reserve(size_t(std::min<int64_t>(n, 1 << 20)));
    else
        normalVertices_.reserve(size_t(std::min<int64_t>(n, 1 << 20)));
}

void Parser::tri(const SceneLine& line) {
    checkRoom(1, line);
    TriPoints p, exact;
    for (size_t k = 0; k < 3; ++k) {
        const Position& v = vertices_[vertexIndex(line, k + 1, vertices_.size(), "vertex")];
        p[k] = transform().point(v.read);
        exact[k] = exactPoint(v.exact);
    }
    added(out_.addFlat(p, exact, currentMaterial()), line);
}

void Parser::vertexNormal(const SceneLine& line) {
    const glm::dvec3 n(line.vec3(4));
    if (n == glm::dvec3(0.0)) line.fail("vertexnormal normal is the zero vector", 4);
    normalVertices_.emplace_back(Position{glm::dvec3(line.vec3(1)), line.dvec3(1)}, n);
}

void Parser::triNormal(const SceneLine& line) {
    checkRoom(1, line);
    TriPoints p, exact, n;
    for (size_t k = 0; k < 3; ++k) {
        const auto& [position, normal] =
            normalVertices_[vertexIndex(line, k + 1, normalVertices_.size(), "vertexnormal")];
        p[k] = transform().point(position.read);
        exact[k] = exactPoint(position.exact);
        n[k] = transform().normal(normal);
    }
    added(out_.addSmooth(p, exact, n, currentMaterial()), line);
}

void Parser::sphere(const SceneLine& line) {
    const glm::dvec3 centre(line.vec3(1));
    const float r = line.number(4);
    if (!(r > 0.0f)) line.fail("sphere radius " + excerpt(line.text(4)) + " must be positive", 4);
    checkRoom(uint64_t(sphereTriangleCount(sphereSteps_)), line);
    added(appendSphere(out_, transform(), centre, r, sphereSteps_, currentMaterial()), line);
}

void Parser::sphereSteps(const SceneLine& line) {
    const int64_t n = line.integer(1);
    if (n < kMinSphereSteps || n > kMaxSphereSteps)
        line.fail("spheresteps " + std::to_string(n) + " is outside " + std::to_string(kMinSphereSteps) +
                      ".." + std::to_string(kMaxSphereSteps),
                  1);
    sphereSteps_ = int(n);
}

void Parser::rotate(const SceneLine& line) {
    const glm::dvec3 axis(line.vec3(1));
    const double degrees = line.number(4);
    if (axis == glm::dvec3(0.0)) line.fail("rotate axis is the zero vector", 1);
    then(line, glm::rotate(glm::dmat4(1.0), glm::radians(degrees), glm::normalize(axis)),
         glm::rotate(glm::dmat4(1.0), glm::radians(line.real(4)), glm::normalize(line.dvec3(1))));
}

void Parser::scale(const SceneLine& line) {
    const glm::dvec3 s(line.vec3(1));
    for (int k = 0; k < 3; ++k)
        if (s[k] == 0.0) line.fail("scale factor 0 would flatten the geometry (no normals)", size_t(k) + 1);
    then(line, glm::scale(glm::dmat4(1.0), s), glm::scale(glm::dmat4(1.0), line.dvec3(1)));
}

void Parser::popTransform(const SceneLine& line) {
    if (transforms_.size() == 1) line.fail("popTransform without a matching pushTransform");
    transforms_.pop_back();
    exactTransforms_.pop_back();
}

void Parser::geo(const SceneLine& line) {
    const std::filesystem::path file = baseDir_ / std::filesystem::path(std::string(line.text(1)));
    MeshRequest request{file, file.lexically_normal().string(), FileLoc{file_, line.number(), 0}, transform(),
                        material_.resolve(), readFile_, warn_};
    if (progress_) progress_("mesh " + file.filename().string());
    loadMeshFile(request, out_);
}

// generate KIND N [SEED]: a procedural mesh (generators.h) under the current transform and material.
void Parser::generate(const SceneLine& line) {
    const std::optional<GeneratorKind> kind = generatorKindFromName(line.text(1));
    if (!kind)
        line.fail("unknown generator " + quoted(line.text(1)) + " (expected one of: " + generatorNames() + ")", 1);
    const int64_t n = line.integer(2);
    if (n < 1 || n > kMaxGeneratedTriangles)
        line.fail("triangle count " + std::to_string(n) + " is outside 1.." + std::to_string(kMaxGeneratedTriangles),
                  2);
    int64_t seed = 1;
    if (line.argCount() == 3) {
        seed = line.integer(3);
        if (seed < 0) line.fail("seed " + std::to_string(seed) + " is negative", 3);
    }
    const GeneratorSpec spec{*kind, n, uint64_t(seed)};
    checkRoom(uint64_t(generatedTriangleCount(spec)), line);
    if (progress_) progress_("generate " + std::string(line.text(1)) + " " + std::to_string(n));
    added(generateMesh(spec, transform(), currentMaterial(), out_), line);
}

}  // namespace

Scene parseSceneText(std::string_view text, const std::string& displayName, const std::filesystem::path& baseDir,
                     const ParseOptions& options) {
    Scene scene;
    Parser parser(scene, displayName, baseDir, options);
    forEachLine(
        text, displayName, TextCheck::Utf8, [&](std::string_view line, int number) { parser.parseLine(line, number); },
        {}, kMaxSceneLineBytes);
    parser.finish();
    return scene;
}

Scene parseScene(std::istream& in, const std::string& displayName, const std::filesystem::path& baseDir,
                 const ParseOptions& options) {
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) throw Error(FileLoc{displayName}, "cannot read scene file");
    return parseSceneText(text, displayName, baseDir, options);
}

Scene loadScene(const std::filesystem::path& file, const ParseOptions& options) {
    if (isMeshFile(file)) return loadMeshScene(file, options);
    std::string whyNot;
    const std::optional<std::string> text = readFileBytes(file, whyNot);
    if (!text) throw Error(FileLoc{file.string()}, "cannot open scene file: " + whyNot);
    Scene scene = parseSceneText(*text, file.string(), file.parent_path(), options);
    scene.sourceFile = file;
    return scene;
}

}  // namespace vkray
