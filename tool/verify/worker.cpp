#include "verify/worker.h"

#include <fmt/format.h>
#include <malloc.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

namespace lwc {

namespace {

using Clock = std::chrono::steady_clock;

// Messages are length-prefixed byte strings; inside them, numbers and length-prefixed blobs.
class Message {
 public:
  Message() { bytes_.reserve(256); }
  explicit Message(std::vector<uint8_t> bytes) : bytes_(std::move(bytes)) {}
  template <typename T>
  void put(T value) { append(&value, sizeof value); }
  void put_blob(const void* data, size_t size) {
    put<uint64_t>(size);
    append(data, size);
  }
  void put_string(const std::string& s) { put_blob(s.data(), s.size()); }
  template <typename T>
  T get() {
    T value{};
    if (at_ + sizeof value <= bytes_.size()) std::memcpy(&value, bytes_.data() + at_, sizeof value);
    at_ += sizeof value;
    return value;
  }
  std::vector<uint8_t> get_blob() {
    size_t size = get<uint64_t>();
    if (at_ + size > bytes_.size()) return {};
    std::vector<uint8_t> out(bytes_.begin() + static_cast<ptrdiff_t>(at_), bytes_.begin() + static_cast<ptrdiff_t>(at_ + size));
    at_ += size;
    return out;
  }
  std::string get_string() {
    std::vector<uint8_t> b = get_blob();
    return {b.begin(), b.end()};
  }
  const std::vector<uint8_t>& bytes() const { return bytes_; }

 private:
  void append(const void* data, size_t size) {
    const auto* bytes = static_cast<const uint8_t*>(data);
    bytes_.insert(bytes_.end(), bytes, bytes + size);
  }
  std::vector<uint8_t> bytes_;
  size_t at_ = 0;
};

bool send_all(int fd, const void* data, size_t size) {
  const auto* p = static_cast<const uint8_t*>(data);
  while (size) {
    ssize_t n = ::send(fd, p, size, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n, size -= static_cast<size_t>(n);
  }
  return true;
}

bool send_message(int fd, const Message& m) {
  uint64_t size = m.bytes().size();
  return send_all(fd, &size, sizeof size) && send_all(fd, m.bytes().data(), m.bytes().size());
}

enum class Received { ok, closed, timed_out };

// Reads exactly `size` bytes; with a deadline, gives up when it passes.
Received receive_all(int fd, void* data, size_t size, const Clock::time_point* deadline) {
  auto* p = static_cast<uint8_t*>(data);
  while (size) {
    if (deadline) {
      auto left = std::chrono::duration_cast<std::chrono::milliseconds>(*deadline - Clock::now()).count();
      if (left <= 0) return Received::timed_out;
      pollfd pfd{fd, POLLIN, 0};
      int ready = ::poll(&pfd, 1, static_cast<int>(std::min<long long>(left, 1000)));
      if (ready < 0 && errno != EINTR) return Received::closed;
      if (ready <= 0) continue;
    }
    ssize_t n = ::recv(fd, p, size, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return Received::closed;
    p += n, size -= static_cast<size_t>(n);
  }
  return Received::ok;
}

Received receive_message(int fd, Message& m, const Clock::time_point* deadline) {
  uint64_t size = 0;
  if (Received r = receive_all(fd, &size, sizeof size, deadline); r != Received::ok) return r;
  std::vector<uint8_t> bytes(size);
  if (Received r = receive_all(fd, bytes.data(), size, deadline); r != Received::ok) return r;
  m = Message(std::move(bytes));
  return Received::ok;
}

constexpr uint32_t kRunRequest = 0, kTimeRequest = 1;

std::vector<uint32_t> as_words(const std::vector<uint8_t>& bytes) {
  std::vector<uint32_t> words(bytes.size() / 4);
  if (!words.empty()) std::memcpy(words.data(), bytes.data(), words.size() * 4);
  return words;
}

// The child: opens the device, says so, then runs each kernel it is sent until the socket closes.
[[noreturn]] void serve(int fd) {
  // lavapipe on one thread: run times are the kernel's own work, not how two threads share the
  // machine with whatever else runs; functions verified side by side each have a process.
  setenv("LP_NUM_THREADS", "1", 0);
  std::string error;
  std::unique_ptr<ComputeDevice> device = ComputeDevice::open(error);
  Message hello;
  hello.put_string(error);
  hello.put_string(device ? device->name() : "");
  if (!send_message(fd, hello) || !device) _exit(0);
  // A request: its header, then each buffer's bytes. A reply: its header, then the bytes of the
  // buffers the kernel changed (inputs are not sent back: they are most of the traffic).
  for (Message request; receive_message(fd, request, nullptr) == Received::ok;) {
    auto kind = request.get<uint32_t>();
    if (kind == kTimeRequest) {
      TimingPlan plan;
      plan.min_rounds = request.get<int32_t>();
      plan.max_rounds = request.get<int32_t>();
      plan.max_spread = request.get<double>();
      plan.max_seconds = request.get<double>();
      plan.sample_seconds = request.get<double>();
      std::vector<uint64_t> kept(request.get<uint64_t>());
      for (uint64_t& id : kept) id = request.get<uint64_t>();
      InterleavedTiming timing;
      std::string problem = device->time_interleaved(kept, plan, timing);
      Message reply;
      reply.put_string(problem);
      reply.put<int32_t>(timing.rounds);
      reply.put<uint64_t>(timing.seconds.size());
      for (size_t k = 0; k < timing.seconds.size(); ++k) {
        reply.put<int32_t>(timing.dispatches_per_sample[k]);
        reply.put_blob(timing.seconds[k].data(), timing.seconds[k].size() * sizeof(double));
      }
      if (!send_message(fd, reply)) break;
      continue;
    }
    auto groups = request.get<uint32_t>();
    auto repeats = request.get<int32_t>();
    bool keep = request.get<uint8_t>();
    std::vector<uint32_t> spirv = as_words(request.get_blob());
    std::vector<std::vector<uint8_t>> buffers(request.get<uint64_t>());
    std::vector<uint8_t> wanted(buffers.size());
    for (size_t i = 0; i < buffers.size(); ++i) {
      buffers[i].resize(request.get<uint64_t>());
      wanted[i] = request.get<uint8_t>();
      if (receive_all(fd, buffers[i].data(), buffers[i].size(), nullptr) != Received::ok) _exit(0);
    }
    DispatchTiming timing;
    uint64_t kept = 0;
    std::string problem = device->run(spirv, buffers, groups, repeats, &timing, keep ? &kept : nullptr);
    Message reply;
    reply.put_string(problem);
    reply.put(timing.pipeline_seconds);
    reply.put_blob(timing.dispatch_seconds.data(), timing.dispatch_seconds.size() * sizeof(double));
    reply.put<uint64_t>(kept);
    for (size_t i = 0; i < buffers.size(); ++i) wanted[i] &= problem.empty();
    for (size_t i = 0; i < buffers.size(); ++i) reply.put<uint64_t>(wanted[i] ? buffers[i].size() : UINT64_MAX);
    if (!send_message(fd, reply)) break;
    for (size_t i = 0; i < buffers.size(); ++i)
      if (wanted[i] && !send_all(fd, buffers[i].data(), buffers[i].size())) _exit(0);
  }
  device.reset();
  _exit(0);
}

}  // namespace

std::unique_ptr<WorkerDevice> WorkerDevice::start(std::string& error, double timeout_seconds) {
  // Every kernel moves buffers of MBs (16,384 records) through both processes. By default glibc
  // maps each such block afresh and unmaps it on free, so every kernel faulted in new zeroed
  // pages: most of verify's time was the kernel's page-fault path. Keep freed blocks for reuse,
  // in one arena: with one per thread, each verifying thread kept its own high-water mark (the
  // host's peak 130 MB -> 92 MB on the corpus, no slower). Set before the fork, so the driver
  // process inherits it.
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_ARENA_MAX, 1);
  std::unique_ptr<WorkerDevice> device(new WorkerDevice(timeout_seconds));
  error = device->spawn();
  if (!error.empty()) return nullptr;
  return device;
}

WorkerDevice::~WorkerDevice() { stop(); }

std::string WorkerDevice::spawn() {
  int fds[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0)
    return fmt::format("cannot create a socket for the driver process: {}", std::strerror(errno));
  pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]), ::close(fds[1]);
    return fmt::format("cannot start the driver process: {}", std::strerror(errno));
  }
  if (pid == 0) {
    ::close(fds[0]);
    serve(fds[1]);
  }
  ::close(fds[1]);
  child_ = pid;
  ++generation_;
  socket_ = fds[0];
  Clock::time_point deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_seconds_));
  Message hello;
  if (Received r = receive_message(socket_, hello, &deadline); r != Received::ok) {
    std::string why = r == Received::timed_out ? fmt::format("opening the device took over {:g} s", timeout_seconds_)
                                               : "the driver process ended while opening the device (" + child_ended() + ")";
    stop();
    return why;
  }
  std::string error = hello.get_string();
  name_ = hello.get_string();
  if (!error.empty()) stop();
  return error;
}

void WorkerDevice::stop() {
  if (socket_ >= 0) ::close(socket_);
  socket_ = -1;
  if (child_ > 0) {
    ::kill(child_, SIGKILL);
    ::waitpid(child_, nullptr, 0);
  }
  child_ = -1;
}

std::string WorkerDevice::child_ended() {
  int status = 0;
  pid_t done = 0;
  // A closed socket means the child is exiting: give it a moment to finish dying.
  for (int i = 0; i < 100 && (done = ::waitpid(child_, &status, WNOHANG)) == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  if (done != child_) return "it stopped answering";
  child_ = -1;
  if (WIFSIGNALED(status)) return fmt::format("killed by signal {}, {}", WTERMSIG(status), strsignal(WTERMSIG(status)));
  return fmt::format("exit status {}", WEXITSTATUS(status));
}

std::string WorkerDevice::run(const std::vector<uint32_t>& spirv, std::vector<std::vector<uint8_t>>& buffers, uint32_t groups,
                              int repeats, DispatchTiming* timing, uint64_t* kept, const std::vector<bool>& read_back) {
  if (child_ < 0)
    if (std::string why = spawn(); !why.empty()) return "the driver process could not be restarted: " + why;
  Message request;
  request.put<uint32_t>(kRunRequest);
  request.put<uint32_t>(groups);
  request.put<int32_t>(repeats);
  request.put<uint8_t>(kept != nullptr);
  request.put_blob(spirv.data(), spirv.size() * 4);
  request.put<uint64_t>(buffers.size());
  for (size_t i = 0; i < buffers.size(); ++i) {
    request.put<uint64_t>(buffers[i].size());
    request.put<uint8_t>(read_back.empty() || (i < read_back.size() && read_back[i]));
  }
  bool sent = send_message(socket_, request);
  for (const auto& b : buffers) sent = sent && send_all(socket_, b.data(), b.size());
  Clock::time_point deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_seconds_));
  Message reply;
  Received r = sent ? receive_message(socket_, reply, &deadline) : Received::closed;
  std::string problem = reply.get_string();
  DispatchTiming t;
  t.pipeline_seconds = reply.get<double>();
  std::vector<uint8_t> seconds = reply.get_blob();
  t.dispatch_seconds.resize(seconds.size() / sizeof(double));
  if (!seconds.empty()) std::memcpy(t.dispatch_seconds.data(), seconds.data(), seconds.size());
  uint64_t kept_id = reply.get<uint64_t>();
  if (kept) *kept = generation_ << 32 | kept_id;  // ids of a restarted driver process never match
  for (size_t i = 0; i < buffers.size() && r == Received::ok; ++i)
    if (auto size = reply.get<uint64_t>(); size != UINT64_MAX) {
      buffers[i].resize(size);
      r = receive_all(socket_, buffers[i].data(), size, &deadline);
    }
  if (std::string lost = lost_child(static_cast<int>(r)); !lost.empty()) return lost;
  if (timing) *timing = t;
  return problem;
}

std::string WorkerDevice::lost_child(int received) {
  if (static_cast<Received>(received) == Received::timed_out) {
    stop();
    return fmt::format("did not finish within {:g} s (the shader hangs or is far too slow): its driver process was killed, "
                       "the next kernel gets a new one", timeout_seconds_);
  }
  if (static_cast<Received>(received) == Received::closed) {
    std::string how = child_ended();
    stop();
    return fmt::format("the driver crashed running this kernel ({}): the next kernel gets a new driver process", how);
  }
  return "";
}

std::string WorkerDevice::time_interleaved(const std::vector<uint64_t>& kept, const TimingPlan& plan, InterleavedTiming& out) {
  out = {};
  for (uint64_t id : kept)
    if (child_ < 0 || id >> 32 != generation_) return "the driver process was restarted, and the kernels to time went with the old one";
  Message request;
  request.put<uint32_t>(kTimeRequest);
  request.put<int32_t>(plan.min_rounds);
  request.put<int32_t>(plan.max_rounds);
  request.put<double>(plan.max_spread);
  request.put<double>(plan.max_seconds);
  request.put<double>(plan.sample_seconds);
  request.put<uint64_t>(kept.size());
  for (uint64_t id : kept) request.put<uint64_t>(id & 0xffffffffu);
  // Every kernel may take up to the timeout once, and the rounds their budget.
  Clock::time_point deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                                                  timeout_seconds_ * static_cast<double>(kept.size() + 1) + plan.max_seconds));
  Message reply;
  Received r = send_message(socket_, request) ? receive_message(socket_, reply, &deadline) : Received::closed;
  if (std::string lost = lost_child(static_cast<int>(r)); !lost.empty()) return lost;
  std::string problem = reply.get_string();
  out.rounds = reply.get<int32_t>();
  out.seconds.resize(reply.get<uint64_t>());
  out.dispatches_per_sample.resize(out.seconds.size());
  for (size_t k = 0; k < out.seconds.size(); ++k) {
    out.dispatches_per_sample[k] = reply.get<int32_t>();
    std::vector<uint8_t> bytes = reply.get_blob();
    out.seconds[k].resize(bytes.size() / sizeof(double));
    if (!bytes.empty()) std::memcpy(out.seconds[k].data(), bytes.data(), out.seconds[k].size() * sizeof(double));
  }
  return problem;
}

}  // namespace lwc
