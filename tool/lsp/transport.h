#pragma once
// The language server's transport (LSP's base protocol): JSON-RPC 2.0 messages, each framed by a
// Content-Length header on a byte stream, read on a thread of their own and written back.
#include <condition_variable>
#include <deque>
#include <istream>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <thread>

#include <nlohmann/json.hpp>

namespace lwc::lsp {

using nlohmann::json;

// JSON-RPC and LSP error codes.
constexpr int kParseError = -32700, kInvalidRequest = -32600, kMethodNotFound = -32601, kInvalidParams = -32602,
              kInternalError = -32603, kServerNotInitialized = -32002, kRequestCancelled = -32800, kContentModified = -32801;

// A member deep in `object`, or null where the path is missing (any message may be malformed).
json value_at(const json& object, std::initializer_list<const char*> path);

// `array` is a JSON array holding `value`.
bool holds(const json& array, const char* value);

// JSON text of a value. Text from the user's files may not be UTF-8: replaced, never a thrown dump.
std::string json_text(const json& value);

// A JSON type in words: "an object", "a string", "an integer".
std::string type_in_words(const json& value);

// What is wrong with a request's id, or "" for none. JSON-RPC allows strings and numbers; LSP's
// ids are strings and integers (32-bit), and a reply must carry the id as it came: a number with
// a fraction, one past 32 bits, or a string that is not UTF-8 (JSON would send it back changed) is
// refused with the rest.
std::string id_problem(const json& id);

// A message from the client, or why none could be read.
struct Incoming {
  json message;              // an object; null when none could be read
  std::string error;         // why none could be read, answered with `code` (id null)
  int code = kParseError;
  std::string framing;       // what was wrong with the framing of a message read all the same
  std::string dropped;       // the first of the bytes dropped, for the log
};

// The client's messages, read on a thread of their own as they arrive: a request still waiting
// can then be cancelled, and a burst of typing analysed once.
class Inbox {
 public:
  // std::cin is tied to std::cout (reading flushes it): untied here, or the reading thread would
  // flush the output while the server writes it.
  explicit Inbox(std::istream& in) : untied_(in.tie(nullptr)), reader_([this, &in] { read(in); }) {}
  ~Inbox() { reader_.join(); }

  // The next message; none once the input is over.
  std::optional<Incoming> next();

  // Takes a waiting `$/cancelRequest` for this id, if there is one.
  bool take_cancel(const json& id);

  // A later change of this document already waits.
  bool change_waits(const std::string& uri);

 private:
  void read(std::istream& in);

  std::mutex mutex_;
  std::condition_variable arrived_;
  std::deque<Incoming> queue_;
  bool done_ = false;
  std::ostream* untied_;
  std::thread reader_;  // last: starts once the rest is built
};

// Writes one message body with its header.
void write_frame(std::ostream& out, std::string_view body);

}  // namespace lwc::lsp
