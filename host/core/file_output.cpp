#include "core/file_output.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <string>
#include <system_error>

#include "core/error.h"
#include "core/temp_files.h"

namespace fs = std::filesystem;

namespace vkray {
namespace {

// "PATH: WHAT: REASON", the reason from errno (EIO when the system left none).
Error systemError(const fs::path& path, const std::string& what, int err) {
    return Error(FileLoc{path.string()}, what + ": " + std::strerror(err != 0 ? err : EIO));
}

Error openError(const fs::path& path, int err) { return systemError(path, "cannot open for writing", err); }
Error writeError(const fs::path& path, int err) { return systemError(path, "write failed", err); }

// Follows symbolic links (a dangling one too: its target is created), so that the file replaced is
// the one the link points at and the link itself stays. The temporary must sit in that file's
// directory, as rename() cannot cross file systems.
fs::path followLinks(const fs::path& named) {
    std::error_code ec;
    fs::path p = fs::absolute(named, ec);
    if (ec) throw openError(named, ec.value());
    for (int hops = 0; hops < 40; ++hops) {  // the kernel's own limit on links in a path
        if (!fs::is_symlink(fs::symlink_status(p, ec))) return p;
        const fs::path to = fs::read_symlink(p, ec);
        if (ec) throw openError(named, ec.value());
        p = to.is_absolute() ? to : p.parent_path() / to;
    }
    throw openError(named, ELOOP);
}

// Six letters or digits, different in each call and each process (mkstemp's XXXXXX; mkstemp itself
// is not used because it creates the file 0600 regardless of the umask).
std::string randomSuffix() {
    static std::atomic<uint64_t> counter{uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()) ^
                                         (uint64_t(::getpid()) << 32)};
    uint64_t z = counter.fetch_add(0x9e3779b97f4a7c15ull, std::memory_order_relaxed);  // splitmix64
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
    std::string s(6, ' ');
    for (char& c : s) {
        c = kAlphabet[z % 62];
        z /= 62;
    }
    return s;
}

// The rename is atomic, but durable only once the directory holding the new name reaches the disk:
// until then a power loss may bring back the previous file (whole, never a mix). Flushing it makes
// "wrote PATH" true when it is printed. Best effort: the file is in place whatever this returns, and
// some file systems cannot flush a directory.
void syncDirectory(const fs::path& dir) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    (void)::fsync(fd);
    ::close(fd);
}

}  // namespace

std::string temporaryNamePrefix(const fs::path& target) {
    // Room for the name within NAME_MAX (255): the dot, ".vkray-" and the six-letter suffix.
    const std::string name = target.filename().string();
    std::string prefix(1, '.');  // appended, not "." + name: GCC 12 warns falsely on that (bug 105329)
    prefix.append(name, 0, 255 - 1 - 7 - 6);
    prefix.append(".vkray-");
    return prefix;
}

void writeFileBytes(const fs::path& path, const void* bytes, size_t size) {
    StreamedFileWriter out(path);
    out.write(bytes, size);
    out.commit();
}

void writeFileText(const fs::path& path, std::string_view text) { writeFileBytes(path, text.data(), text.size()); }

StreamedFileWriter::StreamedFileWriter(const fs::path& path) : path_(path) {
    // The kernel follows the links here, /proc's too (/dev/stdout names a pipe or a terminal by a
    // link no path can follow), so a device or FIFO is recognised whatever the path to it.
    struct stat st {};
    const bool exists = ::stat(path_.c_str(), &st) == 0;
    if (!exists && errno != ENOENT) throw openError(path_, errno);
    if (exists && S_ISDIR(st.st_mode)) throw openError(path_, EISDIR);
    if (exists && !S_ISREG(st.st_mode)) {
        openDirect();
        return;
    }
    target_ = followLinks(path_);
    if (!exists) {
        openTemporary(0, false, 0, 0);  // a missing directory shows there
        return;
    }
    // A file the user made read-only stays theirs, as with fopen's O_TRUNC; the directory alone
    // would let the rename replace it.
    if (::faccessat(AT_FDCWD, target_.c_str(), W_OK, AT_EACCESS) != 0) throw openError(path_, errno);
    openTemporary(st.st_mode & 07777, true, st.st_uid, st.st_gid);
}

// A device or FIFO: written in place, never replaced or removed (it is not ours).
void StreamedFileWriter::openDirect() {
    fd_ = ::open(path_.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (fd_ < 0) throw openError(path_, errno);
}

void StreamedFileWriter::openTemporary(unsigned mode, bool exists, unsigned owner, unsigned group) {
    const fs::path dir = target_.parent_path();
    const std::string prefix = temporaryNamePrefix(target_);
    for (int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
        temp_ = dir / (prefix + randomSuffix());
        // Tracked before it exists, so no moment passes in which an interruption would leave it.
        slot_ = temp_files::track(temp_.c_str());
        // 0666 less the umask for a new file, as fopen gives; O_EXCL: never another writer's file.
        fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd_ >= 0) break;
        const int err = errno;
        temp_files::untrack(slot_);
        slot_ = -1;
        temp_.clear();
        if (err != EEXIST) throw openError(path_, err);
    }
    if (fd_ < 0) throw openError(path_, EEXIST);
    if (!exists) return;
    // The replacement is the same file to its user: same mode bits and, where the system lets us
    // (root writing a user's file), the same owner. Not being able to give a file away is no error:
    // the user then owns the new file, as after any editor's save by rename.
    if (owner != ::geteuid() || group != ::getegid()) {
        if (::fchown(fd_, owner, group) != 0) (void)::fchown(fd_, uid_t(-1), group);
    }
    if (::fchmod(fd_, mode) != 0) {
        const int err = errno;
        discard();  // the constructor throws: no destructor will
        throw writeError(path_, err);
    }
}

void StreamedFileWriter::discard() noexcept {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    if (!committed_ && !temp_.empty()) ::unlink(temp_.c_str());
    temp_files::untrack(slot_);  // after the unlink: an interruption in between finds nothing to do
    slot_ = -1;
}

StreamedFileWriter::~StreamedFileWriter() { discard(); }

void StreamedFileWriter::write(const void* data, size_t size) {
    const char* p = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t n = ::write(fd_, p, std::min(size, size_t(1) << 30));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw writeError(path_, n < 0 ? errno : EIO);  // a full disk shows here or at fsync
        p += n;
        size -= size_t(n);
    }
}

void StreamedFileWriter::commit() {
    if (temp_.empty()) {  // a device or FIFO: nothing to flush or rename
        const int closed = ::close(fd_);
        fd_ = -1;
        if (closed != 0 && errno != EINTR) throw writeError(path_, errno);
        committed_ = true;
        return;
    }
    // Flushed before the rename: file systems may put the rename on disk before the data (delayed
    // allocation in ext4 and XFS), and a crash would then leave PATH empty or short, the very
    // partial file the temporary is there to prevent.
    if (::fsync(fd_) != 0) throw writeError(path_, errno);
    const int closed = ::close(fd_);
    fd_ = -1;
    if (closed != 0 && errno != EINTR) throw writeError(path_, errno);
    if (::rename(temp_.c_str(), target_.c_str()) != 0) throw writeError(path_, errno);
    committed_ = true;
    temp_files::untrack(slot_);
    slot_ = -1;
    syncDirectory(target_.parent_path());
}

}  // namespace vkray
