#include "scene/obj_check.h"

#include <algorithm>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "scene/text_input.h"

namespace vkray {
namespace {

struct Where {
    const std::string& file;
    const std::string& context;
    int line = 0;

    [[noreturn]] void fail(int col, const std::string& what) const {
        throw Error(FileLoc{file, line, col}, what + context);
    }
};

// The tokens after the keyword must be between `least` and `most` finite floats.
void checkNumbers(const std::vector<Token>& t, size_t least, size_t most, const Where& at) {
    const size_t n = t.size() - 1;
    const std::string key = quoted(t[0].text);
    if (n < least || n > most) {
        const std::string count =
            least == most ? std::to_string(least) : std::to_string(least) + " to " + std::to_string(most);
        at.fail(t[0].col, "expected " + count + " numbers after " + key + ", got " + std::to_string(n));
    }
    for (size_t i = 1; i < t.size(); ++i) {
        float value = 0.0f;
        const NumberStatus status = parseFloat(t[i].text, value);
        if (status != NumberStatus::Ok)
            at.fail(t[i].col,
                    describeNumberError(status, t[i].text, "value " + std::to_string(i) + " of " + key,
                                        "a number"));
    }
}

struct ObjCounts {
    int64_t v = 0, vt = 0, vn = 0;
};

// One index of a face corner: 1-based, or negative = relative to the elements defined so far
// (OBJ's rule, as tinyobjloader applies it). A positive index may refer forward in the file.
void checkIndex(std::string_view s, int64_t soFar, int64_t total, const char* noun, const char* plural,
                const Token& corner, const Where& at) {
    int64_t index = 0;
    if (parseInt(s, index) != NumberStatus::Ok)
        at.fail(corner.col, std::string("expected an integer ") + noun + " index in face corner " +
                                quoted(corner.text));
    const std::string defined = std::to_string(total) + " " + (total == 1 ? noun : plural);
    if (index == 0)
        at.fail(corner.col, std::string(noun) + " index 0 in face corner " + quoted(corner.text) +
                                ": OBJ indices start at 1");
    if (index < 0 && soFar + index < 0)
        at.fail(corner.col, "relative " + std::string(noun) + " index " + std::to_string(index) +
                                " reaches before the first one (" + std::to_string(soFar) +
                                " defined so far)");
    if (index > total)
        at.fail(corner.col, std::string(noun) + " index " + std::to_string(index) +
                                " out of range: the file defines " + defined);
}

void checkFace(const std::vector<Token>& t, const ObjCounts& soFar, const ObjCounts& total, const Where& at) {
    if (t.size() < 4)
        at.fail(t[0].col, "expected at least 3 vertices after 'f', got " + std::to_string(t.size() - 1));
    if (t.size() - 1 > kMaxObjFaceCorners)
        at.fail(t[0].col, "face of " + std::to_string(t.size() - 1) + " vertices, more than the " +
                              std::to_string(kMaxObjFaceCorners) + " vkray triangulates (split the polygon)");
    for (size_t i = 1; i < t.size(); ++i) {
        // v, v/vt, v//vn or v/vt/vn
        std::string_view rest = t[i].text;
        std::string_view parts[3];
        int count = 0;
        while (true) {
            const size_t slash = rest.find('/');
            if (count == 3)
                at.fail(t[i].col, "face corner " + quoted(t[i].text) + " has more than 3 parts");
            parts[count++] = rest.substr(0, slash);
            if (slash == std::string_view::npos) break;
            rest.remove_prefix(slash + 1);
        }
        checkIndex(parts[0], soFar.v, total.v, "vertex", "vertices", t[i], at);
        if (count > 1 && !parts[1].empty())
            checkIndex(parts[1], soFar.vt, total.vt, "texture coordinate", "texture coordinates", t[i], at);
        if (count > 2 && !parts[2].empty())
            checkIndex(parts[2], soFar.vn, total.vn, "normal", "normals", t[i], at);
    }
}

// OBJ statements that hold no surface vkray could render, so skipping them loses nothing: texture
// and parameter vertices, grouping, smoothing, lines and points, display and render attributes,
// tinyobjloader's tags. (v, vn, f, mtllib and usemtl are read.)
constexpr std::string_view kIgnoredStatements[] = {
    "vt", "vp", "g", "o", "s", "mg", "l", "p", "lod", "bevel", "c_interp", "d_interp",
    "shadow_obj", "trace_obj", "usemap", "maplib", "ctech", "stech", "t"};
// Statements of the OBJ specification that carry geometry tinyobjloader drops without a word:
// free-form curves and surfaces, `call` (include another file) and `csh` (run a shell command).
constexpr std::string_view kUnsupportedStatements[] = {
    "call", "csh", "cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv",
    "sp", "end", "con", "fo"};

bool oneOf(std::string_view key, std::span<const std::string_view> list) {
    return std::find(list.begin(), list.end(), key) != list.end();
}

void checkStatement(std::string_view key, std::string_view line, const Where& at) {
    if (key == "v" || key == "vn" || key == "f" || key == "mtllib" || key == "usemtl" ||
        oneOf(key, kIgnoredStatements))
        return;
    const int col = int(key.data() - line.data()) + 1;  // firstToken returns a view into the line
    if (key == "fo") at.fail(col, "'fo' (the old spelling of 'f') is not supported; write 'f'");
    if (oneOf(key, kUnsupportedStatements))
        at.fail(col, "OBJ statement " + quoted(key) +
                         " is not supported (vkray reads polygons: v, vn, vt, f); its geometry would be missing");
    at.fail(col, "unknown OBJ statement " + quoted(key) + " (is this an OBJ file?)");
}

}  // namespace

ObjSummary checkObjText(std::string_view text, const std::string& displayName, const std::string& context) {
    // Pass 1: statements, numbers, and the totals that positive (possibly forward) face indices may
    // reach. Lines are tokenized only when their keyword matters: OBJ files run to millions of lines.
    ObjCounts total;
    std::vector<Token> t;
    forEachLine(text, displayName, TextCheck::NoNul, [&](std::string_view line, int number) {
        const std::string_view key = firstToken(line);
        if (key.empty()) return;
        if (key == "v" || key == "vn") {
            tokenize(line, t);
            checkNumbers(t, 3, key == "v" ? 7 : 3, Where{displayName, context, number});
            ++(key == "v" ? total.v : total.vn);
        } else if (key == "vt") {
            ++total.vt;
        } else {
            checkStatement(key, line, Where{displayName, context, number});
        }
    }, context);
    // Pass 2: face indices, relative ones against the counts so far.
    ObjCounts soFar;
    ObjSummary summary;
    forEachLine(text, displayName, TextCheck::NoNul, [&](std::string_view line, int number) {
        const std::string_view key = firstToken(line);
        if (key == "v") {
            ++soFar.v;
        } else if (key == "vn") {
            ++soFar.vn;
        } else if (key == "vt") {
            ++soFar.vt;
        } else if (key == "f") {
            tokenize(line, t);
            checkFace(t, soFar, total, Where{displayName, context, number});
            summary.triangles += t.size() - 3;  // a polygon of n corners makes n - 2 triangles
        }
    }, context);
    return summary;
}

void checkMtlText(std::string_view text, const std::string& displayName, const std::string& context) {
    forEachLine(text, displayName, TextCheck::NoNul, [&](std::string_view line, int number) {
        // Tokenized only when the keyword matters: a 10 MB texture line costs nothing.
        const std::string_view key = firstToken(line);
        const bool colour = key == "Ka" || key == "Kd" || key == "Ks" || key == "Ke" || key == "Tf" || key == "Kt";
        const bool scalar = key == "Ns" || key == "Ni" || key == "d" || key == "Tr";
        if (!colour && !scalar) return;
        const std::vector<Token> t = tokenize(line);
        checkNumbers(t, colour ? 3 : 1, colour ? 3 : 1, Where{displayName, context, number});
    }, context);
}

}  // namespace vkray
