#include "lsp/transport.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include "lsp/json_reader.h"

namespace lwc::lsp {
namespace {

constexpr size_t kMaxMessageBytes = 256u << 20;  // a bound on one message, so no client exhausts memory

// One framed message from the client. `end`: the input is over.
struct Frame {
  bool end = false;
  std::string body;
  std::string error;  // a header block the message cannot be read from
};

Frame read_frame(std::istream& in) {
  Frame f;
  std::optional<size_t> length;
  bool any = false;
  for (std::string line; std::getline(in, line);) {
    any = true;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) break;
    size_t colon = line.find(':');
    if (colon == std::string::npos) continue;  // not a header: the block's length decides
    std::string name = line.substr(0, colon);
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
    if (name != "content-length") continue;
    std::string value = line.substr(colon + 1);
    char* end = nullptr;
    unsigned long long n = std::strtoull(value.c_str(), &end, 10);
    if (end != value.c_str() && n <= kMaxMessageBytes) length = static_cast<size_t>(n);
  }
  if (!any) {
    f.end = true;
    return f;
  }
  if (!length) {
    f.error = "a message without a valid Content-Length header (at most 256 MB)";
    return f;
  }
  f.body.resize(*length);
  in.read(f.body.data(), static_cast<std::streamsize>(*length));
  if (static_cast<size_t>(in.gcount()) != *length) f.end = true;
  return f;
}

}  // namespace

json value_at(const json& object, std::initializer_list<const char*> path) {
  const json* at = &object;
  for (const char* key : path) {
    if (!at->is_object() || !at->contains(key)) return json();
    at = &(*at)[key];
  }
  return *at;
}

bool holds(const json& array, const char* value) { return array.is_array() && std::find(array.begin(), array.end(), value) != array.end(); }

std::string json_text(const json& value) { return value.dump(-1, ' ', false, json::error_handler_t::replace); }

std::optional<Incoming> Inbox::next() {
  std::unique_lock lock(mutex_);
  arrived_.wait(lock, [&] { return !queue_.empty() || done_; });
  if (queue_.empty()) return std::nullopt;
  Incoming in = std::move(queue_.front());
  queue_.pop_front();
  return in;
}

bool Inbox::take_cancel(const json& id) {
  std::lock_guard lock(mutex_);
  auto it = std::find_if(queue_.begin(), queue_.end(), [&](const Incoming& in) {
    return value_at(in.message, {"method"}) == "$/cancelRequest" && value_at(in.message, {"params", "id"}) == id;
  });
  if (it == queue_.end()) return false;
  queue_.erase(it);
  return true;
}

bool Inbox::change_waits(const std::string& uri) {
  std::lock_guard lock(mutex_);
  return std::any_of(queue_.begin(), queue_.end(), [&](const Incoming& in) {
    return value_at(in.message, {"method"}) == "textDocument/didChange" && value_at(in.message, {"params", "textDocument", "uri"}) == uri;
  });
}

void Inbox::read(std::istream& in) {
  for (;;) {
    Frame frame = read_frame(in);
    if (frame.end) break;
    Incoming incoming;
    if (!frame.error.empty()) {
      incoming.error = frame.error;
    } else {
      JsonRead read = read_json(frame.body);
      if (!read.error.empty() || !read.value.is_object()) {
        incoming.error = read.error.empty() ? "the message is not a JSON object" : "the message is not valid JSON: " + read.error;
      } else {
        incoming.message = std::move(read.value);
      }
      if (incoming.message.contains("params") && !incoming.message["params"].is_object() && !incoming.message["params"].is_array()) {
        incoming.message.erase("params");  // invalid; the handler reports what is missing
      }
    }
    bool exit = value_at(incoming.message, {"method"}) == "exit";
    {
      std::lock_guard lock(mutex_);
      queue_.push_back(std::move(incoming));
    }
    arrived_.notify_one();
    if (exit) break;  // nothing after `exit` is read: the server is gone
  }
  std::lock_guard lock(mutex_);
  done_ = true;
  arrived_.notify_one();
}

void write_frame(std::ostream& out, std::string_view body) {
  out << "Content-Length: " << body.size() << "\r\n\r\n" << body;
  out.flush();
}

}  // namespace lwc::lsp
