#include "cli/files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
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
    InputFile f{path, std::move(display), nullptr, std::move(error), argument};
    f.config = configs.for_dir(path.parent_path().empty() ? fs::path(".") : path.parent_path());
    out.push_back(std::move(f));
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
        continue;
      }
      bool is_symlink = e.is_symlink(type_ec);
      bool regular = e.is_regular_file(type_ec);
      if (regular) add(e.path(), child);
      else if (is_symlink) add(e.path(), child, type_ec ? type_ec.message() : "broken symbolic link");
      else add(e.path(), child, "not a regular file");
    }
    walking.pop_back();
  }
};

}  // namespace

std::vector<InputFile> discover(const std::vector<std::string>& args, ConfigFinder& configs, std::vector<SkippedFile>* skipped) {
  Walker w{configs, skipped, {}, {}};
  for (const std::string& arg : args) {
    w.argument = static_cast<size_t>(&arg - args.data());
    fs::path p(arg);
    std::error_code ec;
    fs::file_status st = fs::status(p, ec);
    if (fs::is_directory(st)) w.walk_dir(p, arg);
    else w.add(p, arg, ec && !fs::is_symlink(fs::symlink_status(p)) ? ec.message() : std::string());
  }
  std::stable_sort(w.out.begin(), w.out.end(), [](const InputFile& a, const InputFile& b) { return a.display < b.display; });
  w.out.erase(std::unique(w.out.begin(), w.out.end(), [](const InputFile& a, const InputFile& b) { return a.display == b.display; }),
              w.out.end());
  return w.out;
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

bool write_all(int fd, std::string_view text) {
  size_t done = 0;
  while (done < text.size()) {
    ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}


// Writes text, with the given mode (and owner, when root), to a new temporary file beside
// `target` and syncs it: "" and its path in `temp`, or the reason nothing was written.
std::string write_temp_beside(const fs::path& target, std::string_view text, mode_t mode, const struct stat* owner, std::string& temp) {
  temp = (target.parent_path() / ("." + target.filename().string() + ".lwcport-XXXXXX")).string();
  int fd = ::mkstemp(temp.data());
  if (fd < 0) return fmt::format("cannot create a temporary file beside it: {}", std::strerror(errno));
  auto fail = [&](std::string why) {
    ::close(fd);
    ::unlink(temp.c_str());
    return why;
  };
  if (!write_all(fd, text)) return fail(fmt::format("cannot write: {}", std::strerror(errno)));
  if (::fchmod(fd, mode) != 0) return fail(fmt::format("cannot keep the file mode: {}", std::strerror(errno)));
  if (owner && ::geteuid() == 0 && ::fchown(fd, owner->st_uid, owner->st_gid) != 0)
    return fail(fmt::format("cannot keep the owner: {}", std::strerror(errno)));
  if (::fsync(fd) != 0) return fail(fmt::format("cannot write: {}", std::strerror(errno)));
  if (::close(fd) != 0) {
    ::unlink(temp.c_str());
    return fmt::format("cannot write: {}", std::strerror(errno));
  }
  return "";
}

}  // namespace

std::string replace_file(const fs::path& path, std::string_view expected, std::string_view text) {
  std::error_code ec;
  fs::path target = fs::canonical(path, ec);
  if (ec) return ec.message();
  struct stat st;
  if (::stat(target.c_str(), &st) != 0) return std::strerror(errno);
  // Read-only is the user's (or the version control's: Perforce) word that the file must not change.
  if (!(st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) || ::access(target.c_str(), W_OK) != 0)
    return fmt::format("read-only file (mode {:04o}); not changed", st.st_mode & 07777);
  ReadResult now = read_file(target, SIZE_MAX);
  if (!now.error.empty()) return now.error;
  if (now.text != expected) return "changed since it was read; not written (run lwcport fix again)";
  std::string temp;
  if (std::string why = write_temp_beside(target, text, st.st_mode & 07777, &st, temp); !why.empty()) return why;
  if (::rename(temp.c_str(), target.c_str()) != 0) {
    std::string why = std::strerror(errno);
    ::unlink(temp.c_str());
    return "cannot replace the file: " + why;
  }
  return "";
}

std::string create_file(const fs::path& path, std::string_view text) {
  mode_t mask = ::umask(0);
  ::umask(mask);
  std::string temp;
  if (std::string why = write_temp_beside(path, text, 0666 & ~mask, nullptr, temp); !why.empty()) return why;
  // link() never replaces: a file that appeared meanwhile is kept.
  int linked = ::link(temp.c_str(), path.c_str());
  int error = errno;
  ::unlink(temp.c_str());
  if (linked != 0) return error == EEXIST ? "exists already; not changed" : fmt::format("cannot create: {}", std::strerror(error));
  return "";
}

}  // namespace lwc
