// Structure files (accel/accel_file.h): what is loaded is byte for byte what was built, and a file
// for another scene, another accelerator or tuning, or one truncated, damaged or not a structure
// file at all is refused with a message naming the file and the cause.
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "accel/accel.h"
#include "soup_test_util.h"
#include "accel/accel_file.h"
#include "core/error.h"
#include "core/file_output.h"
#include "core/hash64.h"

namespace vkray::accel {
namespace {

namespace fs = std::filesystem;

fs::path outDir() {
    const fs::path dir = fs::path(VKRAY_TEST_OUTPUT_DIR) / "accel-file";
    fs::create_directories(dir);
    return dir;
}


std::vector<char> readAll(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<char>(std::istreambuf_iterator<char>(in), {});
}

// Whether a temporary file of `file` (core/file_output.h) is left in its directory.
bool temporaryLeft(const fs::path& file) {
    const std::string prefix = temporaryNamePrefix(file);
    for (const fs::directory_entry& e : fs::directory_iterator(file.parent_path()))
        if (e.path().filename().string().starts_with(prefix)) return true;
    return false;
}

void writeAll(const fs::path& path, const std::vector<char>& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

// Builds `name` over `scene` and saves it to `file`; returns what was built.
GpuAccelData buildAndSave(const Scene& scene, const std::string& name, const fs::path& file, int threads = 2) {
    const AccelSpec spec = resolveAccel(name);
    const auto built = buildAccel(scene, spec, BuildOptions{.threads = threads, .progress = {}});
    GpuAccelData data = built->gpuData();
    saveAccelFile(file, spec, scene, data, built->stats());
    return data;
}

// `load` must throw a vkray::Error that names `file` and contains `cause`.
void expectRefused(const std::function<void()>& load, const fs::path& file, const std::string& cause) {
    try {
        load();
        ADD_FAILURE() << file << ": expected the error '" << cause << "'";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind(file.string() + ": ", 0), 0u) << what;
        EXPECT_NE(what.find(cause), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

TEST(Hash64, MatchesTheXxh64ReferenceAndIgnoresHowTheBytesAreSplit) {
    EXPECT_EQ(hash64("", 0), 0xEF46DB3751D8E999ull);
    EXPECT_EQ(hash64("abc", 3), 0x44BC2CF5AD770999ull);
    const std::string fox = "The quick brown fox jumps over the lazy dog";
    EXPECT_EQ(hash64(fox.data(), fox.size()), 0x0B242D361FDA71BCull);
    std::vector<unsigned char> bytes(1000);
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(i * 131 + (i >> 7));
    EXPECT_EQ(hash64(bytes.data(), bytes.size()), 0xDED84C6A6EED36C0ull);  // libxxhash's XXH64
    Hash64 split;
    for (size_t at = 0, step = 1; at < bytes.size(); at += step, step = step * 3 + 1)
        split.update(bytes.data() + at, std::min(step, bytes.size() - at));
    EXPECT_EQ(split.digest(), hash64(bytes.data(), bytes.size()));
}

TEST(SceneGeometryHash, SeesPositionsAndCountButNotMaterials) {
    const Scene a = test::smallSoup(100, 1);
    Scene b = a;
    b.triangles[57].material = 3;
    b.materials.resize(4);
    EXPECT_EQ(sceneGeometryHash(a), sceneGeometryHash(b));
    b.triangles[57].p1.y = std::nextafter(b.triangles[57].p1.y, 9.0f);
    EXPECT_NE(sceneGeometryHash(a), sceneGeometryHash(b));
    Scene c = a;
    std::swap(c.triangles[3], c.triangles[4]);  // triangle identity is scene order
    EXPECT_NE(sceneGeometryHash(a), sceneGeometryHash(c));
    c.triangles.pop_back();
    EXPECT_NE(sceneGeometryHash(a), sceneGeometryHash(c));
}

// The positions are local to Scene::origin: the same floats at another origin are another scene, so
// a structure file saved for one cannot be loaded for the other; an origin of 0 (of either sign)
// enters no bytes into the hash, so it is the positions' hash alone.
TEST(SceneGeometryHash, SeesTheOrigin) {
    const Scene a = test::smallSoup(100, 1);
    Scene b = a;
    b.origin = glm::dvec3(0.0, 0.0, -0.0);
    EXPECT_EQ(sceneGeometryHash(a), sceneGeometryHash(b));
    b.origin = glm::dvec3(1e6, 1e6, 1e6);
    EXPECT_NE(sceneGeometryHash(a), sceneGeometryHash(b));
    Scene c = b;
    c.origin.z = 1e6 + 16.0;
    EXPECT_NE(sceneGeometryHash(b), sceneGeometryHash(c));
}

class EveryStructure : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryStructure, LoadsByteForByteWhatWasBuilt) {
    const Scene scene = test::smallSoup(700, 5);
    const fs::path file = outDir() / (GetParam() + ".vkacc");
    const AccelSpec spec = resolveAccel(GetParam());
    const auto built = buildAccel(scene, spec, BuildOptions{.threads = 2, .progress = {}});
    const GpuAccelData data = built->gpuData();
    EXPECT_EQ(traversalOf(spec), data.traversal);  // what checkSpec() compares a file's traversal with
    saveAccelFile(file, spec, scene, data, built->stats());
    EXPECT_FALSE(temporaryLeft(file));

    const LoadedAccel loaded = loadAccelFile(file, spec, scene);
    EXPECT_EQ(loaded.data.traversal, data.traversal);
    EXPECT_EQ(loaded.data.triangleOrder, data.triangleOrder);
    EXPECT_EQ(loaded.data.nodes, data.nodes);
    EXPECT_EQ(loaded.data.indices, data.indices);
    EXPECT_EQ(loaded.data.extra, data.extra);
    EXPECT_EQ(loaded.data.nodeTexelBytes, data.nodeTexelBytes);
    EXPECT_EQ(loaded.data.maxLeafTriangles, data.maxLeafTriangles);
    EXPECT_EQ(loaded.data.kdShortStack, data.kdShortStack);
    EXPECT_EQ(loaded.builtAs, GetParam());
    // The structural figures come back; the times and the thread count were not stored.
    std::vector<std::string> want, got;
    for (const AccelStat& st : built->stats())
        if (!isBuildTiming(st)) want.push_back(st.key + "=" + std::to_string(st.value) + " " + st.unit);
    for (const AccelStat& st : loaded.stats) got.push_back(st.key + "=" + std::to_string(st.value) + " " + st.unit);
    EXPECT_EQ(got, want);
    EXPECT_FALSE(got.empty());
    EXPECT_TRUE(std::none_of(loaded.stats.begin(), loaded.stats.end(), isBuildTiming));
}

INSTANTIATE_TEST_SUITE_P(Names, EveryStructure,
                         ::testing::Values("bvh", "bvh-fast", "bvh-sah", "bvh-stackless", "bvh-packet", "bvh-sphere", "kd-stack", "kd-shortstack", "kd-packet", "kd-restart",
                                           "kd-pushdown", "kd-ropes", "kd-backtrack"),
                         [](const auto& info) {
                             std::string n = info.param;
                             std::replace(n.begin(), n.end(), '-', '_');
                             return n;
                         });

// kd-shortstack's stack size is the kernel's, not the structure's: a file saved with one size serves
// a render that asks for another, which gets the size it asked for.
TEST(AccelFile, AShortStackFileServesAnyStackSize) {
    const Scene scene = test::smallSoup(300, 3);
    const fs::path file = outDir() / "short-stack.vkacc";
    const AccelSpec saved = resolveAccel("kd-shortstack");
    const auto built = buildAccel(scene, saved, BuildOptions{.threads = 2, .progress = {}});
    const GpuAccelData data = built->gpuData();
    EXPECT_EQ(data.kdShortStack, uint32_t(VKRAY_KD_SHORT_STACK_SIZE));
    saveAccelFile(file, saved, scene, data, built->stats());
    const LoadedAccel loaded = loadAccelFile(file, resolveAccel("kd-shortstack:kd-short-stack=2.0"), scene);
    EXPECT_EQ(loaded.data.kdShortStack, 2u);
    EXPECT_EQ(loaded.data.nodes, data.nodes);
}

TEST(AccelFile, TheSameStructureWritesTheSameBytesWhateverTheThreads) {
    const Scene scene = test::smallSoup(500, 9);
    const fs::path a = outDir() / "threads-1.vkacc", b = outDir() / "threads-2.vkacc";
    buildAndSave(scene, "bvh", a, 1);
    buildAndSave(scene, "bvh", b, 2);
    EXPECT_EQ(readAll(a), readAll(b));
}

TEST(AccelFile, RefusesAnotherScene) {
    const Scene scene = test::smallSoup(400, 2);
    const fs::path file = outDir() / "scene.vkacc";
    buildAndSave(scene, "bvh", file);
    const AccelSpec spec = resolveAccel("bvh");
    const Scene other = test::smallSoup(400, 3);
    expectRefused([&] { loadAccelFile(file, spec, other); }, file,
                  "built for another scene (geometry hash differs); rebuild it with --save-accel");
    const Scene fewer = test::smallSoup(399, 2);
    expectRefused([&] { loadAccelFile(file, spec, fewer); }, file,
                  "built for another scene (400 triangles, this one has 399)");
    Scene recoloured = scene;  // materials are not part of the structure
    recoloured.triangles[0].material = 1;
    recoloured.materials.resize(2);
    EXPECT_NO_THROW(loadAccelFile(file, spec, recoloured));
}

TEST(AccelFile, RefusesAnotherAcceleratorOrTuning) {
    const Scene scene = test::smallSoup(300, 4);
    const fs::path bvhFile = outDir() / "bvh.vkacc", kdFile = outDir() / "kd-stack.vkacc";
    buildAndSave(scene, "bvh", bvhFile);
    buildAndSave(scene, "kd-stack", kdFile);
    expectRefused([&] { loadAccelFile(bvhFile, resolveAccel("kd-stack"), scene); }, bvhFile,
                  "built for --accel bvh, not kd-stack; rebuild it with --save-accel");
    expectRefused([&] { loadAccelFile(bvhFile, resolveAccel("bvh-fast"), scene); }, bvhFile,
                  "built for --accel bvh, not bvh-fast");
    // One tree, another kernel: the kd traversals do not share files.
    expectRefused([&] { loadAccelFile(kdFile, resolveAccel("kd-backtrack"), scene); }, kdFile,
                  "built for --accel kd-stack, not kd-backtrack");
    expectRefused([&] { loadAccelFile(bvhFile, resolveAccel("bvh:aac-delta=9"), scene); }, bvhFile,
                  "built for --accel bvh, not bvh:aac-delta=9");
    // bvh is bvh-hq restructured: the same structure only when tuned alike.
    expectRefused([&] { loadAccelFile(bvhFile, resolveAccel("bvh-hq"), scene); }, bvhFile,
                  "built for --accel bvh, not bvh-hq");
    EXPECT_NO_THROW(loadAccelFile(
        bvhFile, resolveAccel("bvh-hq:bvh-treelet-passes=2:bvh-treelet-min=8"), scene));
}

// Every damage a disk, a copy or an editor can do: each is caught before the arrays are used.
class DamagedFile : public ::testing::Test {
protected:
    void SetUp() override {
        // One pair of files per test: CTest runs the tests of this fixture at the same time.
        const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
        good_ = outDir() / (name + "-good.vkacc");
        bad_ = outDir() / (name + "-bad.vkacc");
        buildAndSave(scene_, "kd-backtrack", good_);  // every array non-empty but the order
        bytes_ = readAll(good_);
        std::memcpy(&metaBytes_, bytes_.data() + 12, 4);
    }
    void expectBad(const std::vector<char>& bytes, const std::string& cause) {
        writeAll(bad_, bytes);
        expectRefused([&] { loadAccelFile(bad_, resolveAccel("kd-backtrack"), scene_); }, bad_, cause);
    }
    size_t payloadStart() const { return 16 + metaBytes_ + 8; }

    Scene scene_ = test::smallSoup(300, 6);
    fs::path good_, bad_;
    std::vector<char> bytes_;
    uint32_t metaBytes_ = 0;
};

TEST_F(DamagedFile, TruncatedAnywhere) {
    ASSERT_NO_THROW(loadAccelFile(good_, resolveAccel("kd-backtrack"), scene_));
    for (size_t keep : {size_t(12), size_t(20), payloadStart(), bytes_.size() / 2, bytes_.size() - 1}) {
        SCOPED_TRACE(keep);
        expectBad(std::vector<char>(bytes_.begin(), bytes_.begin() + std::ptrdiff_t(keep)), "truncated");
    }
    std::vector<char> longer = bytes_;
    longer.push_back('x');
    expectBad(longer, "damaged: 1 byte after the structure's end");
}

TEST_F(DamagedFile, AFlippedByte) {
    std::vector<char> bytes = bytes_;
    bytes[16 + metaBytes_ / 2] ^= 0x10;
    expectBad(bytes, "damaged: its header's checksum does not match");
    for (size_t at : {payloadStart(), payloadStart() + (bytes_.size() - payloadStart()) / 2, bytes_.size() - 1}) {
        SCOPED_TRACE(at);
        bytes = bytes_;
        bytes[at] ^= 0x01;
        expectBad(bytes, "damaged: its arrays' checksum does not match");
    }
}

TEST_F(DamagedFile, NotAStructureFileOrAnotherVersion) {
    std::vector<char> bytes = bytes_;
    bytes[0] = 'X';
    expectBad(bytes, "not a vkray structure file (it does not start with VKRAYACC)");
    expectBad({'c', 'a', 'm'}, "not a vkray structure file");
    bytes = bytes_;
    bytes[8] = 99;
    expectBad(bytes, "structure file format version 99, this vkray reads version " + std::to_string(kAccelFileVersion) +
                         "; rebuild it with --save-accel");
    const fs::path missing = outDir() / "missing.vkacc";
    fs::remove(missing);
    expectRefused([&] { AccelFileReader reader(missing); }, missing, "cannot open structure file: No such file");
    expectRefused([&] { AccelFileReader reader(outDir()); }, outDir(), "is a directory");
}

// A checksum is no defence against a file made on purpose; an index that would send the triangle
// upload out of bounds is refused anyway.
TEST(AccelFile, RefusesATriangleOrderOutOfRange) {
    const Scene scene = test::smallSoup(200, 8);
    const fs::path file = outDir() / "order.vkacc";
    buildAndSave(scene, "bvh", file);
    std::vector<char> bytes = readAll(file);
    uint32_t metaBytes;
    std::memcpy(&metaBytes, bytes.data() + 12, 4);
    const size_t payload = 16 + metaBytes + 8, end = bytes.size() - 8;
    const uint32_t bad = 200;
    std::memcpy(bytes.data() + payload, &bad, 4);
    const uint64_t sum = hash64(bytes.data() + payload, end - payload);
    std::memcpy(bytes.data() + end, &sum, 8);
    writeAll(file, bytes);
    expectRefused([&] { loadAccelFile(file, resolveAccel("bvh"), scene); }, file,
                  "damaged: triangle order entry 200 out of range");
}

TEST(AccelFile, WritingFailsWithThePathAndLeavesNothingBehind) {
    const Scene scene = test::smallSoup(50, 1);
    const fs::path nowhere = outDir() / "no" / "such" / "dir" / "s.vkacc";
    expectRefused([&] { buildAndSave(scene, "bvh", nowhere); }, nowhere, "directory");
    expectRefused([&] { buildAndSave(scene, "bvh", outDir()); }, outDir(), "is a directory");
    // A directory that exists but takes no files (checkAccelFileTarget() finds it before a build).
    expectRefused([&] { checkAccelFileTarget("/proc/s.vkacc"); }, "/proc/s.vkacc",
                  "cannot open for writing");
    // Over an existing file, the new one replaces it whole.
    const fs::path file = outDir() / "replaced.vkacc";
    writeAll(file, {'o', 'l', 'd'});
    buildAndSave(scene, "bvh", file);
    EXPECT_NO_THROW(loadAccelFile(file, resolveAccel("bvh"), scene));
    EXPECT_FALSE(temporaryLeft(file));
}

}  // namespace
}  // namespace vkray::accel
