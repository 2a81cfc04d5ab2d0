#include "scene/obj_check.h"

#include <cstdint>
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
    const std::string key(t[0].text);
    if (n < least || n > most) {
        const std::string count =
            least == most ? std::to_string(least) : std::to_string(least) + " to " + std::to_string(most);
        at.fail(t[0].col, "expected " + count + " numbers after '" + key + "', got " + std::to_string(n));
    }
    for (size_t i = 1; i < t.size(); ++i) {
        float value = 0.0f;
        const NumberStatus status = parseFloat(t[i].text, value);
        if (status != NumberStatus::Ok)
            at.fail(t[i].col,
                    describeNumberError(status, t[i].text, "value " + std::to_string(i) + " of '" + key + "'",
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
        at.fail(corner.col, std::string("expected an integer ") + noun + " index in face corner '" +
                                std::string(corner.text) + "'");
    const std::string defined = std::to_string(total) + " " + (total == 1 ? noun : plural);
    if (index == 0)
        at.fail(corner.col, std::string(noun) + " index 0 in face corner '" + std::string(corner.text) +
                                "': OBJ indices start at 1");
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
    for (size_t i = 1; i < t.size(); ++i) {
        // v, v/vt, v//vn or v/vt/vn
        std::string_view rest = t[i].text;
        std::string_view parts[3];
        int count = 0;
        while (true) {
            const size_t slash = rest.find('/');
            if (count == 3)
                at.fail(t[i].col, "face corner '" + std::string(t[i].text) + "' has more than 3 parts");
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

}  // namespace

void checkObjText(std::string_view text, const std::string& displayName, const std::string& context) {
    // Pass 1: numbers, and the totals that positive (possibly forward) face indices may reach.
    // Lines are tokenized only when their keyword matters: OBJ files run to millions of lines.
    ObjCounts total;
    std::vector<Token> t;
    forEachLine(text, displayName, TextCheck::NoNul, [&](std::string_view line, int number) {
        const std::string_view key = firstToken(line);
        if (key == "v" || key == "vn") {
            tokenize(line, t);
            checkNumbers(t, 3, key == "v" ? 7 : 3, Where{displayName, context, number});
            ++(key == "v" ? total.v : total.vn);
        } else if (key == "vt") {
            ++total.vt;
        }
    });
    // Pass 2: face indices, relative ones against the counts so far.
    ObjCounts soFar;
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
        }
    });
}

void checkMtlText(std::string_view text, const std::string& displayName, const std::string& context) {
    forEachLine(text, displayName, TextCheck::NoNul, [&](std::string_view line, int number) {
        const std::vector<Token> t = tokenize(line);
        if (t.empty()) return;
        const std::string_view key = t[0].text;
        const Where at{displayName, context, number};
        if (key == "Ka" || key == "Kd" || key == "Ks" || key == "Ke" || key == "Tf" || key == "Kt")
            checkNumbers(t, 3, 3, at);
        else if (key == "Ns" || key == "Ni" || key == "d" || key == "Tr")
            checkNumbers(t, 1, 1, at);
    });
}

}  // namespace vkray
