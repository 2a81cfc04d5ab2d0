#include "scene/gltf_loader.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "core/error.h"
#include "scene/gltf_json_check.h"
#include "scene/gltf_material.h"
#include "scene/text_input.h"
#include "scene/tinygltf_config.h"

namespace vkray {
namespace {

// glTF buffers are little-endian; their values are copied as they are.
static_assert(std::endian::native == std::endian::little, "the glTF reader assumes a little-endian host");

// Required extensions that change nothing vkray reads: texture coordinates are not sampled.
constexpr std::string_view kGltfHarmlessExtensions[] = {"KHR_texture_transform"};

// What the file-system callbacks of tinygltf need: the request's reader, and the first failure.
struct GltfFiles {
    const MeshRequest* request;
    std::string error;
};

tinygltf::FsCallbacks gltfCallbacks(GltfFiles& files) {
    tinygltf::FsCallbacks fs;
    // Whether a file exists is what reading it says: one read, and its reason when it fails.
    fs.FileExists = [](const std::string&, void*) { return true; };
    fs.ExpandFilePath = [](const std::string& path, void*) { return path; };
    fs.ReadWholeFile = [](std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
        GltfFiles& f = *static_cast<GltfFiles*>(user);
        std::string whyNot;
        const std::optional<std::string> bytes = f.request->readFile(path, whyNot);
        if (!bytes) {
            if (f.error.empty()) f.error = "cannot open buffer file " + vkray::quoted(path, 256) + ": " + whyNot;
            if (err) *err += f.error + "\n";
            return false;
        }
        out->assign(bytes->begin(), bytes->end());
        return true;
    };
    fs.WriteWholeFile = [](std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
        if (err) *err += "vkray writes no glTF files\n";
        return false;
    };
    fs.user_data = &files;
    return fs;
}

// Images are never decoded: vkray samples no textures.
bool skipGltfImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

std::string firstLine(const std::string& s) {
    const size_t start = s.find_first_not_of("\r\n");
    if (start == std::string::npos) return {};
    return s.substr(start, s.find_first_of("\r\n", start) - start);
}

class GltfReader {
public:
    GltfReader(const MeshRequest& request, SceneBuilder& out)
        : request_(request), out_(out), context_(" (glTF loaded at " + request.requestedAt.str() + ")") {}

    void read();

private:
    [[noreturn]] void fail(const std::string& what) const {
        throw Error(FileLoc{request_.displayName}, what + context_);
    }
    void load();
    void checkExtensions(const std::vector<std::string>& required) const;
    std::vector<int> roots() const;
    glm::dmat4 localMatrix(const tinygltf::Node& n, int index) const;
    void walk(int root, std::vector<char>& seen);
    void mesh(int index, const glm::dmat4& toWorld);
    void primitive(const tinygltf::Primitive& p, const Transform& toWorld, const std::string& name);
    struct View;
    View accessor(int index, int type, std::initializer_list<int> componentTypes, const std::string& role) const;
    std::vector<uint32_t> vertexSequence(const tinygltf::Primitive& p, size_t vertexCount, const std::string& name) const;
    uint32_t material(int index);
    void warnings() const;

    const MeshRequest& request_;
    SceneBuilder& out_;
    std::string context_;
    tinygltf::Model model_;
    std::vector<std::optional<uint32_t>> materials_;
    std::optional<uint32_t> plain_;
    std::vector<int64_t> meshUses_, meshTriangles_;
    int64_t pointsAndLines_ = 0;
    bool morphTargets_ = false;
};

void GltfReader::load() {
    std::string whyNot;
    const std::optional<std::string> bytes = request_.readFile(request_.file, whyNot);
    if (!bytes) throw meshOpenError(request_, "glTF", whyNot);
    if (const std::optional<std::string_view> json = gltfJsonText(*bytes)) {
        const GltfJsonCheck check = checkGltfJson(*json);
        if (check.typeProblem) fail(*check.typeProblem);
        checkExtensions(check.extensionsRequired);
    }
    GltfFiles files{&request_, {}};
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks(gltfCallbacks(files));
    loader.SetImageLoader(&skipGltfImage, nullptr);
    std::string err, warn;
    const std::string baseDir = request_.file.parent_path().string();
    // By content, not extension: a .gltf that holds GLB reads as GLB.
    const bool binary = bytes->size() >= 4 && bytes->compare(0, 4, "glTF") == 0;
    const bool ok =
        binary ? loader.LoadBinaryFromMemory(&model_, &err, &warn, reinterpret_cast<const unsigned char*>(bytes->data()),
                                             unsigned(bytes->size()), baseDir)
               : loader.LoadASCIIFromString(&model_, &err, &warn, bytes->data(), unsigned(bytes->size()), baseDir);
    if (!files.error.empty()) fail(files.error);
    if (!ok || !firstLine(err).empty())
        fail(firstLine(err).empty() ? std::string("tinygltf cannot read the file") : "tinygltf: " + firstLine(err));
}

void GltfReader::checkExtensions(const std::vector<std::string>& required) const {
    for (const std::string& ext : required) {
        const auto known = gltfMaterialExtensions();
        if (std::find(known.begin(), known.end(), ext) != known.end() ||
            std::find(std::begin(kGltfHarmlessExtensions), std::end(kGltfHarmlessExtensions), ext) !=
                std::end(kGltfHarmlessExtensions))
            continue;
        std::string list;
        for (const std::string_view k : known) list += (list.empty() ? "" : ", ") + std::string(k);
        fail("the file requires the extension " + vkray::quoted(ext) + ", which vkray does not read (it reads " + list + ")");
    }
}

std::vector<int> GltfReader::roots() const {
    if (!model_.scenes.empty()) {
        const int s = model_.defaultScene < 0 ? 0 : model_.defaultScene;
        if (size_t(s) >= model_.scenes.size())
            fail("the default scene " + std::to_string(s) + " is out of range: the file has " +
                 std::to_string(model_.scenes.size()) + " scenes");
        return model_.scenes[size_t(s)].nodes;
    }
    // No scene: every node that is no node's child (the file's node forest).
    std::vector<char> child(model_.nodes.size(), 0);
    for (const tinygltf::Node& n : model_.nodes)
        for (const int c : n.children)
            if (c >= 0 && size_t(c) < child.size()) child[size_t(c)] = 1;
    std::vector<int> r;
    for (size_t i = 0; i < child.size(); ++i)
        if (!child[i]) r.push_back(int(i));
    return r;
}

glm::dmat4 GltfReader::localMatrix(const tinygltf::Node& n, int index) const {
    const auto need = [&](const std::vector<double>& v, size_t size, const char* what) {
        if (!v.empty() && v.size() != size)
            fail("node " + std::to_string(index) + ": its " + what + " has " + std::to_string(v.size()) +
                 " numbers, expected " + std::to_string(size));
        return !v.empty();
    };
    if (need(n.matrix, 16, "matrix")) {
        glm::dmat4 m;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = n.matrix[size_t(4 * c + r)];  // column-major, as glm
        return m;
    }
    glm::dmat4 m(1.0);
    if (need(n.translation, 3, "translation"))
        m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
    if (need(n.rotation, 4, "rotation")) {
        const glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);  // stored x y z w
        const double len = glm::length(q);
        if (!(len > 0.0) || !std::isfinite(len)) fail("node " + std::to_string(index) + ": its rotation is not a quaternion");
        m = m * glm::mat4_cast(q / len);
    }
    if (need(n.scale, 3, "scale")) m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
    return m;
}

// Depth first, children in file order, with an explicit stack: a chain of nodes as deep as the
// file is long must not exhaust the call stack.
void GltfReader::walk(int root, std::vector<char>& seen) {
    std::vector<std::pair<int, glm::dmat4>> stack{{root, request_.toWorld.matrix()}};
    while (!stack.empty()) {
        const auto [index, parent] = stack.back();
        stack.pop_back();
        if (index < 0 || size_t(index) >= model_.nodes.size())
            fail("node index " + std::to_string(index) + " is out of range: the file has " +
                 std::to_string(model_.nodes.size()) + " nodes");
        if (seen[size_t(index)])
            fail("node " + std::to_string(index) + " is reached twice (a cycle, or a node with two parents)");
        seen[size_t(index)] = 1;
        const tinygltf::Node& n = model_.nodes[size_t(index)];
        const glm::dmat4 world = parent * localMatrix(n, index);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (!std::isfinite(world[c][r])) fail("node " + std::to_string(index) + ": its transform is not finite");
        if (n.mesh >= 0) mesh(n.mesh, world);
        for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) stack.emplace_back(*c, world);
    }
}

void GltfReader::mesh(int index, const glm::dmat4& toWorld) {
    if (size_t(index) >= model_.meshes.size())
        fail("mesh index " + std::to_string(index) + " is out of range: the file has " +
             std::to_string(model_.meshes.size()) + " meshes");
    const Transform t(toWorld);
    ++meshUses_[size_t(index)];
    if (!t.isFinite()) return;  // singular (a zero scale): the mesh has no area
    const tinygltf::Mesh& m = model_.meshes[size_t(index)];
    const int64_t before = int64_t(out_.scene().triangles.size());
    for (size_t p = 0; p < m.primitives.size(); ++p)
        primitive(m.primitives[p], t, "mesh " + std::to_string(index) + " primitive " + std::to_string(p));
    meshTriangles_[size_t(index)] = int64_t(out_.scene().triangles.size()) - before;
}

struct GltfReader::View {
    const unsigned char* data = nullptr;
    size_t count = 0, stride = 0;
    int componentType = 0;

    glm::dvec3 vec3(size_t i) const {
        float v[3];
        std::memcpy(v, data + i * stride, sizeof v);
        return glm::dvec3(v[0], v[1], v[2]);
    }
    uint32_t index(size_t i) const {
        const unsigned char* p = data + i * stride;
        switch (componentType) {
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                uint16_t v;
                std::memcpy(&v, p, sizeof v);
                return v;
            }
            default: {
                uint32_t v;
                std::memcpy(&v, p, sizeof v);
                return v;
            }
        }
    }
};

GltfReader::View GltfReader::accessor(int index, int type, std::initializer_list<int> componentTypes,
                                      const std::string& role) const {
    const std::string name = "accessor " + std::to_string(index) + " (" + role + ")";
    if (index < 0 || size_t(index) >= model_.accessors.size())
        fail(name + " is out of range: the file has " + std::to_string(model_.accessors.size()) + " accessors");
    const tinygltf::Accessor& a = model_.accessors[size_t(index)];
    if (a.sparse.isSparse) fail(name + " is sparse, which vkray does not read");
    if (a.type != type || std::find(componentTypes.begin(), componentTypes.end(), a.componentType) == componentTypes.end())
        fail(name + " has the wrong type (type " + std::to_string(a.type) + ", componentType " +
             std::to_string(a.componentType) + ")");
    if (a.bufferView < 0 || size_t(a.bufferView) >= model_.bufferViews.size())
        fail(name + ": its bufferView " + std::to_string(a.bufferView) + " is out of range or absent");
    const tinygltf::BufferView& bv = model_.bufferViews[size_t(a.bufferView)];
    if (bv.buffer < 0 || size_t(bv.buffer) >= model_.buffers.size())
        fail("bufferView " + std::to_string(a.bufferView) + ": its buffer " + std::to_string(bv.buffer) + " is out of range");
    const size_t bufferBytes = model_.buffers[size_t(bv.buffer)].data.size();
    if (bv.byteLength > bufferBytes || bv.byteOffset > bufferBytes - bv.byteLength)
        fail("bufferView " + std::to_string(a.bufferView) + " (bytes " + std::to_string(bv.byteOffset) + " + " +
             std::to_string(bv.byteLength) + ") reaches past its buffer of " + std::to_string(bufferBytes) + " bytes");
    const size_t element = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType))) *
                           size_t(tinygltf::GetNumComponentsInType(uint32_t(a.type)));
    const size_t stride = bv.byteStride ? bv.byteStride : element;
    if (stride < element) fail("bufferView " + std::to_string(a.bufferView) + ": its byteStride is smaller than an element of " + name);
    const bool fits = a.count == 0 || (a.byteOffset <= bv.byteLength && (a.count - 1) <= bv.byteLength / stride &&
                                       element <= bv.byteLength - a.byteOffset &&
                                       (a.count - 1) * stride <= bv.byteLength - a.byteOffset - element);
    if (!fits)
        fail(name + ": its " + std::to_string(a.count) + " elements from byte " + std::to_string(a.byteOffset) +
             " reach past its bufferView " + std::to_string(a.bufferView) + " of " + std::to_string(bv.byteLength) + " bytes");
    return View{model_.buffers[size_t(bv.buffer)].data.data() + bv.byteOffset + a.byteOffset, a.count, stride, a.componentType};
}

// The primitive's vertex indices in drawing order: its index accessor, or 0, 1, 2, ...
std::vector<uint32_t> GltfReader::vertexSequence(const tinygltf::Primitive& p, size_t vertexCount,
                                                 const std::string& name) const {
    std::vector<uint32_t> seq;
    if (p.indices < 0) {
        seq.resize(vertexCount);
        for (size_t i = 0; i < vertexCount; ++i) seq[i] = uint32_t(i);
        return seq;
    }
    const View v = accessor(p.indices, TINYGLTF_TYPE_SCALAR,
                            {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                            "indices of " + name);
    seq.resize(v.count);
    for (size_t i = 0; i < v.count; ++i) {
        seq[i] = v.index(i);
        if (seq[i] >= vertexCount)
            fail(name + ": index " + std::to_string(i) + " of accessor " + std::to_string(p.indices) + " is " +
                 std::to_string(seq[i]) + ", out of range: POSITION has " + std::to_string(vertexCount) + " vertices");
    }
    return seq;
}

void GltfReader::primitive(const tinygltf::Primitive& p, const Transform& toWorld, const std::string& name) {
    if (p.mode >= TINYGLTF_MODE_POINTS && p.mode <= TINYGLTF_MODE_LINE_STRIP) {
        ++pointsAndLines_;
        return;
    }
    if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP && p.mode != TINYGLTF_MODE_TRIANGLE_FAN)
        fail(name + ": unknown mode " + std::to_string(p.mode));
    if (!p.targets.empty()) morphTargets_ = true;
    const auto position = p.attributes.find("POSITION");
    if (position == p.attributes.end()) fail(name + " has no POSITION attribute");
    const View pv = accessor(position->second, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, "POSITION of " + name);
    std::vector<glm::dvec3> points(pv.count), normals;
    for (size_t i = 0; i < pv.count; ++i) {
        const glm::dvec3 v = pv.vec3(i);
        if (!std::isfinite(v.x + v.y + v.z)) fail(name + ": POSITION " + std::to_string(i) + " is not finite");
        points[i] = toWorld.point(v);
    }
    if (const auto normal = p.attributes.find("NORMAL"); normal != p.attributes.end()) {
        const View nv = accessor(normal->second, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, "NORMAL of " + name);
        if (nv.count != pv.count)
            fail(name + ": NORMAL has " + std::to_string(nv.count) + " elements, POSITION " + std::to_string(pv.count));
        normals.resize(nv.count);
        for (size_t i = 0; i < nv.count; ++i) {
            const glm::dvec3 n = nv.vec3(i);
            normals[i] = std::isfinite(n.x + n.y + n.z) ? toWorld.normal(n) : glm::dvec3(0.0);
        }
    }
    const std::vector<uint32_t> seq = vertexSequence(p, pv.count, name);
    if (p.mode == TINYGLTF_MODE_TRIANGLES && seq.size() % 3 != 0)
        fail(name + ": a triangle list of " + std::to_string(seq.size()) + " vertices (not a multiple of 3)");
    const size_t triangles = p.mode == TINYGLTF_MODE_TRIANGLES ? seq.size() / 3 : seq.size() < 3 ? 0 : seq.size() - 2;
    if (const auto problem = out_.roomProblem(triangles)) fail(name + ": " + *problem);
    const uint32_t m = material(p.material);
    for (size_t i = 0; i < triangles; ++i) {
        // The corners of the glTF 2.0 specification (3.7.2.1, "Topology types").
        std::array<uint32_t, 3> c;
        if (p.mode == TINYGLTF_MODE_TRIANGLES)
            c = {seq[3 * i], seq[3 * i + 1], seq[3 * i + 2]};
        else if (p.mode == TINYGLTF_MODE_TRIANGLE_STRIP)
            c = {seq[i], seq[i + 1 + i % 2], seq[i + 2 - i % 2]};
        else
            c = {seq[i + 1], seq[i + 2], seq[0]};
        const TriPoints t{points[c[0]], points[c[1]], points[c[2]]};
        std::optional<TriPoints> n;
        if (!normals.empty()) n = TriPoints{normals[c[0]], normals[c[1]], normals[c[2]]};
        if (!out_.addShaded(t, n, m))
            fail(name + ": a transformed vertex does not fit a 32-bit float");
    }
}

uint32_t GltfReader::material(int index) {
    if (index < 0) {
        if (!plain_) plain_ = out_.material(request_.defaultMaterial);
        return *plain_;
    }
    if (size_t(index) >= model_.materials.size())
        fail("material index " + std::to_string(index) + " is out of range: the file has " +
             std::to_string(model_.materials.size()) + " materials");
    std::optional<uint32_t>& slot = materials_[size_t(index)];
    if (!slot) {
        const tinygltf::Material& gm = model_.materials[size_t(index)];
        const std::string label = "material " + vkray::quoted(gm.name) + " (" + std::to_string(index) + ") of '" +
                                  request_.displayName + "'";
        slot = out_.material(materialFromGltf(gm, request_.defaultMaterial, FileLoc{request_.displayName}, label));
    }
    return *slot;
}

void GltfReader::warnings() const {
    if (!request_.warn) return;
    const std::string in = "in '" + request_.displayName + "': ";
    if (pointsAndLines_ > 0)
        request_.warn(in + std::to_string(pointsAndLines_) + " primitives of points or lines skipped (vkray draws triangles)");
    if (!model_.textures.empty())
        request_.warn(in + std::to_string(model_.textures.size()) +
                      " textures not sampled: the materials' factors alone colour the surfaces");
    if (!model_.skins.empty() || morphTargets_)
        request_.warn(in + "skins and morph targets ignored: meshes are drawn in their rest pose");
    int64_t shared = 0, copies = 0, copied = 0;
    for (size_t m = 0; m < meshUses_.size(); ++m)
        if (meshUses_[m] > 1) {
            ++shared;
            copies += meshUses_[m];
            copied += meshUses_[m] * meshTriangles_[m];
        }
    if (shared > 0)
        request_.warn(in + std::to_string(shared) + " meshes drawn by several nodes are copied per node: " +
                      std::to_string(copies) + " instances, " + std::to_string(copied) + " triangles");
}

void GltfReader::read() {
    load();
    checkExtensions(model_.extensionsRequired);  // also a GLB whose JSON checkGltfJson did not see
    materials_.resize(model_.materials.size());
    meshUses_.assign(model_.meshes.size(), 0);
    meshTriangles_.assign(model_.meshes.size(), 0);
    std::vector<char> seen(model_.nodes.size(), 0);
    for (const int root : roots()) walk(root, seen);
    warnings();
}

}  // namespace

void loadGltf(const MeshRequest& request, SceneBuilder& out) { GltfReader(request, out).read(); }

}  // namespace vkray
