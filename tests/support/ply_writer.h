// PLY files written by the tests (ASCII, binary little- and big-endian) from vertices and faces, so
// that a test states its mesh once and reads it back in every encoding.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vkray::test {

enum class PlyEncoding { Ascii, LittleEndian, BigEndian };

struct PlyMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;                 // empty or one per position
    std::vector<std::array<uint8_t, 3>> colours;    // empty or one per position
    std::vector<std::vector<uint32_t>> faces;
};

// `value`'s bytes in the file's order.
template <class T>
void appendPlyValue(std::string& out, T value, PlyEncoding e) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    const bool swap = (e == PlyEncoding::BigEndian) == (std::endian::native == std::endian::little);
    if (swap)
        for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    out.append(raw, sizeof(T));
}

inline std::string plyFloat(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", double(v));  // 9 digits: every float reads back as itself
    return buf;
}

inline std::string writePly(const PlyMesh& m, PlyEncoding e) {
    std::string s = "ply\nformat ";
    s += e == PlyEncoding::Ascii ? "ascii" : e == PlyEncoding::LittleEndian ? "binary_little_endian" : "binary_big_endian";
    s += " 1.0\ncomment written by the vkray tests\nelement vertex " + std::to_string(m.positions.size()) +
         "\nproperty float x\nproperty float y\nproperty float z\n";
    if (!m.normals.empty()) s += "property float nx\nproperty float ny\nproperty float nz\n";
    if (!m.colours.empty()) s += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    s += "element face " + std::to_string(m.faces.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
    const auto floats = [&](const glm::vec3& v) {
        for (int k = 0; k < 3; ++k)
            if (e == PlyEncoding::Ascii)
                s += plyFloat(v[k]) + " ";
            else
                appendPlyValue(s, v[k], e);
    };
    for (size_t i = 0; i < m.positions.size(); ++i) {
        floats(m.positions[i]);
        if (!m.normals.empty()) floats(m.normals[i]);
        if (!m.colours.empty()) {
            for (const uint8_t c : m.colours[i]) {
                if (e == PlyEncoding::Ascii)
                    s += std::to_string(c) + " ";
                else
                    appendPlyValue(s, c, e);
            }
        }
        if (e == PlyEncoding::Ascii) s += "\n";
    }
    for (const std::vector<uint32_t>& f : m.faces) {
        if (e == PlyEncoding::Ascii) {
            s += std::to_string(f.size());
            for (const uint32_t i : f) s.append(" ").append(std::to_string(i));
            s += "\n";
            continue;
        }
        appendPlyValue(s, uint8_t(f.size()), e);
        for (const uint32_t i : f) appendPlyValue(s, int32_t(i), e);
    }
    return s;
}

// The triangles of `scene` (world positions: origin (0, 0, 0)) as an indexed mesh, equal corners
// sharing one vertex, faces in triangle order.
inline PlyMesh plyMeshOf(const Scene& scene) {
    PlyMesh m;
    std::map<std::array<float, 3>, uint32_t> index;
    const auto vertex = [&](const glm::vec3& p) {
        const auto [it, added] = index.try_emplace({p.x, p.y, p.z}, uint32_t(m.positions.size()));
        if (added) m.positions.push_back(p);
        return it->second;
    };
    for (const Triangle& t : scene.triangles) m.faces.push_back({vertex(t.p0), vertex(t.p1), vertex(t.p2)});
    return m;
}

}  // namespace vkray::test
