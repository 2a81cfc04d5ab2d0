#include "scene/off_loader.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "scene/text_input.h"

namespace vkray {
namespace {

// The shortest lines a vertex ("0 0 0\n") and a face ("3 0 1 2\n") can take: counts that need more
// bytes than the file has are a lie, refused before anything is reserved.
constexpr uint64_t kMinVertexBytes = 6;
constexpr uint64_t kMinFaceBytes = 8;
// A face colour is r g b [a]; nothing else may follow the indices.
constexpr size_t kMaxFaceColourValues = 4;

class OffReader {
public:
    OffReader(const MeshRequest& request, SceneBuilder& out, uint64_t fileBytes)
        : request_(request), out_(out), fileBytes_(fileBytes),
          context_(" (OFF loaded at " + request.requestedAt.str() + ")") {}

    void line(std::string_view text, int number);
    void finish(int lastLine) const;

private:
    enum class Stage { Header, Counts, Vertices, Faces, Done };

    [[noreturn]] void fail(int col, const std::string& what) const {
        throw Error(FileLoc{request_.displayName, line_, col}, what + context_);
    }
    void header();
    void counts(size_t first);
    void vertex();
    void face();
    int64_t integer(size_t i, const char* what) const;
    // Token i as a finite float; `what()` names it in the message, built only on failure (a mesh
    // has millions of numbers).
    template <class Name>
    double number(size_t i, const Name& what) const;

    const MeshRequest& request_;
    SceneBuilder& out_;
    uint64_t fileBytes_;
    std::string context_;

    Stage stage_ = Stage::Header;
    bool colours_ = false;  // COFF: each vertex line carries a colour after x y z
    int line_ = 0;
    int countsLine_ = 0;
    std::vector<Token> t_;  // the current line's tokens (reused: meshes run to millions of lines)
    int64_t vertexCount_ = 0, faceCount_ = 0, facesRead_ = 0;
    std::vector<glm::dvec3> vertices_;  // world space
    std::optional<uint32_t> material_;
};

void OffReader::line(std::string_view text, int number) {
    line_ = number;
    tokenize(text, t_);
    if (t_.empty()) return;  // blank or comment
    switch (stage_) {
        case Stage::Header:
            return header();
        case Stage::Counts:
            return counts(0);
        case Stage::Vertices:
            return vertex();
        case Stage::Faces:
            return face();
        case Stage::Done:
            fail(t_[0].col, "unexpected " + quoted(t_[0].text) + " after the last of the " +
                                std::to_string(faceCount_) + " faces the counts at line " +
                                std::to_string(countsLine_) + " announce");
    }
}

void OffReader::header() {
    const std::string_view key = t_[0].text;
    if (key == "OFF" || key == "COFF") {
        colours_ = key == "COFF";
        if (t_.size() > 1 && t_[1].text == "BINARY")
            fail(t_[1].col, "binary OFF is not supported; convert the file to ASCII OFF");
        stage_ = Stage::Counts;
        if (t_.size() > 1) counts(1);  // "OFF nv nf ne" on one line
        return;
    }
    if (key.ends_with("OFF"))
        fail(t_[0].col, "unsupported OFF variant " + quoted(key) + " (vkray reads OFF and COFF)");
    fail(t_[0].col, "expected the header 'OFF' on the first line, got " + quoted(key));
}

int64_t OffReader::integer(size_t i, const char* what) const {
    int64_t v = 0;
    const NumberStatus status = parseInt(t_[i].text, v);
    if (status != NumberStatus::Ok) fail(t_[i].col, describeNumberError(status, t_[i].text, what, "an integer"));
    return v;
}

template <class Name>
double OffReader::number(size_t i, const Name& what) const {
    float v = 0.0f;
    const NumberStatus status = parseFloat(t_[i].text, v);
    if (status != NumberStatus::Ok) fail(t_[i].col, describeNumberError(status, t_[i].text, what(), "a number"));
    return v;
}

void OffReader::counts(size_t first) {
    const size_t n = t_.size() - first;
    if (n < 2 || n > 3)
        fail(t_[first].col, "expected the counts 'vertices faces [edges]', got " + std::to_string(n) + " values");
    vertexCount_ = integer(first, "the vertex count");
    faceCount_ = integer(first + 1, "the face count");
    if (n == 3) integer(first + 2, "the edge count");
    if (vertexCount_ < 0 || faceCount_ < 0)
        fail(t_[first].col, "negative counts " + std::to_string(vertexCount_) + " " + std::to_string(faceCount_));
    // Each count alone is first bounded by the file size, so the sum below cannot overflow.
    const uint64_t nv = uint64_t(vertexCount_), nf = uint64_t(faceCount_);
    if (nv > fileBytes_ || nf > fileBytes_ || nv * kMinVertexBytes + nf * kMinFaceBytes > fileBytes_)
        fail(t_[first].col, "counts of " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                                " faces cannot fit in a file of " + std::to_string(fileBytes_) + " bytes");
    // Each face makes at least one triangle: refuse a mesh past the scene's limit before reading it.
    if (const auto problem = out_.roomProblem(nf)) fail(t_[first + 1].col, *problem);
    countsLine_ = line_;
    vertices_.reserve(size_t(nv));
    out_.reserve(size_t(nf));  // exact for triangle meshes
    stage_ = vertexCount_ > 0 ? Stage::Vertices : faceCount_ > 0 ? Stage::Faces : Stage::Done;
}

void OffReader::vertex() {
    const size_t values = t_.size();
    const bool ok = colours_ ? (values == 6 || values == 7) : values == 3;
    if (!ok)
        fail(t_[0].col, std::string("expected ") + (colours_ ? "x y z r g b [a]" : "3 numbers x y z") +
                            " for vertex " + std::to_string(vertices_.size()) + ", got " +
                            std::to_string(values) + " values");
    glm::dvec3 p;
    for (size_t k = 0; k < 3; ++k)
        p[int(k)] = number(k, [&] {
            return "coordinate " + std::to_string(k + 1) + " of vertex " + std::to_string(vertices_.size());
        });
    for (size_t k = 3; k < values; ++k)
        number(k, [&] { return "colour value " + std::to_string(k - 2) + " of vertex " + std::to_string(vertices_.size()); });
    vertices_.push_back(request_.toWorld.point(p));
    if (int64_t(vertices_.size()) == vertexCount_) stage_ = faceCount_ > 0 ? Stage::Faces : Stage::Done;
}

void OffReader::face() {
    const int64_t n = integer(0, "the face's vertex count");
    if (n < 3) fail(t_[0].col, "a face needs at least 3 vertices, got " + std::to_string(n));
    const size_t extra = t_.size() - 1;
    if (uint64_t(n) > extra)
        fail(t_[0].col, "face of " + std::to_string(n) + " vertices lists only " + std::to_string(extra) + " values");
    if (extra - size_t(n) > kMaxFaceColourValues)
        fail(t_[size_t(n) + 1].col, "face of " + std::to_string(n) + " vertices has " +
                                        std::to_string(extra - size_t(n)) +
                                        " values after its indices (at most a colour r g b a)");
    for (size_t k = size_t(n) + 1; k < t_.size(); ++k)
        number(k, [&] { return "face colour value " + std::to_string(k - size_t(n)); });
    if (const auto problem = out_.roomProblem(uint64_t(n) - 2)) fail(t_[0].col, *problem);

    const auto corner = [&](size_t k) -> const glm::dvec3& {
        const int64_t i = integer(k, "vertex index");
        if (i < 0 || i >= vertexCount_)
            fail(t_[k].col, "vertex index " + std::to_string(i) + " out of range: the file has " +
                                std::to_string(vertexCount_) + " vertices (0-based)");
        return vertices_[size_t(i)];
    };
    if (!material_) material_ = out_.material(request_.defaultMaterial);
    // A fan around the first corner: predictable, and exact for the convex faces OFF files hold.
    const glm::dvec3& p0 = corner(1);
    for (size_t k = 2; k + 1 <= size_t(n); ++k)
        if (!out_.addFlat({p0, corner(k), corner(k + 1)}, *material_))
            fail(t_[k].col, "a transformed vertex does not fit a 32-bit float");
    if (++facesRead_ == faceCount_) stage_ = Stage::Done;
}

void OffReader::finish(int lastLine) const {
    std::string missing;
    switch (stage_) {
        case Stage::Header:
            missing = "no 'OFF' header";
            break;
        case Stage::Counts:
            missing = "no counts after the header";
            break;
        case Stage::Vertices:
            missing = std::to_string(vertices_.size()) + " of the " + std::to_string(vertexCount_) +
                      " vertices announced at line " + std::to_string(countsLine_);
            break;
        case Stage::Faces:
            missing = std::to_string(facesRead_) + " of the " + std::to_string(faceCount_) +
                      " faces announced at line " + std::to_string(countsLine_);
            break;
        case Stage::Done:
            return;
    }
    throw Error(FileLoc{request_.displayName, lastLine, 0}, "file ends early: " + missing + context_);
}

}  // namespace

void loadOff(const MeshRequest& request, SceneBuilder& out) {
    std::string whyNot;
    const std::optional<std::string> bytes = request.readFile(request.file, whyNot);
    if (!bytes) throw meshOpenError(request, "OFF", whyNot);
    OffReader reader(request, out, bytes->size());
    int lastLine = 0;
    forEachLine(
        *bytes, request.displayName, TextCheck::NoNul,
        [&](std::string_view line, int number) {
            reader.line(line, number);
            lastLine = number;
        },
        " (OFF loaded at " + request.requestedAt.str() + ")");
    reader.finish(lastLine);
}

}  // namespace vkray
