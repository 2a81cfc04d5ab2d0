// Small glTF 2.0 files written by the tests: a binary buffer of accessors built value by value, and
// the JSON around it, with the buffer embedded as base64, beside it as a .bin file, or as a .glb.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace vkray::test {

inline std::string base64(const std::string& bytes) {
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const size_t n = std::min<size_t>(3, bytes.size() - i);
        uint32_t v = 0;
        for (size_t k = 0; k < 3; ++k) v = v << 8 | (k < n ? uint8_t(bytes[i + k]) : 0u);
        for (size_t k = 0; k < 4; ++k) out += k <= n ? kAlphabet[(v >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

class GltfWriter {
public:
    // A VEC3 FLOAT accessor of `values` (x y z x y z ...), in its own buffer view.
    int vec3(const std::vector<float>& values) {
        return add(values.data(), values.size() * sizeof(float), values.size() / 3, 5126, "VEC3");
    }
    // A SCALAR accessor of unsigned shorts (5123) or unsigned ints (5125).
    int indices16(const std::vector<uint16_t>& v) { return add(v.data(), v.size() * 2, v.size(), 5123, "SCALAR"); }
    int indices32(const std::vector<uint32_t>& v) { return add(v.data(), v.size() * 4, v.size(), 5125, "SCALAR"); }
    // An accessor written as it is (for bad files), appended to the accessors.
    int rawAccessor(const std::string& json) {
        accessors_.push_back(json);
        return int(accessors_.size()) - 1;
    }

    const std::string& buffer() const { return bin_; }

    // The file's JSON: `rest` holds the other top-level members ("meshes": [...], "nodes": ...,
    // without braces); `uri` the buffer's (nothing: a GLB's buffer).
    std::string json(const std::string& rest, const std::string& uri) const {
        std::string s = "{\"asset\": {\"version\": \"2.0\"},\n\"buffers\": [{\"byteLength\": " +
                        std::to_string(bin_.size()) + (uri.empty() ? "" : ", \"uri\": \"" + uri + "\"") + "}],\n";
        s += "\"bufferViews\": [" + join(views_) + "],\n\"accessors\": [" + join(accessors_) + "]";
        if (!rest.empty()) s += ",\n" + rest;
        return s + "}\n";
    }
    std::string embedded(const std::string& rest) const {
        return json(rest, "data:application/octet-stream;base64," + base64(bin_));
    }
    // The GLB container (glTF 2.0, "Binary glTF Layout"): header, JSON chunk, BIN chunk.
    std::string glb(const std::string& rest) const {
        std::string j = json(rest, "");
        while (j.size() % 4) j += ' ';
        std::string b = bin_;
        while (b.size() % 4) b += '\0';
        std::string out = "glTF";
        word(out, 2);
        word(out, uint32_t(12 + 8 + j.size() + 8 + b.size()));
        word(out, uint32_t(j.size()));
        out += "JSON" + j;
        word(out, uint32_t(b.size()));
        out += std::string("BIN\0", 4) + b;
        return out;
    }

private:
    int add(const void* data, size_t bytes, size_t count, int componentType, const char* type) {
        while (bin_.size() % 4) bin_ += '\0';
        views_.push_back("{\"buffer\": 0, \"byteOffset\": " + std::to_string(bin_.size()) +
                         ", \"byteLength\": " + std::to_string(bytes) + "}");
        bin_.append(static_cast<const char*>(data), bytes);
        accessors_.push_back("{\"bufferView\": " + std::to_string(views_.size() - 1) + ", \"componentType\": " +
                             std::to_string(componentType) + ", \"count\": " + std::to_string(count) +
                             ", \"type\": \"" + type + "\"}");
        return int(accessors_.size()) - 1;
    }
    static std::string join(const std::vector<std::string>& items) {
        std::string s;
        for (const std::string& i : items) s += (s.empty() ? "" : ",\n ") + i;
        return s;
    }
    static void word(std::string& out, uint32_t v) {
        char raw[4];
        std::memcpy(raw, &v, 4);  // GLB is little-endian, as the machines the tests run on
        out.append(raw, 4);
    }

    std::string bin_;
    std::vector<std::string> views_, accessors_;
};

}  // namespace vkray::test
