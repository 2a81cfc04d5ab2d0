#include "scene/gltf_json_check.h"

#include <cstdint>
#include <cstring>
#include <span>

#include <nlohmann/json.hpp>

namespace vkray {
namespace {

using nlohmann::json;

enum class JsonKind { Object, String, Number, Index, ObjectArray, IndexArray, NumberArray, StringArray, IndexObject };

// A member of a glTF object that vkray reads, its JSON type (glTF 2.0 specification, "JSON Schema
// Reference"), and for objects the members of theirs that vkray reads.
struct JsonMember {
    std::string_view name;
    JsonKind kind;
    std::span<const JsonMember> members = {};
};

// A texture reference: not sampled, but a wrong one is a broken file all the same.
constexpr JsonMember kTextureInfoMembers[] = {{"index", JsonKind::Index}, {"extensions", JsonKind::Object}};
constexpr JsonMember kPbrMembers[] = {
    {"baseColorFactor", JsonKind::NumberArray}, {"metallicFactor", JsonKind::Number},
    {"roughnessFactor", JsonKind::Number}, {"baseColorTexture", JsonKind::Object, kTextureInfoMembers},
    {"metallicRoughnessTexture", JsonKind::Object, kTextureInfoMembers}};
constexpr JsonMember kMaterialMembers[] = {
    {"name", JsonKind::String}, {"pbrMetallicRoughness", JsonKind::Object, kPbrMembers},
    {"emissiveFactor", JsonKind::NumberArray}, {"extensions", JsonKind::Object},
    {"normalTexture", JsonKind::Object, kTextureInfoMembers}, {"occlusionTexture", JsonKind::Object, kTextureInfoMembers},
    {"emissiveTexture", JsonKind::Object, kTextureInfoMembers}};
constexpr JsonMember kPrimitiveMembers[] = {
    {"attributes", JsonKind::IndexObject}, {"indices", JsonKind::Index}, {"material", JsonKind::Index},
    {"mode", JsonKind::Index}, {"targets", JsonKind::ObjectArray}};
constexpr JsonMember kMeshMembers[] = {{"name", JsonKind::String}, {"primitives", JsonKind::ObjectArray, kPrimitiveMembers}};
constexpr JsonMember kNodeMembers[] = {
    {"name", JsonKind::String},          {"mesh", JsonKind::Index},         {"children", JsonKind::IndexArray},
    {"matrix", JsonKind::NumberArray},   {"translation", JsonKind::NumberArray}, {"rotation", JsonKind::NumberArray},
    {"scale", JsonKind::NumberArray}};
constexpr JsonMember kSceneMembers[] = {{"name", JsonKind::String}, {"nodes", JsonKind::IndexArray}};
constexpr JsonMember kAccessorMembers[] = {
    {"bufferView", JsonKind::Index}, {"byteOffset", JsonKind::Index}, {"componentType", JsonKind::Index},
    {"count", JsonKind::Index}, {"type", JsonKind::String}, {"sparse", JsonKind::Object}};
constexpr JsonMember kBufferViewMembers[] = {
    {"buffer", JsonKind::Index}, {"byteOffset", JsonKind::Index}, {"byteLength", JsonKind::Index},
    {"byteStride", JsonKind::Index}};
constexpr JsonMember kBufferMembers[] = {{"byteLength", JsonKind::Index}, {"uri", JsonKind::String}};
constexpr JsonMember kTextureMembers[] = {{"sampler", JsonKind::Index}, {"source", JsonKind::Index}};
constexpr JsonMember kTopMembers[] = {
    {"asset", JsonKind::Object},
    {"scene", JsonKind::Index},
    {"scenes", JsonKind::ObjectArray, kSceneMembers},
    {"nodes", JsonKind::ObjectArray, kNodeMembers},
    {"meshes", JsonKind::ObjectArray, kMeshMembers},
    {"materials", JsonKind::ObjectArray, kMaterialMembers},
    {"accessors", JsonKind::ObjectArray, kAccessorMembers},
    {"bufferViews", JsonKind::ObjectArray, kBufferViewMembers},
    {"buffers", JsonKind::ObjectArray, kBufferMembers},
    {"textures", JsonKind::ObjectArray, kTextureMembers},
    {"images", JsonKind::ObjectArray},
    {"extensionsUsed", JsonKind::StringArray},
    {"extensionsRequired", JsonKind::StringArray},
};

std::string jsonTypeName(const json& v) {
    switch (v.type()) {
        case json::value_t::object: return "an object";
        case json::value_t::array: return "an array";
        case json::value_t::string: return "a string";
        case json::value_t::boolean: return "a boolean";
        case json::value_t::null: return "null";
        case json::value_t::number_integer:
        case json::value_t::number_unsigned: return "the integer " + v.dump();
        case json::value_t::number_float: return "the number " + v.dump();
        default: return "not a value";
    }
}

// An index or count: tinygltf keeps indices in ints, so one of 2^31 or more would not survive.
bool isGltfIndex(const json& v) {
    if (v.is_number_unsigned()) return v.get<uint64_t>() <= uint64_t(INT32_MAX);
    return v.is_number_integer() && v.get<int64_t>() >= 0 && v.get<int64_t>() <= INT32_MAX;
}

class JsonTypeCheck {
public:
    std::optional<std::string> problem;

    void object(const json& o, std::span<const JsonMember> members, const std::string& path) {
        for (const JsonMember& m : members) {
            if (problem) return;
            const auto it = o.find(m.name);
            if (it != o.end()) member(*it, m, path.empty() ? std::string(m.name) : path + "." + std::string(m.name));
        }
    }

private:
    void expect(bool ok, const json& v, const std::string& path, const char* expected) {
        if (!ok && !problem) problem = path + " is " + jsonTypeName(v) + ", expected " + expected;
    }

    void member(const json& v, const JsonMember& m, const std::string& path) {
        switch (m.kind) {
            case JsonKind::Object:
                expect(v.is_object(), v, path, "an object");
                if (v.is_object()) object(v, m.members, path);
                return;
            case JsonKind::String: return expect(v.is_string(), v, path, "a string");
            case JsonKind::Number: return expect(v.is_number(), v, path, "a number");
            case JsonKind::Index: return expect(isGltfIndex(v), v, path, "a non-negative integer below 2^31");
            case JsonKind::IndexObject:
                expect(v.is_object(), v, path, "an object");
                if (v.is_object())
                    for (const auto& [key, value] : v.items())
                        expect(isGltfIndex(value), value, path + "." + key, "a non-negative integer below 2^31");
                return;
            default: return array(v, m, path);
        }
    }

    void array(const json& v, const JsonMember& m, const std::string& path) {
        expect(v.is_array(), v, path, "an array");
        if (!v.is_array()) return;
        for (size_t i = 0; i < v.size() && !problem; ++i) {
            const json& item = v[i];
            const std::string at = path + "[" + std::to_string(i) + "]";
            if (m.kind == JsonKind::ObjectArray) {
                expect(item.is_object(), item, at, "an object");
                if (item.is_object()) object(item, m.members, at);
            } else if (m.kind == JsonKind::IndexArray) {
                expect(isGltfIndex(item), item, at, "a non-negative integer below 2^31");
            } else if (m.kind == JsonKind::NumberArray) {
                expect(item.is_number(), item, at, "a number");
            } else {
                expect(item.is_string(), item, at, "a string");
            }
        }
    }
};

uint32_t glbWord(std::string_view bytes, size_t at) {
    uint32_t v;
    std::memcpy(&v, bytes.data() + at, 4);  // little-endian, as the glTF reader requires of its host
    return v;
}

}  // namespace

std::optional<std::string_view> gltfJsonText(std::string_view bytes) {
    if (!bytes.starts_with("glTF")) return bytes;
    // Binary glTF: a 12-byte header (magic, version, length), then chunks of (length, type, data).
    if (bytes.size() < 20) return std::nullopt;
    const uint32_t length = glbWord(bytes, 12);
    if (length > bytes.size() - 20 || bytes.substr(16, 4) != "JSON") return std::nullopt;
    return bytes.substr(20, length);
}

GltfJsonCheck checkGltfJson(std::string_view text) {
    GltfJsonCheck result;
    const json doc = json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
    if (doc.is_discarded()) return result;  // tinygltf reports the syntax error
    if (!doc.is_object()) {
        result.typeProblem = "the JSON is " + jsonTypeName(doc) + ", expected an object";
        return result;
    }
    // glTF 1.0 (a different schema: scenes and meshes by name) fails the 2.0 checks below in some
    // member or other; its version says what is wrong at once.
    if (const auto asset = doc.find("asset"); asset != doc.end() && asset->is_object()) {
        const auto version = asset->find("version");
        if (version != asset->end() && version->is_string() && !version->get<std::string>().starts_with("2.")) {
            result.typeProblem = "glTF version '" + version->get<std::string>() + "': vkray reads glTF 2.0";
            return result;
        }
    }
    JsonTypeCheck check;
    check.object(doc, kTopMembers, "");
    result.typeProblem = check.problem;
    if (!check.problem && doc.contains("extensionsRequired"))
        for (const json& e : doc["extensionsRequired"]) result.extensionsRequired.push_back(e.get<std::string>());
    return result;
}

}  // namespace vkray
