#include "project/files.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <sys/stat.h>
#include <sys/xattr.h>
#include <unistd.h>

#include <fmt/format.h>

#include "core/fd_io.h"

#include <algorithm>
#include <cctype>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <set>

namespace fs = std::filesystem;

namespace lwc {

namespace {

struct Walker {
  ConfigFinder& configs;
  std::vector<SkippedFile>* skipped;
  std::vector<InputFile> out;
  std::vector<std::pair<dev_t, ino_t>> walking;  // folders on the current path
  size_t argument = 0;

  void add(const fs::path& path, std::string display, std::string error = {}) {
    InputFile f{path, std::move(display), nullptr, std::move(error), argument, {}, {}};
    f.config = configs.for_dir(path.parent_path().empty() ? fs::path(".") : path.parent_path());
    out.push_back(std::move(f));
  }

  // Files of unmapped extensions, per configuration and extension: how many, and the one (the
  // first whose text reads as shader code) that carries the note, or none yet.
  struct Unmapped {
    size_t files = 0;
    std::optional<size_t> noted;
  };
  std::map<std::pair<const ProjectConfig*, std::string>, Unmapped> unmapped;

  // Nothing silent: an unmapped extension whose files read as shader code is named once.
  void sniff(const fs::path& path, const std::string& display, const std::shared_ptr<const ProjectConfig>& config) {
    std::string name = path.filename().string();
    size_t dot = name.rfind('.');
    if (dot == std::string::npos || dot == 0) return;
    std::string ext = name.substr(dot);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (not_shader_extensions().count(ext)) return;
    Unmapped& u = unmapped[{config.get(), ext}];
    ++u.files;
    if (u.noted) return;
    std::optional<ShaderEvidence> e = shader_evidence(path);
    if (!e) return;
    add(path, display);
    out.back().unmapped = InputFile::Unmapped{ext, e->language, e->words, 0};
    u.noted = out.size() - 1;
  }

  // After the walk: each note counts every other file of its extension.
  void count_unmapped() {
    for (const auto& [key, u] : unmapped)
      if (u.noted) out[*u.noted].unmapped->more = u.files - 1;
  }

  // The first 64 KiB of a regular file read as shader code, or none.
  static std::optional<ShaderEvidence> shader_evidence(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return std::nullopt;
    std::ifstream in(path, std::ios::binary);
    std::string start(1u << 16, '\0');
    in.read(start.data(), static_cast<std::streamsize>(start.size()));
    start.resize(static_cast<size_t>(in.gcount()));
    return reads_as_shader(start);
  }

  // Extensions of files that are never shader code (sources of other languages, data, media,
  // build files): not read.
  static const std::set<std::string>& not_shader_extensions() {
    static const std::set<std::string> set = {
        ".c", ".cc", ".cpp", ".cxx", ".h", ".hh", ".hpp", ".hxx", ".inl", ".ipp", ".m", ".mm", ".cs", ".java", ".py", ".rb", ".go",
        ".rs", ".swift", ".kt", ".lua", ".json", ".md", ".txt", ".rst", ".xml", ".yml", ".yaml", ".toml", ".ini", ".cfg", ".cmake",
        ".mk", ".sh", ".bat", ".cmd", ".ps1", ".png", ".jpg", ".jpeg", ".tga", ".dds", ".exr", ".hdr", ".bmp", ".gif", ".ico",
        ".svg", ".psd", ".ktx", ".uasset", ".umap", ".fbx", ".obj", ".gltf", ".glb", ".bin", ".spv", ".dxil", ".cso", ".o", ".a",
        ".so", ".dll", ".lib", ".exe", ".pdb", ".zip", ".gz", ".7z", ".tar", ".pdf", ".html", ".htm", ".css", ".ttf", ".otf",
        ".wav", ".mp3", ".ogg", ".uplugin", ".uproject", ".sln", ".vcxproj", ".filters", ".csproj", ".lock", ".log", ".csv",
        ".tsv", ".meta", ".asset", ".prefab", ".unity", ".mat", ".gitignore", ".gitattributes", ".editorconfig"};
    return set;
  }

  void walk_dir(const fs::path& dir, const std::string& display) {
    struct stat st;
    if (::stat(dir.c_str(), &st) != 0) {
      add(dir, display, std::strerror(errno));
      return;
    }
    auto id = std::make_pair(st.st_dev, st.st_ino);
    if (std::find(walking.begin(), walking.end(), id) != walking.end()) {
      add(dir, display, "symlink loop: this folder is already being walked; not followed");
      return;
    }
    walking.push_back(id);
    std::error_code ec;
    std::vector<fs::directory_entry> entries;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) entries.push_back(*it);
    if (ec) add(dir, display, ec.message());
    std::sort(entries.begin(), entries.end(), [](auto& a, auto& b) { return a.path().filename() < b.path().filename(); });
    auto config = configs.for_dir(dir);
    for (const auto& e : entries) {
      std::string name = e.path().filename().string();
      std::string child = display.empty() || display == "." ? name : (display.back() == '/' ? display + name : display + "/" + name);
      std::error_code type_ec;
      bool is_dir = e.is_directory(type_ec);
      if (name == ".git" || name == "node_modules") continue;
      if (config->excluded(e.path(), is_dir)) {
        if (skipped && !is_dir) skipped->push_back({child, "excluded by " + (config->dir / ".lwcport.json").string()});
        continue;
      }
      if (is_dir) {
        walk_dir(e.path(), child);
        continue;
      }
      if (!config->formats.for_path(name)) {
        if (skipped) skipped->push_back({child, "not a shader extension (map it in .lwcport.json \"extensions\")"});
        if (config->formats.mapped_extension(name).empty()) sniff(e.path(), child, config);
        continue;
      }
      bool is_symlink = e.is_symlink(type_ec);
      bool regular = e.is_regular_file(type_ec);
      if (regular) add(e.path(), child);
      else if (is_symlink) add(e.path(), child, unreadable_because(e.path(), type_ec ? type_ec.message() : "broken symbolic link"));
      else add(e.path(), child, "not a regular file");
    }
    walking.pop_back();
  }
};

}  // namespace

std::vector<InputFile> discover(const std::vector<std::string>& args, ConfigFinder& configs, std::vector<SkippedFile>* skipped) {
  Walker w{configs, skipped, {}, {}, {}, {}};
  for (const std::string& arg : args) {
    w.argument = static_cast<size_t>(&arg - args.data());
    fs::path p(arg);
    std::error_code ec;
    fs::file_status st = fs::status(p, ec);
    if (fs::is_directory(st)) w.walk_dir(p, arg);
    else w.add(p, arg, ec && !fs::is_symlink(fs::symlink_status(p)) ? ec.message() : std::string());
  }
  w.count_unmapped();
  std::stable_sort(w.out.begin(), w.out.end(), [](const InputFile& a, const InputFile& b) { return a.display < b.display; });
  w.out.erase(std::unique(w.out.begin(), w.out.end(), [](const InputFile& a, const InputFile& b) { return a.display == b.display; }),
              w.out.end());
  return w.out;
}

std::string unreadable_because(const fs::path& path, const std::string& error) {
  std::error_code ec;
  if (!fs::is_symlink(fs::symlink_status(path, ec))) return error;
  // A link in a loop is not dangling: its error says what it is.
  if (fs::exists(path, ec) || (ec && ec != std::errc::no_such_file_or_directory)) return error;
  fs::path target = fs::read_symlink(path, ec);
  return ec ? "dangling symbolic link: the file it points to does not exist"
            : fmt::format("dangling symbolic link to {}: the file it points to does not exist", target.string());
}

ReadResult read_file(const fs::path& path, size_t max_bytes) {
  ReadResult r;
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    r.error = std::strerror(errno);
    return r;
  }
  struct stat st;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    r.error = S_ISDIR(st.st_mode) ? "is a directory" : "not a regular file";
    ::close(fd);
    return r;
  }
  r.size = static_cast<size_t>(st.st_size);
  if (r.size > max_bytes) {
    r.too_large = true;
    ::close(fd);
    return r;
  }
  r.text.resize(r.size);
  size_t done = 0;
  while (done < r.size) {
    ssize_t n = ::read(fd, r.text.data() + done, r.size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      r.error = std::strerror(errno);
      break;
    }
    if (n == 0) break;
    done += static_cast<size_t>(n);
  }
  r.text.resize(done);
  ::close(fd);
  return r;
}

}  // namespace lwc

namespace lwc {

namespace {


// Temporary files being written, removed if the run is interrupted (SIGINT, SIGTERM, SIGHUP):
// fixed slots, so the signal handler only reads memory and calls unlink.
constexpr int kTempSlots = 64;
char temp_paths[kTempSlots][4096];
std::atomic<bool> temp_used[kTempSlots];
std::atomic<bool> dying{false};   // a signal came: create no more
std::atomic<int> uninterrupted{0};     // temporary files being created and not yet in a slot, or files being written in place

// Blocks the interrupting signals in the calling thread; returns the mask to restore.
sigset_t block_interrupts() {
  sigset_t set, old;
  sigemptyset(&set);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&set, sig);
  ::pthread_sigmask(SIG_BLOCK, &set, &old);
  return old;
}

// A stretch of work no interrupt may cut in two: no signal in this thread meanwhile, and the
// handler (on another thread) waits for it to end before it removes the temporary files and dies.
struct Uninterrupted {
  sigset_t old = block_interrupts();
  Uninterrupted() { ++uninterrupted; }
  ~Uninterrupted() {
    --uninterrupted;
    ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
  }
};

// Creates a temporary file from `name` (a mkstemp template, given back with the file's name).
// mkstemp fills in the name inside its slot, so a signal at any moment finds it there.
int make_temp(std::string& name, int& slot) {
  Uninterrupted while_recorded;
  if (dying) {
    errno = EINTR;
    return -1;
  }
  slot = -1;
  if (name.size() < sizeof(temp_paths[0]))
    for (int i = 0; i < kTempSlots && slot < 0; ++i) {
      bool expected = false;
      if (!temp_used[i].load() && temp_used[i].compare_exchange_strong(expected, true)) slot = i;
    }
  if (slot < 0) return ::mkstemp(name.data());  // more writers than slots: not cleaned up on a signal
  std::memcpy(temp_paths[slot], name.c_str(), name.size() + 1);
  int fd = ::mkstemp(temp_paths[slot]);
  name = temp_paths[slot];
  return fd;
}

void release_temp(int slot) {
  if (slot >= 0) temp_used[slot].store(false);
}

extern "C" void remove_temps_and_die(int sig) {
  dying = true;
  while (uninterrupted.load() > 0) {
  }
  for (int i = 0; i < kTempSlots; ++i)
    if (temp_used[i].load()) ::unlink(temp_paths[i]);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

// A temporary file beside a target, registered for removal on a signal and removed when done
// unless kept.
struct TempFile {
  std::string path;
  int slot = -1;
  bool keep = false;
  ~TempFile() {
    if (!path.empty() && !keep) ::unlink(path.c_str());
    release_temp(slot);
  }
};

// Copies the extended attributes of `from` (an open file) to `to`; "" or the reason.
std::string copy_xattrs(int from, int to) {
  ssize_t size = ::flistxattr(from, nullptr, 0);
  if (size < 0) return errno == ENOTSUP ? "" : fmt::format("cannot read its extended attributes: {}", std::strerror(errno));
  std::string names(static_cast<size_t>(size), '\0');
  size = ::flistxattr(from, names.data(), names.size());
  if (size < 0) return fmt::format("cannot read its extended attributes: {}", std::strerror(errno));
  for (size_t at = 0; at < static_cast<size_t>(size); at += std::strlen(names.c_str() + at) + 1) {
    const char* name = names.c_str() + at;
    ssize_t n = ::fgetxattr(from, name, nullptr, 0);
    if (n < 0) return fmt::format("cannot read extended attribute {}: {}", name, std::strerror(errno));
    std::string value(static_cast<size_t>(n), '\0');
    n = ::fgetxattr(from, name, value.data(), value.size());
    if (n < 0 || ::fsetxattr(to, name, value.data(), static_cast<size_t>(n), 0) != 0)
      return fmt::format("cannot keep extended attribute {}: {}", name, std::strerror(errno));
  }
  return "";
}

// Writes text to a new temporary file beside `target` and syncs it, with the mode, owner (when
// root) and extended attributes of `original` (an open file) when given, else `mode`: "" and
// its path in `temp`, or the reason nothing was written.
std::string write_temp_beside(const fs::path& target, std::string_view text, mode_t mode, int original, TempFile& temp) {
  std::string name = (target.parent_path() / ("." + target.filename().string() + ".lwcport-XXXXXX")).string();
  int fd = make_temp(name, temp.slot);
  if (fd < 0) return fmt::format("cannot create a temporary file beside it: {}", std::strerror(errno));
  temp.path = name;
  auto fail = [&](std::string why) {
    ::close(fd);
    return why;
  };
  if (!write_all(fd, text)) return fail(fmt::format("cannot write: {}", std::strerror(errno)));
  if (original >= 0) {
    struct stat st;
    if (::fstat(original, &st) != 0) return fail(std::strerror(errno));
    // Owner first: chown clears the setuid and setgid bits, which the mode then restores.
    if (::geteuid() == 0 && ::fchown(fd, st.st_uid, st.st_gid) != 0)
      return fail(fmt::format("cannot keep the owner: {}", std::strerror(errno)));
    mode = st.st_mode & 07777;
    if (std::string why = copy_xattrs(original, fd); !why.empty()) return fail(why);
  }
  if (::fchmod(fd, mode) != 0) return fail(fmt::format("cannot keep the file mode: {}", std::strerror(errno)));
  if (::fsync(fd) != 0) return fail(fmt::format("cannot write: {}", std::strerror(errno)));
  if (::close(fd) != 0) return fmt::format("cannot write: {}", std::strerror(errno));
  return "";
}

}  // namespace

void block_interrupts_in_this_thread() { block_interrupts(); }

void remove_temporary_files_on_signals() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction action {};
    action.sa_handler = remove_temps_and_die;
    sigemptyset(&action.sa_mask);
    ::sigaction(sig, &action, nullptr);
  }
}

namespace {

// A lease: the kernel tells (and holds back) whoever opens the file while it is held. A write
// lease is refused while anyone else has the file open at all, and holds back every later opener
// until it is released; a read lease is refused while it is open for writing, and holds back
// openers for writing.
enum class Lease { held, open_elsewhere, unavailable };

Lease take_lease(int fd, int type) {
  // A broken lease is announced with SIGIO, whose default action ends the process; we poll instead.
  static const bool ignored = [] {
    struct sigaction action {};
    action.sa_handler = SIG_IGN;
    return ::sigaction(SIGIO, &action, nullptr) == 0;
  }();
  if (!ignored) return Lease::unavailable;
  if (::fcntl(fd, F_SETLEASE, type) == 0) return Lease::held;
  // EAGAIN: open elsewhere. EACCES (not the owner), EINVAL (file system, or leases off): no lease.
  return errno == EAGAIN ? Lease::open_elsewhere : Lease::unavailable;
}

const std::string kChanged = "changed since it was read; not written (run lwcport fix again)";
const std::string kOpenElsewhere = "open in another program; not changed (close it and run lwcport fix again)";

// The file's bytes, read through `fd` from its start ("" and false on an error).
bool read_whole(int fd, std::string& out) {
  out.clear();
  char buffer[1 << 16];
  for (off_t at = 0;;) {
    ssize_t n = ::pread(fd, buffer, sizeof buffer, at);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return false;
    if (n == 0) return true;
    out.append(buffer, static_cast<size_t>(n));
    at += n;
  }
}

// The file rewritten in place through `fd` (open for reading and writing, a write lease held):
// no one else has it open, and whoever opens it now waits until the lease goes with `fd`, then
// finds the new text whole. Nothing can write into it unseen, and no save is lost: a program that
// found it by name just before opens this same file (there is no other) after us.
std::string write_in_place(const fs::path& target, int fd, const struct stat& st, std::string_view expected, std::string_view text) {
  // Read through our own descriptor: opening it again would wait on our own lease.
  std::string now;
  if (!read_whole(fd, now)) return std::strerror(errno);
  if (now != expected) return kChanged;
  // The old text beside it until the new one is on disk: a crash or power cut mid-write leaves it there.
  TempFile journal;
  if (std::string why = write_temp_beside(target, expected, 0600, -1, journal); !why.empty()) return why;
  std::string failed;
  {
    Uninterrupted whole;  // an interrupt waits for the write, so the file is never left half written
    if (::pwrite(fd, text.data(), text.size(), 0) != static_cast<ssize_t>(text.size()) || ::ftruncate(fd, static_cast<off_t>(text.size())) != 0 ||
        ::fsync(fd) != 0)
      failed = std::strerror(errno);
    // The kernel clears the setuid and setgid bits on a write by anyone but root: given back.
    struct stat after;
    if (failed.empty() && ::fstat(fd, &after) == 0 && (after.st_mode & 07777) != (st.st_mode & 07777) && ::fchmod(fd, st.st_mode & 07777) != 0)
      failed = fmt::format("cannot keep the file mode: {}", std::strerror(errno));
  }
  if (!failed.empty()) {
    journal.keep = true;
    return fmt::format("cannot write: {}; its content before is kept in {}", failed, journal.path);
  }
  // A save that renamed a new file over this name meanwhile (renames open nothing) stands: ours
  // went to the file it replaced.
  struct stat named;
  if (::stat(target.c_str(), &named) != 0 || named.st_ino != st.st_ino || named.st_dev != st.st_dev) return kChanged;
  return "";
}

// A new file swapped in for the old, where no write lease can be had (not the file's owner, a
// network file system, leases off) or one name of a hard-linked file is to change alone. `original`
// is open read-only; a read lease on it, where the kernel allows one, catches an editor that opened
// the file for writing and has not written yet.
std::string replace_by_swap(const fs::path& target, int original, std::string_view expected, std::string_view text) {
  Lease lease = take_lease(original, F_RDLCK);
  if (lease == Lease::open_elsewhere) return kOpenElsewhere;
  // Opening it to read does not break a read lease; an opener for writing does.
  auto unchanged = [&](const fs::path& at) {
    return read_file(at, SIZE_MAX).text == expected && (lease != Lease::held || ::fcntl(original, F_GETLEASE) == F_RDLCK);
  };
  if (!unchanged(target)) return kChanged;
  TempFile temp;
  if (std::string why = write_temp_beside(target, text, 0, original, temp); !why.empty()) return why;
  // The swap: the file as it is at this instant comes out at the temporary path and is checked
  // there (content, and the lease not broken by an opener for writing), so an edit saved at any
  // moment before is caught and put back, never overwritten.
  if (::renameat2(AT_FDCWD, temp.path.c_str(), AT_FDCWD, target.c_str(), RENAME_EXCHANGE) == 0) {
    // Left open: an opener that found the old file by name before the swap and reaches the
    // lease only after this check (a few microseconds inside the kernel) writes to the old file.
    // The write lease above closes it wherever the kernel gives one.
    if (unchanged(temp.path)) return "";
    ::renameat2(AT_FDCWD, temp.path.c_str(), AT_FDCWD, target.c_str(), RENAME_EXCHANGE);
    // What is now at the temporary path should be our text; anything else is an edit made in
    // the moment between the two swaps: kept, and said where.
    if (read_file(temp.path, SIZE_MAX).text != text) {
      temp.keep = true;
      return kChanged + "; an edit made while writing is kept in " + temp.path;
    }
    return kChanged;
  }
  if (errno != EINVAL && errno != ENOSYS && errno != ENOTSUP) return "cannot replace the file: " + std::string(std::strerror(errno));
  // A file system without the swap: check once more right before the rename.
  if (!unchanged(target)) return kChanged;
  if (::rename(temp.path.c_str(), target.c_str()) != 0) return "cannot replace the file: " + std::string(std::strerror(errno));
  temp.path.clear();
  return "";
}

}  // namespace

std::string replace_file(const fs::path& path, std::string_view expected, std::string_view text, bool split_links) {
  std::error_code ec;
  fs::path target = fs::canonical(path, ec);
  if (ec) return ec.message();
  int fd = ::open(target.c_str(), O_RDWR | O_CLOEXEC);
  bool writable = fd >= 0;
  if (!writable) fd = ::open(target.c_str(), O_RDONLY | O_CLOEXEC);  // for the reason it cannot be written
  if (fd < 0) return std::strerror(errno);
  struct Closer {
    int& fd;
    ~Closer() { ::close(fd); }  // releases a lease, and lets a held-back opener go on
  } closer{fd};
  struct stat st;
  if (::fstat(fd, &st) != 0) return std::strerror(errno);
  // Read-only is the user's (or the version control's: Perforce) word that the file must not change.
  if (!(st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) || ::access(target.c_str(), W_OK) != 0 || !writable)
    return fmt::format("read-only file (mode {:04o}); not changed", st.st_mode & 07777);
  // A new file renamed over one name would leave the other names with the old content.
  if (st.st_nlink > 1 && !split_links)
    return fmt::format("it has {} hard links and replacing it would split them; not changed (fix a copy, break the links, "
                       "or run with --force to replace this name only)", st.st_nlink);
  if (st.st_nlink == 1) {
    Lease lease = take_lease(fd, F_WRLCK);
    if (lease == Lease::held) return write_in_place(target, fd, st, expected, text);
    if (lease == Lease::open_elsewhere) return kOpenElsewhere;
  }
  // The read lease needs a descriptor that does not write.
  ::close(fd);
  fd = ::open(target.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::strerror(errno);
  return replace_by_swap(target, fd, expected, text);
}

std::string create_file(const fs::path& path, std::string_view text) {
  mode_t mask = ::umask(0);
  ::umask(mask);
  TempFile temp;
  if (std::string why = write_temp_beside(path, text, 0666 & ~mask, -1, temp); !why.empty()) return why;
  // link() never replaces: a file that appeared meanwhile is kept.
  int linked = ::link(temp.path.c_str(), path.c_str());
  int error = errno;
  if (linked != 0) return error == EEXIST ? "exists already; not changed" : fmt::format("cannot create: {}", std::strerror(error));
  return "";
}

}  // namespace lwc
