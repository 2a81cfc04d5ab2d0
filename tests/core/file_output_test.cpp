// Outputs written atomically (core/file_output.h): a failure, an exception or an interruption leaves
// the previous file byte-identical and no temporary behind; links are written through and devices
// written directly.
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/file_output.h"

namespace vkray {
namespace {

namespace fs = std::filesystem;

// A fresh, empty folder for one test.
fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::path(VKRAY_TEST_OUTPUT_DIR) / "file-output" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string readAll(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

void writePlain(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

// Every temporary file (".NAME.vkray-XXXXXX") left in `dir`.
std::vector<std::string> temporariesIn(const fs::path& dir) {
    std::vector<std::string> found;
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
        if (e.path().filename().string().find(".vkray-") != std::string::npos) found.push_back(e.path().filename());
    return found;
}

// The message of the vkray::Error `write` throws ("" when it throws none).
template <class F>
std::string errorOf(F&& write) {
    try {
        write();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

unsigned modeOf(const fs::path& path) {
    struct stat st {};
    EXPECT_EQ(::stat(path.c_str(), &st), 0) << path;
    return st.st_mode & 07777;
}

const std::string kOld = "the previous output, which must survive\n";

TEST(FileOutput, ReplacesTheFileWholeAndLeavesNoTemporary) {
    const fs::path dir = freshDir("replace");
    const fs::path file = dir / "out.txt";
    writeFileText(file, "first");
    EXPECT_EQ(readAll(file), "first");
    writeFileText(file, "second, longer than the first");
    EXPECT_EQ(readAll(file), "second, longer than the first");
    writeFileText(file, "");
    EXPECT_EQ(readAll(file), "");
    EXPECT_TRUE(temporariesIn(dir).empty());
}

TEST(FileOutput, KeepsTheModeOfAnExistingFileAndGivesANewOneTheUmaskDefault) {
    const fs::path dir = freshDir("mode");
    const mode_t saved = ::umask(027);
    writeFileText(dir / "new.txt", "x");
    ::umask(saved);
    EXPECT_EQ(modeOf(dir / "new.txt"), 0640u);  // 0666 less the umask, as fopen gives

    writePlain(dir / "mine.txt", kOld);
    fs::permissions(dir / "mine.txt", fs::perms(0604));
    writeFileText(dir / "mine.txt", "new");
    EXPECT_EQ(modeOf(dir / "mine.txt"), 0604u);
    EXPECT_EQ(readAll(dir / "mine.txt"), "new");
}

// RLIMIT_FSIZE makes every write past `bytes` fail with EFBIG (SIGXFSZ ignored), as a full disk
// fails with ENOSPC; restored when the test ends.
class FileSizeLimit {
public:
    explicit FileSizeLimit(rlim_t bytes) {
        ::getrlimit(RLIMIT_FSIZE, &saved_);
        savedHandler_ = std::signal(SIGXFSZ, SIG_IGN);
        rlimit lowered = saved_;
        lowered.rlim_cur = bytes;
        EXPECT_EQ(::setrlimit(RLIMIT_FSIZE, &lowered), 0);
    }
    ~FileSizeLimit() {
        ::setrlimit(RLIMIT_FSIZE, &saved_);
        std::signal(SIGXFSZ, savedHandler_);
    }

private:
    rlimit saved_{};
    void (*savedHandler_)(int) = SIG_DFL;
};

TEST(FileOutput, AFailedWriteLeavesThePreviousFileAndNoTemporary) {
    const fs::path dir = freshDir("write-fails");
    const fs::path file = dir / "image.png";
    writePlain(file, kOld);
    const std::string big(256 * 1024, 'n');
    {
        const FileSizeLimit limit(64 * 1024);
        EXPECT_EQ(errorOf([&] { writeFileText(file, big); }), file.string() + ": write failed: File too large");
        // A streamed write failing after its first pieces went out.
        EXPECT_EQ(errorOf([&] {
                      StreamedFileWriter out(file);
                      for (int i = 0; i < 8; ++i) out.write(big.data(), 32 * 1024);
                      out.commit();
                  }),
                  file.string() + ": write failed: File too large");
    }
    EXPECT_EQ(readAll(file), kOld);
    EXPECT_TRUE(temporariesIn(dir).empty());
}

TEST(FileOutput, AnExceptionBeforeCommitLeavesThePreviousFile) {
    const fs::path dir = freshDir("no-commit");
    const fs::path file = dir / "s.vkacc";
    writePlain(file, kOld);
    {
        StreamedFileWriter out(file);
        EXPECT_TRUE(fs::exists(out.temporaryPath()));
        EXPECT_EQ(out.temporaryPath().parent_path(), fs::absolute(dir));
        out.write("partial", 7);
    }
    EXPECT_EQ(readAll(file), kOld);
    EXPECT_TRUE(temporariesIn(dir).empty());
}

// A directory the writer may not write in, and a file its user made read-only: refused in one
// line, the previous file kept. Root may write anywhere, so the writes run in a child that drops to
// an unprivileged user where the test runs as root.
TEST(FileOutput, AReadOnlyDirectoryOrFileIsRefusedAndKeepsThePreviousFile) {
    const fs::path dir = freshDir("read-only");
    const fs::path closed = dir / "closed", writable = dir / "writable";
    fs::create_directories(closed);
    fs::create_directories(writable);
    writePlain(closed / "prev.png", kOld);
    writePlain(writable / "locked.txt", kOld);
    fs::permissions(closed, fs::perms(0555));
    fs::permissions(writable, fs::perms(0777));
    fs::permissions(writable / "locked.txt", fs::perms(0444));
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        if (::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) ::_exit(10);
        const std::string a = errorOf([&] { writeFileText(closed / "prev.png", "new"); });
        const std::string b = errorOf([&] { writeFileText(writable / "locked.txt", "new"); });
        ::_exit(a == (closed / "prev.png").string() + ": cannot open for writing: Permission denied"
                    ? (b == (writable / "locked.txt").string() + ": cannot open for writing: Permission denied" ? 0 : 12)
                    : 11);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    fs::permissions(closed, fs::perms(0755));
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0) << "10: cannot drop root, 11: the directory's error, 12: the file's";
    EXPECT_EQ(readAll(closed / "prev.png"), kOld);
    EXPECT_EQ(readAll(writable / "locked.txt"), kOld);
    EXPECT_TRUE(temporariesIn(closed).empty());
    EXPECT_TRUE(temporariesIn(writable).empty());
}

TEST(FileOutput, ASymbolicLinkIsWrittenThroughAndStays) {
    const fs::path dir = freshDir("symlink");
    fs::create_directories(dir / "real");
    writePlain(dir / "real" / "image.png", kOld);
    fs::permissions(dir / "real" / "image.png", fs::perms(0640));
    fs::create_symlink("real/image.png", dir / "link.png");
    fs::create_symlink("link.png", dir / "link-to-link.png");
    writeFileText(dir / "link-to-link.png", "new");
    EXPECT_TRUE(fs::is_symlink(dir / "link.png"));
    EXPECT_TRUE(fs::is_symlink(dir / "link-to-link.png"));
    EXPECT_EQ(readAll(dir / "real" / "image.png"), "new");
    EXPECT_EQ(modeOf(dir / "real" / "image.png"), 0640u);
    // A dangling link: the file it names is created.
    fs::create_symlink("real/later.png", dir / "dangling.png");
    writeFileText(dir / "dangling.png", "made");
    EXPECT_TRUE(fs::is_symlink(dir / "dangling.png"));
    EXPECT_EQ(readAll(dir / "real" / "later.png"), "made");
    EXPECT_TRUE(temporariesIn(dir).empty());
    EXPECT_TRUE(temporariesIn(dir / "real").empty());
    // A loop is refused, not followed forever.
    fs::create_symlink("loop-b", dir / "loop-a");
    fs::create_symlink("loop-a", dir / "loop-b");
    EXPECT_EQ(errorOf([&] { writeFileText(dir / "loop-a", "x"); }),
              (dir / "loop-a").string() + ": cannot open for writing: Too many levels of symbolic links");
}

TEST(FileOutput, DevicesAreWrittenDirectlyAndNeverRemoved) {
    EXPECT_NO_THROW(writeFileText("/dev/null", "discarded"));
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
    if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
    EXPECT_EQ(errorOf([] { writeFileText("/dev/full", "x"); }), "/dev/full: write failed: No space left on device");
    EXPECT_TRUE(fs::is_character_file("/dev/full"));
    // Through a link: the link stays too.
    const fs::path dir = freshDir("device");
    fs::create_symlink("/dev/full", dir / "out.png");
    EXPECT_EQ(errorOf([&] { writeFileText(dir / "out.png", "x"); }),
              (dir / "out.png").string() + ": write failed: No space left on device");
    EXPECT_TRUE(fs::is_symlink(dir / "out.png"));
    EXPECT_TRUE(temporariesIn(dir).empty());
}

TEST(FileOutput, APipeIsWrittenIntoEvenByAProcLink) {
    // /proc/self/fd/N of a pipe (as /dev/stdout is) links to "pipe:[inode]", which no path follows.
    int ends[2];
    ASSERT_EQ(::pipe(ends), 0);
    writeFileText("/proc/self/fd/" + std::to_string(ends[1]), "through the pipe");
    ::close(ends[1]);
    std::string got;
    char buffer[64];
    for (ssize_t n; (n = ::read(ends[0], buffer, sizeof buffer)) > 0;) got.append(buffer, size_t(n));
    ::close(ends[0]);
    EXPECT_EQ(got, "through the pipe");
    // A named pipe stays one.
    const fs::path fifo = freshDir("fifo") / "out.fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
    std::string read;
    std::thread reader([&] { read = readAll(fifo); });
    writeFileText(fifo, "into the fifo");
    reader.join();
    EXPECT_EQ(read, "into the fifo");
    EXPECT_TRUE(fs::is_fifo(fifo));
    EXPECT_TRUE(temporariesIn(fifo.parent_path()).empty());
}

TEST(FileOutput, FailuresToOpenNameTheFileAndTheCause) {
    const fs::path dir = freshDir("open-fails");
    EXPECT_EQ(errorOf([&] { writeFileText(dir / "no" / "such" / "x.png", "x"); }),
              (dir / "no" / "such" / "x.png").string() + ": cannot open for writing: No such file or directory");
    EXPECT_EQ(errorOf([&] { writeFileText(dir, "x"); }), dir.string() + ": cannot open for writing: Is a directory");
    EXPECT_TRUE(temporariesIn(dir).empty());
}

TEST(FileOutput, TheLongestFileNameStillGetsATemporary) {
    const fs::path dir = freshDir("long-name");
    const fs::path file = dir / (std::string(250, 'n') + ".png");
    writeFileText(file, "long");
    EXPECT_EQ(readAll(file), "long");
    EXPECT_TRUE(temporariesIn(dir).empty());
}

TEST(FileOutput, ConcurrentWritersOfOneFileEachReplaceItWhole) {
    const fs::path dir = freshDir("concurrent");
    const fs::path file = dir / "bench.json";
    {
        StreamedFileWriter a(file), b(file);
        EXPECT_NE(a.temporaryPath(), b.temporaryPath());
    }
    const std::string x(100000, 'x'), y(50000, 'y');
    auto writer = [&](const std::string& text) {
        for (int i = 0; i < 50; ++i) writeFileText(file, text);
    };
    std::thread tx(writer, x), ty(writer, y);
    tx.join();
    ty.join();
    const std::string last = readAll(file);
    EXPECT_TRUE(last == x || last == y);
    EXPECT_TRUE(temporariesIn(dir).empty());
}

// A child writes a big file slowly and is interrupted partway: it dies of the signal (its exit
// status is the signal's), its temporary is gone and the previous file is untouched.
class Interrupted : public ::testing::TestWithParam<int> {};

TEST_P(Interrupted, AStreamedWriteLeavesNoTemporaryAndThePreviousFile) {
    const int sig = GetParam();
    const fs::path dir = freshDir("interrupted-" + std::to_string(sig));
    const fs::path file = dir / "big.vkacc";
    writePlain(file, kOld);
    int ready[2];
    ASSERT_EQ(::pipe(ready), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        ::close(ready[0]);
        std::signal(sig, SIG_DFL);  // as a shell starts vkray, whatever the test runner set
        const std::vector<char> chunk(1 << 20, 'c');
        StreamedFileWriter out(file);
        out.write(chunk.data(), chunk.size());
        const std::string temp = out.temporaryPath().string() + "\n";
        if (::write(ready[1], temp.data(), temp.size()) != ssize_t(temp.size())) ::_exit(20);
        for (int i = 0; i < 6000; ++i) {  // a minute at most, never reached
            out.write(chunk.data(), 4096);
            ::usleep(10000);
        }
        ::_exit(21);
    }
    ::close(ready[1]);
    std::string temp;
    char c;
    while (::read(ready[0], &c, 1) == 1 && c != '\n') temp += c;
    ::close(ready[0]);
    ASSERT_FALSE(temp.empty());
    EXPECT_TRUE(fs::exists(temp));
    ASSERT_EQ(::kill(child, sig), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status)) << "exit status " << WEXITSTATUS(status);
    EXPECT_EQ(WTERMSIG(status), sig);
    EXPECT_FALSE(fs::exists(temp));
    EXPECT_TRUE(temporariesIn(dir).empty());
    EXPECT_EQ(readAll(file), kOld);
}

INSTANTIATE_TEST_SUITE_P(FileOutput, Interrupted, ::testing::Values(SIGINT, SIGTERM, SIGHUP),
                         [](const ::testing::TestParamInfo<int>& info) {
                             return info.param == SIGINT ? "SIGINT" : info.param == SIGTERM ? "SIGTERM" : "SIGHUP";
                         });

}  // namespace
}  // namespace vkray
