// Structure files: `vkray render --save-accel FILE` writes what a GPU render needs of a built
// structure (GpuAccelData, with its structural figures for --stats), and `--load-accel FILE` reads
// it back instead of building, so repeated renders of a big scene skip a build of seconds to
// minutes. A file is a cache, never trusted: it is used only by the accelerator it was built for
// (same traversal, same structureKey(): preset and tuning), over the same geometry (triangle count and
// an XXH64 of every vertex position, in scene order), by a vkray with the same GPU layouts
// (shaders/shared/*_layout.h, hashed at configure time); its header and its arrays carry checksums,
// so a truncated or damaged file is refused too. Each refusal is one vkray::Error naming the file
// and the cause. The layout is in docs/outputs.md ("Structure files").
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "accel/accel_spec.h"
#include "core/hash64.h"
#include "scene/scene.h"

namespace vkray::accel {

// The bytes that open every structure file, and the version of the layout after them; a file of
// another version is refused (it is rebuilt, never converted).
inline constexpr char kAccelFileMagic[8] = {'V', 'K', 'R', 'A', 'Y', 'A', 'C', 'C'};
inline constexpr uint32_t kAccelFileVersion = 2;

// XXH64 of the triangle count, every triangle's vertex positions in scene order and, when it is not
// (0, 0, 0), Scene::origin: all a structure depends on (materials, normals, lights and the camera may
// change freely). The positions are local to the origin, so the same floats at another origin are
// another scene; a file saved before the origin existed (always 0) still matches.
uint64_t sceneGeometryHash(const Scene& scene);

// What a structure depends on of its scene: the triangle count and sceneGeometryHash(). Made once a
// scene where several things are checked against it (a structure file read or written, the
// metadata of an EXR output); made from the Scene where a call passes one, hashing it there.
struct SceneGeometry {
    uint64_t triangles = 0, hash = 0;
    SceneGeometry(const Scene& scene);  // not explicit: a Scene passes for its geometry
};

// Whether a build figure is a time or a setting of the build (threads) rather than a property of
// the structure: those are not stored, so that a file says nothing stale and the same build always
// writes the same bytes.
bool isBuildTiming(const AccelStat& stat);

// Refuses, before any work, a --save-accel path that cannot be written: a missing directory, a
// directory in its place.
void checkAccelFileTarget(const std::filesystem::path& path);

// Writes `data` (built by `spec` over `scene`) and the structural figures of `stats` to `path`:
// streamed to a temporary beside it and renamed over `path` once complete (core/file_output.h), so a
// failed or interrupted write never leaves a partial file under the name. Throws vkray::Error
// naming `path` on any failure.
void saveAccelFile(const std::filesystem::path& path, const AccelSpec& spec, const SceneGeometry& scene,
                   const GpuAccelData& data, const std::vector<AccelStat>& stats);

struct LoadedAccel {
    GpuAccelData data;
    std::vector<AccelStat> stats;  // the structural figures saved with it
    std::string builtAs;           // the --accel name the file was written with
};

// Reading in two steps, so that the command line can refuse a wrong file before it loads the
// scene (which, for a big one, takes seconds): the constructor and checkSpec() read only the
// header; read() checks the scene and reads the arrays.
class AccelFileReader {
public:
    // Opens `path` and checks the magic, the version, the header's checksum and the GPU layouts.
    explicit AccelFileReader(const std::filesystem::path& path);
    ~AccelFileReader();
    AccelFileReader(AccelFileReader&&) noexcept;
    AccelFileReader& operator=(AccelFileReader&&) noexcept;

    // Refuses a file built for another traversal or another structure (preset, tuning); keeps what the
    // spec sets in the kernel but not in the structure (kd-shortstack's stack size) for readArrays().
    void checkSpec(const AccelSpec& spec);
    // Refuses a file built for other geometry.
    void checkScene(const SceneGeometry& scene);
    // Reads the arrays, checking the file's size and the payload's checksum; after checkScene(),
    // once.
    LoadedAccel readArrays();
    // checkScene(), then readArrays().
    LoadedAccel read(const SceneGeometry& scene);

    const std::filesystem::path& path() const { return path_; }

    struct Header;

private:
    void checkFileSize() const;
    void readHashed(void* data, size_t size, Hash64& hash);

    std::filesystem::path path_;
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
    std::unique_ptr<Header> header_;
    uint32_t kdShortStack_ = 0;  // GpuAccelData::kdShortStack of the spec checked
    uint32_t metaBytes_ = 0;
    bool sceneChecked_ = false;
};

// The three steps at once.
LoadedAccel loadAccelFile(const std::filesystem::path& path, const AccelSpec& spec, const SceneGeometry& scene);

}  // namespace vkray::accel
