// A PLY reader of vkray's own rather than Assimp's: the format is a small header and a flat table of
// values, and Assimp's importer reads past truncated or inconsistent files where vkray must name the
// byte at fault, and brings a large library for one format.
#include "scene/ply_loader.h"

#include <array>
#include <cfloat>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "scene/ply_format.h"
#include "scene/text_input.h"

namespace vkray {
namespace {

// Where the values vkray uses sit in an element (-1: absent).
struct PlyColourProps {
    int r = -1, g = -1, b = -1;
    bool present() const { return r >= 0; }
};

// Finds r g b under `names` (all three or none; `element` is for the message).
PlyColourProps plyColourProps(const ply::Element& e, const char* const (&names)[3], const FileLoc& at,
                              const std::string& context) {
    PlyColourProps c{e.find(names[0]), e.find(names[1]), e.find(names[2])};
    const int found = (c.r >= 0) + (c.g >= 0) + (c.b >= 0);
    if (found != 0 && found != 3)
        throw Error(at, "element " + vkray::quoted(e.name) + " has only some of " + names[0] + " " + names[1] + " " +
                            names[2] + context);
    for (const int i : {c.r, c.g, c.b})
        if (i >= 0 && e.properties[size_t(i)].list)
            throw Error(at, "property " + vkray::quoted(e.properties[size_t(i)].name) + " of " + vkray::quoted(e.name) +
                                " is a list, expected a scalar" + context);
    return c;
}

class PlyReader {
public:
    PlyReader(const MeshRequest& request, SceneBuilder& out, std::string_view bytes)
        : request_(request), out_(out), context_(" (PLY loaded at " + request.requestedAt.str() + ")"),
          header_(ply::parseHeader(bytes, request.displayName, context_)),
          body_(bytes, header_, request.displayName, context_) {}

    void read();

private:
    FileLoc headerLine(int line) const { return FileLoc{request_.displayName, line, 0}; }
    int scalar(const ply::Element& e, std::string_view name, bool required) const;
    void record(const ply::Element& e, int64_t i, std::vector<double>& values, int list, std::vector<uint32_t>& corners);
    void vertices(const ply::Element& e);
    void faces(const ply::Element& e);
    glm::vec3 colour(const ply::Element& e, const PlyColourProps& c, const std::vector<double>& values);
    uint32_t material(const std::optional<glm::vec3>& diffuse);

    const MeshRequest& request_;
    SceneBuilder& out_;
    std::string context_;
    ply::Header header_;
    ply::Body body_;

    bool haveVertices_ = false;
    std::vector<glm::dvec3> positions_;  // world space
    std::vector<glm::dvec3> normals_;    // world space, unit or zero; empty without nx ny nz
    std::vector<glm::vec3> colours_;     // empty without vertex colours
    std::optional<uint32_t> plain_;      // request.defaultMaterial's index
    std::map<std::array<float, 3>, uint32_t> byColour_;
};

void PlyReader::read() {
    if (header_.strayLines > 0 && request_.warn)
        request_.warn("in '" + request_.displayName + "': " + std::to_string(header_.strayLines) +
                      " header line(s) with no PLY keyword read as comments (the first: line " +
                      std::to_string(header_.firstStrayLine) + ")");
    for (const ply::Element& e : header_.elements) {
        if (e.name == "vertex")
            vertices(e);
        else if (e.name == "face")
            faces(e);
        else
            body_.skip(e);
    }
    body_.finish();
}

int PlyReader::scalar(const ply::Element& e, std::string_view name, bool required) const {
    const int i = e.find(name);
    if (i < 0 && required)
        throw Error(headerLine(e.line), "element " + vkray::quoted(e.name) + " has no property " + vkray::quoted(name) + context_);
    if (i >= 0 && e.properties[size_t(i)].list)
        throw Error(headerLine(e.properties[size_t(i)].line),
                    "property " + vkray::quoted(name) + " of " + vkray::quoted(e.name) + " is a list, expected a scalar" + context_);
    return i;
}

glm::vec3 PlyReader::colour(const ply::Element& e, const PlyColourProps& c, const std::vector<double>& values) {
    glm::vec3 rgb;
    int k = 0;
    for (const int i : {c.r, c.g, c.b}) {
        const ply::Type t = e.properties[size_t(i)].type;
        const double v = values[size_t(i)] / ply::maxOf(t);
        if (!(v >= 0.0) || !std::isfinite(float(v)))
            body_.fail("colour " + vkray::quoted(e.properties[size_t(i)].name) + " is negative or not a finite 32-bit float",
                       false);
        rgb[k++] = float(v);
    }
    return rgb;
}

// Element i of `e`: its scalars into `values` (by property), its lists read past, but for the list
// property `list` (-1: none), the face's vertex indices, checked against the vertices read, into
// `corners`.
void PlyReader::record(const ply::Element& e, int64_t i, std::vector<double>& values, int list,
                       std::vector<uint32_t>& corners) {
    const int64_t vertexCount = int64_t(positions_.size());
    body_.begin(e, i);
    for (size_t k = 0; k < e.properties.size(); ++k) {
        const ply::Property& p = e.properties[k];
        if (!p.list) {
            values[k] = body_.value(p, p.type);
            continue;
        }
        const int64_t n = body_.listLength(p);
        if (int(k) == list) {
            if (n < 3) body_.fail("a face needs at least 3 vertices, got " + std::to_string(n));
            if (const auto problem = out_.roomProblem(uint64_t(n) - 2)) body_.fail(*problem);
            corners.clear();
        }
        for (int64_t j = 0; j < n; ++j) {
            const double index = body_.value(p, p.type);
            if (int(k) != list) continue;
            if (index < 0 || index >= double(vertexCount))
                body_.fail("vertex index " + std::to_string(int64_t(index)) + " out of range: the file has " +
                           std::to_string(vertexCount) + " vertices (0-based)");
            corners.push_back(uint32_t(index));
        }
    }
}

void PlyReader::vertices(const ply::Element& e) {
    const int x = scalar(e, "x", true), y = scalar(e, "y", true), z = scalar(e, "z", true);
    const int nx = scalar(e, "nx", false), ny = scalar(e, "ny", false), nz = scalar(e, "nz", false);
    const int normalProps = (nx >= 0) + (ny >= 0) + (nz >= 0);
    if (normalProps != 0 && normalProps != 3)
        throw Error(headerLine(e.line), "element 'vertex' has only some of nx ny nz" + context_);
    static const char* const kRgb[3] = {"red", "green", "blue"};
    static const char* const kDiffuseRgb[3] = {"diffuse_red", "diffuse_green", "diffuse_blue"};
    PlyColourProps c = plyColourProps(e, kRgb, headerLine(e.line), context_);
    if (!c.present()) c = plyColourProps(e, kDiffuseRgb, headerLine(e.line), context_);

    haveVertices_ = true;
    positions_.reserve(size_t(e.count));  // parseHeader bounded the count by the file's size
    if (nx >= 0) normals_.reserve(size_t(e.count));
    if (c.present()) colours_.reserve(size_t(e.count));
    std::vector<double> v(e.properties.size());
    std::vector<uint32_t> none;
    for (int64_t i = 0; i < e.count; ++i) {
        record(e, i, v, -1, none);
        const auto finite = [&](int a, int b, int d) {
            for (const int k : {a, b, d})
                if (!std::isfinite(v[size_t(k)]) || std::abs(v[size_t(k)]) > double(FLT_MAX))
                    body_.fail(vkray::quoted(e.properties[size_t(k)].name) + " is not a finite 32-bit float", false);
            return glm::dvec3(v[size_t(a)], v[size_t(b)], v[size_t(d)]);
        };
        positions_.push_back(request_.toWorld.point(finite(x, y, z)));
        if (nx >= 0) normals_.push_back(request_.toWorld.normal(finite(nx, ny, nz)));
        if (c.present()) colours_.push_back(colour(e, c, v));
    }
}

uint32_t PlyReader::material(const std::optional<glm::vec3>& diffuse) {
    if (!diffuse) {
        if (!plain_) plain_ = out_.material(request_.defaultMaterial);
        return *plain_;
    }
    const std::array<float, 3> key{diffuse->r, diffuse->g, diffuse->b};
    const auto it = byColour_.find(key);
    if (it != byColour_.end()) return it->second;
    Material m = request_.defaultMaterial;
    m.diffuse = *diffuse;
    return byColour_[key] = out_.material(m);
}

void PlyReader::faces(const ply::Element& e) {
    int list = e.find("vertex_indices");
    if (list < 0) list = e.find("vertex_index");
    if (list < 0)
        throw Error(headerLine(e.line), "element 'face' has no list property 'vertex_indices'" + context_);
    const ply::Property& indices = e.properties[size_t(list)];
    if (!indices.list || !ply::isInteger(indices.type))
        throw Error(headerLine(indices.line), "property " + vkray::quoted(indices.name) + " of 'face' must be a list of integers" + context_);
    if (e.count > 0 && !haveVertices_)
        throw Error(headerLine(e.line), "element 'face' comes before element 'vertex' (vkray reads them in that order)" + context_);
    static const char* const kRgb[3] = {"red", "green", "blue"};
    const PlyColourProps c = plyColourProps(e, kRgb, headerLine(e.line), context_);
    // Each face makes at least one triangle: refuse a mesh past the scene's limit before reading it.
    if (const auto problem = out_.roomProblem(uint64_t(e.count))) throw Error(headerLine(e.line), *problem + context_);
    out_.reserve(size_t(e.count));

    std::vector<double> v(e.properties.size());
    std::vector<uint32_t> corners;
    for (int64_t i = 0; i < e.count; ++i) {
        record(e, i, v, list, corners);
        std::optional<glm::vec3> diffuse;
        if (c.present())
            diffuse = colour(e, c, v);
        else if (!colours_.empty())
            diffuse = colours_[corners[0]];
        const uint32_t m = material(diffuse);
        // A fan around the first corner, as for OFF: predictable, and exact for convex faces.
        for (size_t k = 1; k + 1 < corners.size(); ++k) {
            const TriPoints p{positions_[corners[0]], positions_[corners[k]], positions_[corners[k + 1]]};
            std::optional<TriPoints> n;
            if (!normals_.empty()) n = TriPoints{normals_[corners[0]], normals_[corners[k]], normals_[corners[k + 1]]};
            if (!out_.addShaded(p, n, m)) body_.fail("a transformed vertex does not fit a 32-bit float", false);
        }
    }
}

}  // namespace

void loadPly(const MeshRequest& request, SceneBuilder& out) {
    std::string whyNot;
    const std::optional<std::string> bytes = request.readFile(request.file, whyNot);
    if (!bytes) throw meshOpenError(request, "PLY", whyNot);
    PlyReader(request, out, *bytes).read();
}

}  // namespace vkray
