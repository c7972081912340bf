#include "host/isolate.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <exception>
#include <vector>

#include <fmt/format.h>

namespace lwc::host {

namespace {

constexpr int kThrew = 3;  // the unit's work threw: its message is what the process wrote

bool write_all(int fd, const std::string& bytes) {
  for (size_t at = 0; at < bytes.size();) {
    ssize_t n = ::write(fd, bytes.data() + at, bytes.size() - at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    at += static_cast<size_t>(n);
  }
  return true;
}

// In the unit's process: the work, its bytes down the pipe, and out without running this
// program's exit handlers (they belong to the process it was copied from).
[[noreturn]] void child(size_t i, int fd, unsigned cpu_seconds, const std::function<std::string(size_t)>& work) {
  struct rlimit limit {cpu_seconds, cpu_seconds + 5};
  ::setrlimit(RLIMIT_CPU, &limit);
  int code = 0;
  std::string bytes;
  try {
    bytes = work(i);
  } catch (const std::exception& e) {
    bytes = e.what(), code = kThrew;
  } catch (...) {
    bytes = "an unknown exception", code = kThrew;
  }
  if (!write_all(fd, bytes)) code = code ? code : 1;
  ::_exit(code);
}

struct Running {
  size_t unit;
  pid_t pid;
  int fd;
  std::string bytes;
};

// What became of a unit's process, "" when it ended well.
std::string judged(int status, unsigned cpu_seconds, const std::string& bytes) {
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  if (WIFEXITED(status) && WEXITSTATUS(status) == kThrew) return "the analysis stopped: " + bytes;
  if (WIFEXITED(status)) return fmt::format("the analysis ended with exit status {}", WEXITSTATUS(status));
  int sig = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  if (sig == SIGXCPU) return fmt::format("the analysis ran past {} seconds of CPU time and was stopped", cpu_seconds);
  bool crashed = sig == SIGSEGV || sig == SIGBUS || sig == SIGILL || sig == SIGFPE || sig == SIGABRT || sig == SIGTRAP;
  return fmt::format("the analysis {} (signal {}, {})", crashed ? "crashed" : "was ended", sig, ::strsignal(sig));
}

}  // namespace

void run_isolated(size_t count, unsigned jobs, unsigned cpu_seconds, const std::function<std::string(size_t)>& work,
                  const std::function<void(size_t, std::string&&)>& done, const std::function<void(size_t, const std::string&)>& failed) {
  std::vector<Running> running;
  size_t next = 0;
  while (next < count || !running.empty()) {
    while (next < count && running.size() < std::max(1u, jobs)) {
      size_t unit = next++;
      int ends[2];
      if (::pipe2(ends, O_CLOEXEC) != 0) {
        failed(unit, fmt::format("no process could be started for it: {}", std::strerror(errno)));
        continue;
      }
      pid_t pid = ::fork();
      if (pid == 0) {
        ::close(ends[0]);
        child(unit, ends[1], cpu_seconds, work);
      }
      ::close(ends[1]);
      if (pid < 0) {
        ::close(ends[0]);
        failed(unit, fmt::format("no process could be started for it: {}", std::strerror(errno)));
        continue;
      }
      running.push_back({unit, pid, ends[0], {}});
    }
    if (running.empty()) continue;
    std::vector<pollfd> fds;
    for (const Running& r : running) fds.push_back({r.fd, POLLIN, 0});
    if (::poll(fds.data(), fds.size(), -1) < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(fmt::format("waiting for the units' processes: {}", std::strerror(errno)));
    }
    for (size_t k = fds.size(); k-- > 0;) {
      if (!(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      Running& r = running[k];
      char buffer[1 << 16];
      ssize_t n = ::read(r.fd, buffer, sizeof buffer);
      if (n > 0) {
        r.bytes.append(buffer, static_cast<size_t>(n));
        continue;
      }
      if (n < 0 && errno == EINTR) continue;
      // The end of its output: the process has finished (or closed the pipe by dying).
      ::close(r.fd);
      int status = 0;
      while (::waitpid(r.pid, &status, 0) < 0 && errno == EINTR) {
      }
      std::string why = judged(status, cpu_seconds, r.bytes);
      size_t unit = r.unit;
      std::string bytes = std::move(r.bytes);
      running.erase(running.begin() + static_cast<std::ptrdiff_t>(k));
      if (why.empty()) done(unit, std::move(bytes));
      else failed(unit, why);
    }
  }
}

}  // namespace lwc::host
