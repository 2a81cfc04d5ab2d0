#include "accel/accel_file.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <iterator>
#include <span>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>

#include "accel/kd/kd_accel.h"
#include "core/error.h"
#include "core/file_output.h"
#include "core/hash64.h"

#ifndef VKRAY_GPU_LAYOUT_HASH
#error "VKRAY_GPU_LAYOUT_HASH (the hash of shaders/shared/*_layout.h) comes from CMakeLists.txt"
#endif

namespace vkray::accel {

// The layout of a file (all integers little-endian, as the host writes them; hash64.h insists):
//   "VKRAYACC", u32 version, u32 metaBytes, meta[metaBytes], u64 XXH64(meta),
//   triangleOrder (u32 each), nodes, indices, extra (bytes), u64 XXH64(the four arrays).
// meta is the Header below, field by field (strings as u32 length + bytes, doubles as IEEE bits).
struct AccelFileReader::Header {
    uint64_t layoutHash = 0;
    std::string traversal, specName, structureKey;
    uint64_t triangles = 0, sceneHash = 0;
    uint32_t nodeTexelBytes = 0, maxLeafTriangles = 0;
    uint64_t orderCount = 0, nodesBytes = 0, indicesBytes = 0, extraBytes = 0;
    std::vector<AccelStat> stats;
};

namespace {

namespace fs = std::filesystem;
using Header = AccelFileReader::Header;

constexpr uint64_t kLayoutHash = VKRAY_GPU_LAYOUT_HASH;
constexpr size_t kPrefixBytes = 16;            // magic, version, metaBytes
constexpr uint32_t kMaxMetaBytes = 1u << 20;   // names, key and a few dozen figures: a few KiB
constexpr size_t kChunkBytes = size_t(8) << 20;  // hashed while still in cache, read or written


constexpr std::string_view kRebuild = "; rebuild it with --save-accel";

// ---- meta: the header as bytes ----------------------------------------------------------------

class MetaWriter {
public:
    template <class T>
    void put(T v) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes_.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
    void put(const std::string& s) {
        put(uint32_t(s.size()));
        bytes_ += s;
    }
    const std::string& bytes() const { return bytes_; }

private:
    std::string bytes_;
};

// Reads what MetaWriter wrote; a header that ends early is damaged (its checksum matched, so it
// was written that way: by a broken writer, not by a bad disk).
class MetaReader {
public:
    MetaReader(std::span<const char> bytes, const fs::path& path) : bytes_(bytes), path_(path) {}

    template <class T>
    T get() {
        T v;
        std::memcpy(&v, take(sizeof v), sizeof v);
        return v;
    }
    std::string getString() {
        const uint32_t n = get<uint32_t>();
        return std::string(take(n), n);
    }
    bool done() const { return at_ == bytes_.size(); }

private:
    const char* take(size_t n) {
        if (n > bytes_.size() - at_) throw fileError(path_, "damaged: its header ends early");
        const char* p = bytes_.data() + at_;
        at_ += n;
        return p;
    }
    std::span<const char> bytes_;
    size_t at_ = 0;
    const fs::path& path_;
};

std::string encodeMeta(const Header& h) {
    MetaWriter w;
    w.put(h.layoutHash);
    w.put(h.traversal);
    w.put(h.specName);
    w.put(h.structureKey);
    w.put(h.triangles);
    w.put(h.sceneHash);
    w.put(h.nodeTexelBytes);
    w.put(h.maxLeafTriangles);
    for (uint64_t v : {h.orderCount, h.nodesBytes, h.indicesBytes, h.extraBytes}) w.put(v);
    w.put(uint32_t(h.stats.size()));
    for (const AccelStat& st : h.stats) {
        w.put(st.key);
        w.put(st.value);
        w.put(st.unit);
    }
    return w.bytes();
}

Header decodeMeta(std::span<const char> bytes, const fs::path& path) {
    MetaReader r(bytes, path);
    Header h;
    h.layoutHash = r.get<uint64_t>();
    h.traversal = r.getString();
    h.specName = r.getString();
    h.structureKey = r.getString();
    h.triangles = r.get<uint64_t>();
    h.sceneHash = r.get<uint64_t>();
    h.nodeTexelBytes = r.get<uint32_t>();
    h.maxLeafTriangles = r.get<uint32_t>();
    for (uint64_t* v : {&h.orderCount, &h.nodesBytes, &h.indicesBytes, &h.extraBytes}) *v = r.get<uint64_t>();
    const uint32_t statCount = r.get<uint32_t>();
    for (uint32_t k = 0; k < statCount; ++k) {
        AccelStat st;
        st.key = r.getString();
        st.value = r.get<double>();
        st.unit = r.getString();
        h.stats.push_back(std::move(st));
    }
    if (!r.done()) throw fileError(path, "damaged: its header is longer than its fields");
    return h;
}

// ---- writing ----------------------------------------------------------------------------------

// Writes `bytes` in chunks, each hashed into `hash` just before it is written.
void writeHashed(StreamedFileWriter& out, std::span<const std::byte> bytes, Hash64& hash) {
    for (size_t at = 0; at < bytes.size(); at += kChunkBytes) {
        const size_t n = std::min(kChunkBytes, bytes.size() - at);
        hash.update(bytes.data() + at, n);
        out.write(bytes.data() + at, n);
    }
}

template <class T>
std::span<const std::byte> byteSpan(const std::vector<T>& v) {
    return std::as_bytes(std::span<const T>(v));
}

Header headerFor(const AccelSpec& spec, const SceneGeometry& scene, const GpuAccelData& data,
                 const std::vector<AccelStat>& stats) {
    Header h;
    h.layoutHash = kLayoutHash;
    h.traversal = std::string(traversalName(data.traversal));
    h.specName = spec.name;
    h.structureKey = structureKey(spec);
    h.triangles = scene.triangles;
    h.sceneHash = scene.hash;
    h.nodeTexelBytes = data.nodeTexelBytes;
    h.maxLeafTriangles = data.maxLeafTriangles;
    h.orderCount = data.triangleOrder.size();
    h.nodesBytes = data.nodes.size();
    h.indicesBytes = data.indices.size();
    h.extraBytes = data.extra.size();
    std::copy_if(stats.begin(), stats.end(), std::back_inserter(h.stats),
                 [](const AccelStat& st) { return !isBuildTiming(st); });
    return h;
}

// ---- reading ----------------------------------------------------------------------------------

Traversal traversalNamed(const std::string& name, const fs::path& path) {
    for (Traversal t : kTraversals)
        if (traversalName(t) == name) return t;
    throw fileError(path, "built for a traversal this vkray does not have ('" + name + "')" + std::string(kRebuild));
}

// What a header must hold whatever it was built for: texel sizes the kernels can bind.
void checkConsistent(const Header& h, const fs::path& path) {
    const bool texelOk = h.nodeTexelBytes == 4 || h.nodeTexelBytes == 8 || h.nodeTexelBytes == 16;
    if (!texelOk || h.nodesBytes % std::max<uint32_t>(h.nodeTexelBytes, 1) != 0 ||
        h.indicesBytes % sizeof(uint32_t) != 0 || h.extraBytes % 16 != 0)
        throw fileError(path, "damaged: its array sizes are not whole texels");
}

}  // namespace

uint64_t sceneGeometryHash(const Scene& scene) {
    Hash64 hash;
    const uint64_t count = scene.triangles.size();
    hash.update(&count, sizeof count);
    // The positions gathered block by block (each triangle's material, between them, left out), so
    // the hash runs over long contiguous runs.
    constexpr size_t kBlock = 4096;
    std::vector<float> block(kBlock * 9);
    for (size_t first = 0; first < scene.triangles.size(); first += kBlock) {
        const size_t n = std::min(kBlock, scene.triangles.size() - first);
        float* out = block.data();
        for (size_t k = 0; k < n; ++k) {
            const Triangle& t = scene.triangles[first + k];
            for (const glm::vec3& p : {t.p0, t.p1, t.p2}) *out++ = p.x, *out++ = p.y, *out++ = p.z;
        }
        hash.update(block.data(), n * 9 * sizeof(float));
    }
    if (scene.origin != glm::dvec3(0.0)) {
        const double origin[3] = {scene.origin.x, scene.origin.y, scene.origin.z};
        hash.update(origin, sizeof origin);
    }
    return hash.digest();
}

SceneGeometry::SceneGeometry(const Scene& scene) : triangles(scene.triangles.size()), hash(sceneGeometryHash(scene)) {}

bool isBuildTiming(const AccelStat& stat) {
    return stat.key == "threads" || (stat.key.size() > 3 && stat.key.ends_with("_ms"));
}

void checkAccelFileTarget(const fs::path& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw fileError(path, "cannot write a structure file: is a directory");
    const fs::path dir = path.parent_path();
    if (!dir.empty() && !fs::is_directory(dir, ec))
        throw fileError(path, "cannot write: directory " + dir.string() + " does not exist");
    // The one sure test of a directory's permissions, its file system and quotas: create the
    // temporary file (empty) and remove it again.
    StreamedFileWriter probe(path);
}

void saveAccelFile(const fs::path& path, const AccelSpec& spec, const SceneGeometry& scene, const GpuAccelData& data,
                   const std::vector<AccelStat>& stats) {
    checkAccelFileTarget(path);
    const std::string meta = encodeMeta(headerFor(spec, scene, data, stats));
    StreamedFileWriter out(path);
    out.write(kAccelFileMagic, sizeof kAccelFileMagic);
    const uint32_t prefix[2] = {kAccelFileVersion, uint32_t(meta.size())};
    out.write(prefix, sizeof prefix);
    out.write(meta.data(), meta.size());
    const uint64_t metaHash = hash64(meta.data(), meta.size());
    out.write(&metaHash, sizeof metaHash);
    Hash64 payload;
    writeHashed(out, byteSpan(data.triangleOrder), payload);
    for (const std::vector<std::byte>* array : {&data.nodes, &data.indices, &data.extra})
        writeHashed(out, byteSpan(*array), payload);
    const uint64_t payloadHash = payload.digest();
    out.write(&payloadHash, sizeof payloadHash);
    out.commit();
}

AccelFileReader::AccelFileReader(const fs::path& path) : path_(path), file_(nullptr, std::fclose) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw fileError(path, "cannot open structure file: is a directory");
    file_.reset(std::fopen(path.c_str(), "rb"));
    if (!file_) throw fileError(path, std::string("cannot open structure file: ") + std::strerror(errno));

    unsigned char prefix[kPrefixBytes];
    const size_t got = std::fread(prefix, 1, sizeof prefix, file_.get());
    if (got < sizeof kAccelFileMagic || std::memcmp(prefix, kAccelFileMagic, sizeof kAccelFileMagic) != 0)
        throw fileError(path, "not a vkray structure file (it does not start with VKRAYACC)");
    if (got < sizeof prefix) throw fileError(path, "truncated: the file ends inside its header");
    uint32_t version, metaBytes;
    std::memcpy(&version, prefix + 8, 4);
    std::memcpy(&metaBytes, prefix + 12, 4);
    if (version != kAccelFileVersion)
        throw fileError(path, "structure file format version " + std::to_string(version) + ", this vkray reads version " +
                                  std::to_string(kAccelFileVersion) + std::string(kRebuild));
    if (metaBytes > kMaxMetaBytes) throw fileError(path, "damaged: its header claims " + std::to_string(metaBytes) + " bytes");

    metaBytes_ = metaBytes;
    std::vector<char> meta(metaBytes + sizeof(uint64_t));
    if (std::fread(meta.data(), 1, meta.size(), file_.get()) != meta.size())
        throw fileError(path, "truncated: the file ends inside its header");
    uint64_t metaHash;
    std::memcpy(&metaHash, meta.data() + metaBytes, sizeof metaHash);
    if (hash64(meta.data(), metaBytes) != metaHash) throw fileError(path, "damaged: its header's checksum does not match");
    header_ = std::make_unique<Header>(decodeMeta(std::span<const char>(meta.data(), metaBytes), path));
    if (header_->layoutHash != kLayoutHash)
        throw fileError(path, "written by a vkray with other GPU structure layouts (shaders/shared/*_layout.h)" +
                                  std::string(kRebuild));
    checkConsistent(*header_, path);
}

AccelFileReader::~AccelFileReader() = default;
AccelFileReader::AccelFileReader(AccelFileReader&&) noexcept = default;
AccelFileReader& AccelFileReader::operator=(AccelFileReader&&) noexcept = default;

void AccelFileReader::checkSpec(const AccelSpec& spec) {
    const Header& h = *header_;
    kdShortStack_ = spec.family == Family::Kd ? kdShortStack(spec.kdTraversal, spec.kdShortStack) : 0u;
    // bvh and bvh-hq name one structure and one traversal: either reads the other's file. The kd
    // traversals share a tree but not a file (nor, for kd-backtrack and kd-ropes, the arrays).
    const std::string key = structureKey(spec);
    if (h.traversal == traversalName(traversalOf(spec)) && h.structureKey == key) return;
    if (h.specName != spec.name)
        throw fileError(path_, "built for --accel " + h.specName + ", not " + spec.name + std::string(kRebuild));
    throw fileError(path_, "built for --accel " + h.specName + " tuned otherwise (" + h.structureKey +
                               "; this render: " + key + ")" + std::string(kRebuild));
}

void AccelFileReader::checkScene(const SceneGeometry& scene) {
    const Header& h = *header_;
    if (h.triangles != scene.triangles)
        throw fileError(path_, "built for another scene (" + std::to_string(h.triangles) + " triangles, this one has " +
                                   std::to_string(scene.triangles) + ")" + std::string(kRebuild));
    if (h.sceneHash != scene.hash)
        throw fileError(path_, "built for another scene (geometry hash differs)" + std::string(kRebuild));
    if (h.orderCount != 0 && h.orderCount != h.triangles)
        throw fileError(path_, "damaged: its triangle order has " + std::to_string(h.orderCount) + " entries for " +
                                   std::to_string(h.triangles) + " triangles");
    sceneChecked_ = true;
}

void AccelFileReader::checkFileSize() const {
    const Header& h = *header_;
    std::error_code ec;
    const uintmax_t size = fs::file_size(path_, ec);
    if (ec) throw fileError(path_, "cannot read its size: " + ec.message());
    // Sizes from a header are summed with care: a crafted one must not wrap around to the file size.
    const auto overflow = [&] { return fileError(path_, "damaged: its header's array sizes overflow"); };
    if (h.orderCount > UINT64_MAX / sizeof(uint32_t)) throw overflow();
    uint64_t expected = kPrefixBytes + metaBytes_ + 2 * sizeof(uint64_t);
    for (uint64_t v : {h.orderCount * sizeof(uint32_t), h.nodesBytes, h.indicesBytes, h.extraBytes}) {
        if (v > UINT64_MAX - expected) throw overflow();
        expected += v;
    }
    if (size < expected)
        throw fileError(path_, "truncated: " + std::to_string(size) + " bytes, its header promises " +
                                   std::to_string(expected));
    if (size > expected) {
        const uint64_t extra = size - expected;
        throw fileError(path_, "damaged: " + std::to_string(extra) + (extra == 1 ? " byte" : " bytes") +
                                   " after the structure's end");
    }
}

void AccelFileReader::readHashed(void* data, size_t size, Hash64& hash) {
    auto* p = static_cast<std::byte*>(data);
    for (size_t at = 0; at < size; at += kChunkBytes) {
        const size_t n = std::min(kChunkBytes, size - at);
        if (std::fread(p + at, 1, n, file_.get()) != n)
            throw fileError(path_, std::ferror(file_.get()) ? std::string("read failed: ") + std::strerror(errno)
                                                            : std::string("truncated: the file ends inside its arrays"));
        hash.update(p + at, n);
    }
}

LoadedAccel AccelFileReader::read(const SceneGeometry& scene) {
    checkScene(scene);
    return readArrays();
}

LoadedAccel AccelFileReader::readArrays() {
    if (!sceneChecked_ || !file_) throw std::logic_error("AccelFileReader::readArrays: checkScene() first, once");
    checkFileSize();
    const Header& h = *header_;
    LoadedAccel loaded;
    GpuAccelData& d = loaded.data;
    d.traversal = traversalNamed(h.traversal, path_);
    d.nodeTexelBytes = h.nodeTexelBytes;
    d.maxLeafTriangles = h.maxLeafTriangles;
    d.kdShortStack = kdShortStack_;
    Hash64 payload;
    d.triangleOrder.resize(h.orderCount);
    readHashed(d.triangleOrder.data(), d.triangleOrder.size() * sizeof(uint32_t), payload);
    for (auto [array, bytes] : {std::pair{&d.nodes, h.nodesBytes}, {&d.indices, h.indicesBytes}, {&d.extra, h.extraBytes}}) {
        array->resize(bytes);
        readHashed(array->data(), array->size(), payload);
    }
    uint64_t payloadHash = 0;
    if (std::fread(&payloadHash, 1, sizeof payloadHash, file_.get()) != sizeof payloadHash)
        throw fileError(path_, "truncated: the file ends before its checksum");
    if (payload.digest() != payloadHash) throw fileError(path_, "damaged: its arrays' checksum does not match");
    // A checksum catches damage, not a file made by hand: an index past the triangles would send the
    // upload out of bounds, so it is refused here (the node arrays are bounded by the kernels).
    for (uint32_t t : d.triangleOrder)
        if (t >= h.triangles) throw fileError(path_, "damaged: triangle order entry " + std::to_string(t) + " out of range");
    loaded.stats = h.stats;
    loaded.builtAs = h.specName;
    file_.reset();
    return loaded;
}

LoadedAccel loadAccelFile(const fs::path& path, const AccelSpec& spec, const SceneGeometry& scene) {
    AccelFileReader reader(path);
    reader.checkSpec(spec);
    return reader.read(scene);
}

}  // namespace vkray::accel
