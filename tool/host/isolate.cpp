#include "host/isolate.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "core/fd_io.h"

namespace lwc::host {

namespace {

// A worker's answer for one unit: a status byte, the length, the bytes.
enum Status : char { kDone = 0, kThrew = 1 };
constexpr size_t kHeader = 1 + sizeof(uint64_t);
constexpr size_t kNoUnit = SIZE_MAX;

// A worker process: it takes unit numbers from `orders` and answers each on `answers`, one unit
// after another (its warm heap serves the next unit: a fresh process per unit paid ~10% more CPU
// faulting its memory in). Each unit may use `cpu_seconds` more of CPU than the worker had used.
[[noreturn]] void serve(int orders, int answers, unsigned cpu_seconds, const std::function<std::string(size_t)>& work) {
  for (uint64_t unit; read_all(orders, reinterpret_cast<char*>(&unit), sizeof unit);) {
    struct rusage used {};
    ::getrusage(RUSAGE_SELF, &used);
    struct rlimit limit {};
    ::getrlimit(RLIMIT_CPU, &limit);
    limit.rlim_cur = static_cast<rlim_t>(used.ru_utime.tv_sec + used.ru_stime.tv_sec + 1) + cpu_seconds;
    if (limit.rlim_max != RLIM_INFINITY && limit.rlim_cur > limit.rlim_max) limit.rlim_cur = limit.rlim_max;
    ::setrlimit(RLIMIT_CPU, &limit);
    Status status = kDone;
    std::string bytes;
    try {
      bytes = work(static_cast<size_t>(unit));
    } catch (const std::exception& e) {
      bytes = e.what(), status = kThrew;
    } catch (...) {
      bytes = "an unknown exception", status = kThrew;
    }
    char header[kHeader];
    header[0] = status;
    uint64_t size = bytes.size();
    std::memcpy(header + 1, &size, sizeof size);
    if (!write_all(answers, std::string_view(header, kHeader)) || !write_all(answers, bytes)) ::_exit(1);
  }
  ::_exit(0);  // no more orders; not this program's exit handlers (they belong to the process it was copied from)
}

struct Worker {
  pid_t pid = -1;
  int orders = -1, answers = -1;
  size_t unit = kNoUnit;  // the unit it works on
  std::string bytes;      // what it has answered so far
};

// What became of a worker that ended in the middle of a unit.
std::string judged(int status, unsigned cpu_seconds) {
  if (WIFEXITED(status)) return fmt::format("the analysis ended with exit status {}", WEXITSTATUS(status));
  int sig = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  if (sig == SIGXCPU) return fmt::format("the analysis ran past {} seconds of CPU time and was stopped", cpu_seconds);
  bool crashed = sig == SIGSEGV || sig == SIGBUS || sig == SIGILL || sig == SIGFPE || sig == SIGABRT || sig == SIGTRAP;
  return fmt::format("the analysis {} (signal {}, {})", crashed ? "crashed" : "was ended", sig, ::strsignal(sig));
}

}  // namespace

void run_isolated(size_t count, unsigned jobs, unsigned cpu_seconds, const std::function<std::string(size_t)>& work,
                  const std::function<void(size_t, std::string&&)>& done, const std::function<void(size_t, const std::string&)>& failed) {
  // A worker that died leaves its order pipe without a reader: a write to it must fail, not end us.
  struct sigaction ignore {}, old {};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGPIPE, &ignore, &old);
  struct Restore {
    struct sigaction& old;
    ~Restore() { ::sigaction(SIGPIPE, &old, nullptr); }
  } restore{old};

  std::vector<Worker> workers;
  size_t next = 0;
  auto start = [&]() -> bool {
    int orders[2], answers[2];
    if (::pipe2(orders, O_CLOEXEC) != 0) return false;
    if (::pipe2(answers, O_CLOEXEC) != 0) {
      ::close(orders[0]), ::close(orders[1]);
      return false;
    }
    pid_t pid = ::fork();
    if (pid == 0) {
      // The other workers' pipes stay theirs: a copy held here would keep them from seeing the end.
      for (const Worker& w : workers) ::close(w.orders), ::close(w.answers);
      ::close(orders[1]), ::close(answers[0]);
      serve(orders[0], answers[1], cpu_seconds, work);
    }
    ::close(orders[0]), ::close(answers[1]);
    if (pid < 0) {
      ::close(orders[1]), ::close(answers[0]);
      return false;
    }
    workers.push_back({pid, orders[1], answers[0], kNoUnit, {}});
    return true;
  };
  // Gives the worker its next unit, or its end when there is none.
  auto assign = [&](Worker& w) {
    w.unit = kNoUnit;
    if (next >= count) {
      if (w.orders >= 0) ::close(w.orders);
      w.orders = -1;
      return;
    }
    uint64_t unit = next;
    if (!write_all(w.orders, std::string_view(reinterpret_cast<const char*>(&unit), sizeof unit))) return;  // it died: another takes the unit
    w.unit = next++;
  };

  while (next < count || !workers.empty()) {
    while (workers.size() < std::max(1u, jobs) && next < count) {
      if (!start()) {
        if (workers.empty()) {
          // Not even one process: every unit left says so.
          std::string why = fmt::format("no process could be started for it: {}", std::strerror(errno));
          for (; next < count; ++next) failed(next, why);
        }
        break;
      }
      assign(workers.back());
    }
    if (workers.empty()) break;
    std::vector<pollfd> fds;
    for (const Worker& w : workers) fds.push_back({w.answers, POLLIN, 0});
    if (::poll(fds.data(), fds.size(), -1) < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(fmt::format("waiting for the units' processes: {}", std::strerror(errno)));
    }
    for (size_t k = fds.size(); k-- > 0;) {
      if (!(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      Worker& w = workers[k];
      char buffer[1 << 16];
      ssize_t n = ::read(w.answers, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n > 0) {
        w.bytes.append(buffer, static_cast<size_t>(n));
        uint64_t size = 0;
        if (w.bytes.size() >= kHeader) std::memcpy(&size, w.bytes.data() + 1, sizeof size);
        if (w.bytes.size() < kHeader || w.bytes.size() - kHeader < size) continue;
        // A whole answer: its unit is done, and the worker gets the next.
        size_t unit = w.unit;
        Status status = static_cast<Status>(w.bytes[0]);
        std::string bytes = w.bytes.substr(kHeader, size);
        w.bytes.erase(0, kHeader + size);
        assign(w);
        if (status == kDone) done(unit, std::move(bytes));
        else failed(unit, "the analysis stopped: " + bytes);
        continue;
      }
      // The worker ended: after its last order, or in the middle of a unit.
      ::close(w.answers);
      if (w.orders >= 0) ::close(w.orders);
      int status = 0;
      while (::waitpid(w.pid, &status, 0) < 0 && errno == EINTR) {
      }
      size_t unit = w.unit;
      workers.erase(workers.begin() + static_cast<std::ptrdiff_t>(k));
      if (unit != kNoUnit) failed(unit, judged(status, cpu_seconds));
    }
  }
}

}  // namespace lwc::host
