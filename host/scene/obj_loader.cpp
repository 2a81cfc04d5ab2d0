#include "scene/obj_loader.h"

#include <optional>
#include <sstream>
#include <vector>

#include <tiny_obj_loader.h>

#include "core/error.h"
#include "scene/mtl_material.h"
#include "scene/obj_check.h"
#include "scene/text_input.h"

namespace vkray {
namespace {

// Reads each `mtllib` file next to the OBJ and checks it before tinyobjloader parses it; a missing
// one is an error here (tinyobjloader only warns and falls back to a default material).
class CheckedMtlReader : public tinyobj::MaterialReader {
public:
    CheckedMtlReader(const MeshRequest& request, std::string context)
        : request_(request), context_(std::move(context)) {}

    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* byName, std::string* warn, std::string* err) override {
        const std::filesystem::path file = (request_.file.parent_path() / name).lexically_normal();
        std::string whyNot;
        const std::optional<std::string> bytes = request_.readFile(file, whyNot);
        if (!bytes)
            throw Error(request_.requestedAt, "cannot open material library " + quoted(file.string(), 256) +
                                                  " named by 'mtllib' in '" + request_.displayName + "': " + whyNot);
        checkMtlText(*bytes, file.string(), context_);
        std::istringstream in{std::string(withoutUtf8Bom(*bytes))};
        tinyobj::LoadMtl(byName, materials, &in, warn, err);
        return true;
    }

private:
    const MeshRequest& request_;
    std::string context_;
};

// tinyobjloader warnings are errors (nothing is skipped silently), except these harmless ones.
bool isHarmlessWarning(std::string_view line) {
    return line.empty() || line == "." || line.starts_with("Both `d` and `Tr`") ||
           line.starts_with("Empty group name");
}

void throwOnDiagnostics(const MeshRequest& request, bool ok, const std::string& warn,
                        const std::string& err) {
    const std::string prefix = "in '" + request.displayName + "': ";
    std::istringstream lines(err);
    for (std::string line; std::getline(lines, line);)
        if (!line.empty()) throw Error(request.requestedAt, prefix + line);
    if (!ok) throw Error(request.requestedAt, prefix + "tinyobjloader failed to read the file");
    std::istringstream warnings(warn);
    for (std::string line; std::getline(warnings, line);)
        if (!isHarmlessWarning(line)) throw Error(request.requestedAt, prefix + line);
}

glm::dvec3 element(const std::vector<tinyobj::real_t>& values, int index) {
    return glm::dvec3(values[3 * size_t(index)], values[3 * size_t(index) + 1],
                      values[3 * size_t(index) + 2]);
}

// Scene material index per OBJ material, created on first use so unused MTL entries stay out.
class MaterialTable {
public:
    MaterialTable(const MeshRequest& request, const std::vector<tinyobj::material_t>& mtl, SceneBuilder& out)
        : request_(request), mtl_(mtl), out_(out), cache_(mtl.size()) {}

    uint32_t index(int objMaterial) {
        if (objMaterial < 0 || size_t(objMaterial) >= mtl_.size()) {
            if (fallback_ == kNone) fallback_ = out_.material(request_.defaultMaterial);
            return fallback_;
        }
        std::optional<uint32_t>& slot = cache_[size_t(objMaterial)];
        if (!slot) {
            const tinyobj::material_t& m = mtl_[size_t(objMaterial)];
            const std::string label = "material '" + m.name + "' of '" + request_.displayName + "'";
            slot = out_.material(materialFromMtl(m, request_.requestedAt, label));
        }
        return *slot;
    }

private:
    const MeshRequest& request_;
    const std::vector<tinyobj::material_t>& mtl_;
    SceneBuilder& out_;
    std::vector<std::optional<uint32_t>> cache_;
    // Not std::optional: GCC 12 warns falsely (-Wmaybe-uninitialized) on it here.
    static constexpr uint32_t kNone = ~0u;
    uint32_t fallback_ = kNone;
};

// Appends one tinyobjloader mesh (all triangles after triangulation) in face order.
void appendMesh(const MeshRequest& request, const tinyobj::attrib_t& attrib, const tinyobj::mesh_t& mesh,
                MaterialTable& table, SceneBuilder& out) {
    const auto fail = [&](const std::string& what) {
        throw Error(request.requestedAt, "in '" + request.displayName + "': " + what);
    };
    const int vertexCount = int(attrib.vertices.size() / 3);
    const int normalCount = int(attrib.normals.size() / 3);
    for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
        if (mesh.num_face_vertices[f] != 3) fail("a face was not triangulated");
        TriPoints p, n;
        bool normals = true;
        for (size_t k = 0; k < 3; ++k) {
            const tinyobj::index_t& idx = mesh.indices[3 * f + k];
            // checkObjText has range-checked every index; this guards the reads regardless.
            if (idx.vertex_index < 0 || idx.vertex_index >= vertexCount || idx.normal_index >= normalCount)
                fail("face index out of range");
            p[k] = request.toWorld.point(element(attrib.vertices, idx.vertex_index));
            if (idx.normal_index < 0) {
                normals = false;
                continue;
            }
            n[k] = request.toWorld.normal(element(attrib.normals, idx.normal_index));
        }
        const uint32_t material = table.index(mesh.material_ids.empty() ? -1 : mesh.material_ids[f]);
        if (!out.addShaded(p, normals ? std::optional<TriPoints>(n) : std::nullopt, material))
            fail("a transformed vertex does not fit a 32-bit float");
    }
}

}  // namespace

void loadObj(const MeshRequest& request, SceneBuilder& out) {
    std::string whyNot;
    std::optional<std::string> bytes = request.readFile(request.file, whyNot);
    if (!bytes) throw meshOpenError(request, "OBJ", whyNot);
    const std::string context = " (OBJ loaded at " + request.requestedAt.str() + ")";
    const ObjSummary summary = checkObjText(*bytes, request.displayName, context);
    // Before tinyobjloader spends time and memory on a mesh that cannot be kept.
    if (const auto problem = out.roomProblem(summary.triangles))
        throw Error(request.requestedAt, "in '" + request.displayName + "': " + *problem);

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    CheckedMtlReader mtlReader(request, context);
    // The BOM is stripped as checkObjText does, or tinyobjloader would skip a first `v` line and
    // every index after it would be off by one. The text moves into the stream: no copy.
    if (withoutUtf8Bom(*bytes).size() != bytes->size()) bytes->erase(0, 3);
    std::istringstream in(std::move(*bytes));
    const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &mtlReader,
                                     /*triangulate=*/true, /*default_vcols_fallback=*/false);
    throwOnDiagnostics(request, ok, warn, err);

    // tinyobjloader's ear clipping gives up on some polygons (degenerate, self-overlapping) and
    // drops what it has not cut yet without a warning: a face of n corners must make n - 2 triangles.
    uint64_t made = 0;
    for (const tinyobj::shape_t& shape : shapes) made += shape.mesh.num_face_vertices.size();
    if (made != summary.triangles)
        throw Error(request.requestedAt,
                    "in '" + request.displayName + "': tinyobjloader triangulated the faces into " + std::to_string(made) +
                        " triangles instead of " + std::to_string(summary.triangles) +
                        " (a degenerate or self-overlapping polygon); split such polygons into triangles");

    // Textures are not sampled (the Whitted model has none): say so once, as the glTF reader does.
    size_t textured = 0;
    for (const tinyobj::material_t& m : materials)
        textured += !m.diffuse_texname.empty() || !m.ambient_texname.empty() || !m.specular_texname.empty();
    if (textured > 0 && request.warn)
        request.warn("in '" + request.displayName + "': " + std::to_string(textured) +
                     " MTL material(s) with texture maps (map_Kd ...): not sampled, their Kd/Ka/Ks colours alone "
                     "colour the surfaces");
    MaterialTable table(request, materials, out);
    for (const tinyobj::shape_t& shape : shapes) appendMesh(request, attrib, shape.mesh, table, out);
}

}  // namespace vkray
