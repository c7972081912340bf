#include "lsp/transport.h"

#include <algorithm>
#include <charconv>
#include <cstring>

#include <fmt/format.h>

#include "core/source.h"
#include "lsp/json_reader.h"

namespace lwc::lsp {
namespace {

constexpr size_t kMaxMessageBytes = 256u << 20;  // a bound on one message, so no client exhausts memory
// A "header" with a longer line, or more lines, is not one.
constexpr size_t kMaxHeaderLine = 4096, kMaxHeaderLines = 32;
constexpr std::string_view kLengthName = "content-length";
constexpr size_t npos = std::string_view::npos;

char lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

// `text` is "Content-Length", or a start of it, in any case.
bool starts_length_name(std::string_view text) {
  if (text.size() > kLengthName.size()) return false;
  for (size_t i = 0; i < text.size(); ++i)
    if (lower(text[i]) != kLengthName[i]) return false;
  return true;
}

// `text` holds "Content-Length" (in any case) at `at`.
bool length_name_at(std::string_view text, size_t at) {
  return at <= text.size() && text.size() - at >= kLengthName.size() && starts_length_name(text.substr(at, kLengthName.size()));
}

// Where in `text` a header that may start a message begins: "Content-Length", spaces, ':'.
size_t find_length_header(std::string_view text) {
  for (size_t at = 0; at + kLengthName.size() <= text.size(); ++at) {
    if (!length_name_at(text, at)) continue;
    size_t colon = text.find_first_not_of(" \t", at + kLengthName.size());
    if (colon != npos && text[colon] == ':') return at;
  }
  return npos;
}

// How many bytes at the end of `text` may begin a "Content-Length" header (its name, or a start
// of it, or it and spaces): a Content-Length that cuts the next header in two.
size_t header_start_at_end(std::string_view text) {
  for (size_t k = std::min(text.size(), kLengthName.size() + 8); k > 0; --k) {
    std::string_view tail = text.substr(text.size() - k);
    size_t name = std::min(k, kLengthName.size());
    if (starts_length_name(tail.substr(0, name)) && tail.find_first_not_of(" \t", name) == npos) return k;
  }
  return 0;
}

// A byte of a header's name (an HTTP token).
bool is_token_byte(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || (c != '\0' && std::strchr("!#$%&'*+-.^_`|~", c));
}

std::string_view trimmed(std::string_view s) {
  size_t begin = s.find_first_not_of(" \t");
  if (begin == npos) return {};
  return s.substr(begin, s.find_last_not_of(" \t") - begin + 1);
}

// The first bytes of `bytes` as printable text (any other byte as \xNN), for the log.
std::string excerpt(std::string_view bytes, size_t most = 60) {
  std::string out;
  for (size_t i = 0; i < bytes.size() && i < most; ++i) {
    unsigned char c = static_cast<unsigned char>(bytes[i]);
    if (c >= 0x20 && c < 0x7F) out += static_cast<char>(c);
    else out += fmt::format("\\x{:02X}", c);
  }
  return bytes.size() > most ? out + "..." : out;
}

// Where a JSON object at the start of some bytes ends, found as the bytes come (strings and their
// escapes followed): a message whose framing was wrong is read as soon as its last byte is here.
class ObjectEnd {
 public:
  enum State { before, inside, closed, none };  // none: the bytes are not one object

  void feed(char c) {
    bool space = c == ' ' || c == '\t' || c == '\r' || c == '\n';
    if (state_ == before && !space) state_ = c == '{' ? inside : none;
    else if (state_ == closed && !space) state_ = none;
    if (state_ != inside) return;
    if (in_string_) {
      if (escaped_) escaped_ = false;
      else if (c == '\\') escaped_ = true;
      else if (c == '"') in_string_ = false;
    } else if (c == '"') {
      in_string_ = true;
    } else if (c == '{' || c == '[') {
      ++depth_;
    } else if ((c == '}' || c == ']') && --depth_ == 0) {
      state_ = closed;
    }
  }
  State state() const { return state_; }
  void give_up() { state_ = none; }

  // The bytes past the end of the object at the start of `bytes`; npos when it does not end there.
  static size_t after(std::string_view bytes) {
    ObjectEnd end;
    for (size_t i = 0; i < bytes.size(); ++i) {
      end.feed(bytes[i]);
      if (end.state() == closed) return i + 1;
      if (end.state() == none) break;
    }
    return npos;
  }

 private:
  State state_ = before;
  long depth_ = 0;
  bool in_string_ = false, escaped_ = false;
};

Incoming read_as(json message, std::string framing = "") {
  Incoming in;
  in.message = std::move(message);
  in.framing = std::move(framing);
  return in;
}

// A block of "Name: value" lines up to an empty line, as it starts a message.
struct Header {
  enum Kind { message, broken, junk, end } kind = junk;
  size_t length = 0;    // of the message's body
  std::string problem;  // why it gives no length (broken)
  size_t size = 0;      // its bytes
};

// Bytes no message was read from, gathered up to the next header: one message whose framing was
// wrong (then it is read from them) or junk (dropped).
struct Dropped {
  std::string bytes;               // the first kMaxMessageBytes of them
  size_t count = 0;                // all of them
  std::string problem;             // what was found wrong first
  std::optional<size_t> declared;  // the Content-Length their first part was read with
  ObjectEnd object;                // where the object they start ends

  bool empty() const { return count == 0 && problem.empty() && !declared; }

  void add(std::string_view more) {
    count += more.size();
    bytes.append(more.substr(0, kMaxMessageBytes - std::min(bytes.size(), kMaxMessageBytes)));
    for (char c : more) object.feed(c);
  }

  // A message read from them, with what was wrong with its framing; or why none could be.
  Incoming finish() const {
    Incoming in;
    if (count == bytes.size()) {
      JsonRead r = read_json(bytes);
      if (r.error.empty() && r.value.is_object())
        return read_as(std::move(r.value), declared && count > *declared   ? fmt::format("its Content-Length ({}) was less than its {} bytes", *declared, count)
                                           : declared && count < *declared ? fmt::format("its Content-Length ({}) was more than its {} bytes", *declared, count)
                                           : !problem.empty()              ? problem
                                                                           : "it came without a Content-Length header");
    }
    if (declared && count == *declared) {
      in.error = "the message is not valid JSON: " + problem;
    } else {
      std::string why = !problem.empty() ? problem : "no Content-Length header came before them";
      if (declared) why = fmt::format("read with a Content-Length of {}: {}", *declared, why);
      in.error = count == 0 ? fmt::format("a header no message came after ({})", why)
                            : fmt::format("{} bytes that are not a message were dropped ({})", count, why);
    }
    in.dropped = excerpt(bytes);
    return in;
  }
};

// The client's stream cut into messages. After a framing error (a Content-Length that is not a
// number, too large, less or more than the body, or bytes that are no message at all) it
// resynchronises: what follows is read as the message it turns out to be, or dropped up to the
// next "Content-Length" header.
class MessageReader {
 public:
  explicit MessageReader(std::istream& in) : in_(in) {}

  // The next message, or what was dropped and why; none at the end of the input.
  std::optional<Incoming> next() {
    Dropped dropped;
    for (;;) {
      buffer_.erase(0, pos_);
      pos_ = 0;
      if (dropped.empty())  // line ends between messages are no error
        while (have(1) && (buffer_[pos_] == '\r' || buffer_[pos_] == '\n')) ++pos_;
      Header h = header();
      if (h.kind == Header::end) return dropped.empty() ? std::nullopt : std::optional(dropped.finish());
      if (h.kind == Header::junk) {
        dropped.add(std::string_view(buffer_).substr(pos_++, 1));
        if (!skip_to_length_header(dropped)) continue;
        Incoming in = dropped.finish();  // an object ended: the message whose framing was wrong, if it is one
        if (in.message.is_object()) return in;
        dropped.object.give_up();
        continue;
      }
      if (!dropped.empty()) return dropped.finish();  // the header after them is read again next time
      pos_ += h.size;
      if (h.kind == Header::broken) {
        dropped.problem = h.problem;
        continue;
      }
      bool whole = have(h.length);
      std::string_view body = std::string_view(buffer_).substr(pos_, h.length);
      dropped.declared = h.length;
      if (whole) {
        JsonRead r = read_json(body);
        if (r.error.empty()) {
          pos_ += body.size();
          if (r.value.is_object()) return read_as(std::move(r.value));
          Incoming batch;
          batch.error = "the message is JSON but not an object (LSP sends no batches)";
          batch.code = kInvalidRequest;
          return batch;
        }
        dropped.problem = r.error;
      }
      // Not a message as framed. An object at its start, or a header inside it, says where the
      // message ends.
      if (size_t end = ObjectEnd::after(body); end < body.size()) {
        JsonRead r = read_json(body.substr(0, end));
        if (r.error.empty() && r.value.is_object()) {
          pos_ += end;
          return read_as(std::move(r.value), fmt::format("its Content-Length ({}) was more than its {} bytes", h.length, end));
        }
      }
      if (size_t next = find_length_header(body); next != npos) {
        dropped.add(body.substr(0, next));
        pos_ += next;
        return dropped.finish();
      }
      // What may start the next header is read again as such.
      size_t kept = header_start_at_end(body);
      dropped.add(body.substr(0, body.size() - kept));
      pos_ += body.size() - kept;
      // One whole object that is no message, or no object at all: no byte after it can mend it.
      if (whole && dropped.object.state() != ObjectEnd::inside) return dropped.finish();
    }
  }

 private:
  // `n` bytes from `pos_` are buffered; false when the input ends first. Read only as needed (the
  // client waits for answers before it sends more), a megabyte at a time (a Content-Length no body
  // follows costs no memory).
  bool have(size_t n) {
    while (buffer_.size() - pos_ < n) {
      if (ended_) return false;
      size_t want = std::min<size_t>(n - (buffer_.size() - pos_), 1u << 20), old = buffer_.size();
      buffer_.resize(old + want);
      in_.read(buffer_.data() + old, static_cast<std::streamsize>(want));
      buffer_.resize(old + static_cast<size_t>(in_.gcount()));
      if (buffer_.size() < old + want) ended_ = true;
    }
    return true;
  }

  // A byte at `at` (an index into buffer_), read if need be; '\0' past the end of the input.
  char byte(size_t at) { return have(at - pos_ + 1) ? buffer_[at] : '\0'; }

  // The header block at pos_. It is junk from its first byte that no header can hold, so no
  // bytes are waited for that a header would not need.
  Header header() {
    if (!have(1)) return {Header::end, 0, "", 0};
    Header h;
    size_t length = npos;  // none yet
    size_t at = pos_;
    for (size_t lines = 0;; ++lines) {
      if (byte(at) == '\n' || (byte(at) == '\r' && byte(at + 1) == '\n')) {
        if (lines == 0) return h;  // no header before it: junk (a message after it is read from its object)
        at += byte(at) == '\r' ? 2 : 1;
        break;
      }
      if (lines == kMaxHeaderLines) return h;
      size_t name = at;
      while (is_token_byte(byte(at)) && at - name < kMaxHeaderLine) ++at;
      size_t name_end = at;
      while ((byte(at) == ' ' || byte(at) == '\t') && at - name < kMaxHeaderLine) ++at;  // HTTP has none here; a client may
      if (name_end == name || byte(at) != ':') return h;
      size_t colon = at;
      while (byte(at) != '\n' && byte(at) != '\0' && at - name < kMaxHeaderLine) ++at;
      if (byte(at) != '\n') return h;
      std::string_view line(buffer_.data() + name, at - name);
      if (line.back() == '\r') line.remove_suffix(1);
      ++at;
      if (name_end - name != kLengthName.size() || !length_name_at(line, 0)) continue;
      std::string_view value = trimmed(line.substr(colon - name + 1));
      size_t n = 0;
      auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), n);
      length = npos;
      if (value.empty() || end != value.data() + value.size() || error == std::errc::invalid_argument)
        h.problem = fmt::format("its Content-Length \"{}\" is not a number", excerpt(value));
      else if (error == std::errc::result_out_of_range || n > kMaxMessageBytes)
        h.problem = fmt::format("its Content-Length ({}) is more than the 256 MB a message may have", excerpt(value));
      else
        length = n;
    }
    h.size = at - pos_;
    h.kind = length != npos ? Header::message : Header::broken;
    h.length = length != npos ? length : 0;
    if (length == npos && h.problem.empty()) h.problem = "its header has no Content-Length";
    return h;
  }

  // Drops bytes up to the next "Content-Length" (in any case) or the end of the input (false), or
  // up to the end of an object the dropped bytes started (true).
  bool skip_to_length_header(Dropped& dropped) {
    for (;;) {
      if (dropped.object.state() == ObjectEnd::closed) return true;
      if (!have(1)) return false;
      // Looked for only at a 'c': a closing brace is never waited past.
      if (lower(buffer_[pos_]) == 'c' && have(kLengthName.size()) && length_name_at(buffer_, pos_)) return false;
      dropped.add(std::string_view(buffer_).substr(pos_++, 1));
      if (pos_ >= (1u << 16)) {
        buffer_.erase(0, pos_);
        pos_ = 0;
      }
    }
  }

  std::istream& in_;
  std::string buffer_;  // bytes read and not taken yet, from pos_
  size_t pos_ = 0;
  bool ended_ = false;
};

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

std::string type_in_words(const json& value) {
  if (value.is_number_integer()) return "an integer";
  if (value.is_number()) return "a number with a fraction";
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  if (value.is_null()) return "null";
  return value.is_object() ? "an object" : value.is_array() ? "an array" : "a string";
}

std::string id_problem(const json& id) {
  constexpr long long kLeast = -2147483648LL, kMost = 2147483647LL;
  if (id.is_string()) return find_invalid_utf8(id.get_ref<const std::string&>()) ? "the request's id is a string that is not UTF-8" : "";
  bool in_range = id.is_number_unsigned() ? id.get<unsigned long long>() <= kMost
                                          : id.is_number_integer() && id.get<long long>() >= kLeast && id.get<long long>() <= kMost;
  if (in_range) return "";
  std::string what = id.is_number() ? json_text(id) : type_in_words(id);
  return fmt::format("the request's id must be a string or an integer from {} to {}, not {}", kLeast, kMost, what);
}

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
  MessageReader reader(in);
  while (std::optional<Incoming> incoming = reader.next()) {
    json& message = incoming->message;
    if (message.contains("params") && !message["params"].is_object() && !message["params"].is_array())
      message.erase("params");  // invalid; the handler reports what is missing
    bool exit = value_at(message, {"method"}) == "exit";
    {
      std::lock_guard lock(mutex_);
      queue_.push_back(std::move(*incoming));
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
