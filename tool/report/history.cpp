#include "report/history.h"

#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace lwc {

namespace fs = std::filesystem;

namespace {

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Runs a git command in `dir`; its standard output, or an error naming the command.
// Standard error is kept apart (a warning must not land in a blob's content) and its first line
// names the failure.
std::string git(const fs::path& dir, const std::string& args, const std::string& input_file = "") {
  fs::path errors = fs::temp_directory_path() / fmt::format("lwcport-git-{}.err", ::getpid());
  std::string command = "git -C " + quoted(dir.string()) + " " + args + (input_file.empty() ? "" : " < " + quoted(input_file)) + " 2>" +
                        quoted(errors.string());
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run git");
  std::string out;
  char buf[1 << 16];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  int status = ::pclose(pipe);
  std::ifstream err_file(errors);
  std::string first;
  std::getline(err_file, first);
  err_file.close();
  fs::remove(errors);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127) first = "git is not installed";
    throw std::runtime_error(fmt::format("git {}: {}", args.substr(0, args.find(' ')), first));
  }
  return out;
}

}  // namespace

fs::path git_top(const fs::path& dir) {
  std::string top = git(dir, "rev-parse --show-toplevel");
  while (!top.empty() && (top.back() == '\n' || top.back() == '\r')) top.pop_back();
  return top;
}

std::vector<CommitFiles> git_history(const fs::path& top, const std::vector<std::string>& paths, int count, const std::string& since) {
  std::string range = since.empty() ? fmt::format("-n {} HEAD", count) : quoted(since + "..HEAD");
  // One line per commit: hash, date, subject, separated by tabs (a subject holds no tab).
  std::string log = git(top, "log --first-parent --format=%H%x09%cI%x09%s " + range);
  std::vector<CommitFiles> commits;
  for (size_t at = 0; at < log.size();) {
    size_t end = log.find('\n', at);
    if (end == std::string::npos) end = log.size();
    std::string line = log.substr(at, end - at);
    at = end + 1;
    size_t a = line.find('\t'), b = a == std::string::npos ? a : line.find('\t', a + 1);
    if (b == std::string::npos) continue;
    commits.push_back({line.substr(0, a), line.substr(a + 1, b - a - 1), line.substr(b + 1), {}});
  }
  std::string pathspec;
  for (const std::string& p : paths) pathspec += " " + quoted(p);
  for (CommitFiles& c : commits) {
    // NUL-separated records: "<mode> blob <id>\t<path>".
    std::string tree = git(top, "ls-tree -r -z --full-tree " + c.commit + " --" + pathspec);
    for (size_t at = 0; at < tree.size();) {
      size_t end = tree.find('\0', at);
      if (end == std::string::npos) end = tree.size();
      std::string record = tree.substr(at, end - at);
      at = end + 1;
      size_t tab = record.find('\t');
      if (tab == std::string::npos || record.find(" blob ") == std::string::npos) continue;
      size_t id_at = record.find(" blob ") + 6;
      c.files.emplace_back(record.substr(tab + 1), record.substr(id_at, tab - id_at));
    }
  }
  std::reverse(commits.begin(), commits.end());
  return commits;
}

std::map<std::string, std::string> git_blobs(const fs::path& top, const std::set<std::string>& ids) {
  std::map<std::string, std::string> out;
  if (ids.empty()) return out;
  fs::path list = fs::temp_directory_path() / fmt::format("lwcport-blobs-{}.txt", ::getpid());
  {
    std::ofstream f(list);
    for (const std::string& id : ids) f << id << '\n';
  }
  std::string batch;
  try {
    batch = git(top, "cat-file --batch", list.string());
  } catch (...) {
    fs::remove(list);
    throw;
  }
  fs::remove(list);
  // Each: "<id> blob <size>\n<content>\n".
  for (size_t at = 0; at < batch.size();) {
    size_t nl = batch.find('\n', at);
    if (nl == std::string::npos) break;
    std::string header = batch.substr(at, nl - at);
    size_t sp1 = header.find(' '), sp2 = header.rfind(' ');
    if (sp1 == std::string::npos || header.find(" missing") != std::string::npos) {
      at = nl + 1;
      continue;
    }
    size_t size = std::stoul(header.substr(sp2 + 1));
    out[header.substr(0, sp1)] = batch.substr(nl + 1, size);
    at = nl + 1 + size + 1;
  }
  return out;
}

}  // namespace lwc
