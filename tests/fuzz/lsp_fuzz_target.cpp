// libFuzzer target for the language server's framing and JSON-RPC layer: any bytes as the
// server's standard input (after the first, which picks the size of the chunks the stream hands
// them out in, as a pipe does), then a request and `exit`. A crash, an uncaught exception or a hang,
// output that is not framed JSON, a library's internals in a message, or the request after the
// input left unanswered is a bug. Built with ASan and UBSan (tests/fuzz/build.sh).
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <streambuf>
#include <string>

#include <nlohmann/json.hpp>

#include "lsp/server.h"

namespace {

void check(bool ok) {
  if (!ok) std::abort();
}

// A stream that hands out its bytes `chunk` at a time and counts how many were taken.
class ChunkedStream : public std::streambuf {
 public:
  ChunkedStream(std::string bytes, size_t chunk) : bytes_(std::move(bytes)), chunk_(chunk) {}
  size_t taken() const { return handed_ - static_cast<size_t>(egptr() - gptr()); }

 protected:
  int_type underflow() override {
    if (handed_ >= bytes_.size()) return traits_type::eof();
    char* begin = bytes_.data() + handed_;
    size_t n = std::min(chunk_, bytes_.size() - handed_);
    setg(begin, begin, begin + n);
    handed_ += n;
    return traits_type::to_int_type(*begin);
  }

 private:
  std::string bytes_;
  size_t chunk_;
  size_t handed_ = 0;
};

// A library's internals in an error's words: after the last of our prefixes that are followed by
// words of ours alone (a client's text, a method's name, is echoed before them and may hold anything).
bool shows_internals(const nlohmann::json& message) {
  const nlohmann::json none = nlohmann::json::object();
  nlohmann::json text = message.contains("error") ? message["error"].value("message", nlohmann::json())
                                                  : message.value("params", none).value("message", nlohmann::json());
  if (!text.is_string()) return false;
  const std::string& words = text.get_ref<const std::string&>();
  for (const char* prefix : {"bad parameters: ", " failed: "}) {
    size_t at = words.rfind(prefix);
    if (at != std::string::npos && words.find("json.exception", at) != std::string::npos) return true;
  }
  return false;
}

std::string frame(const std::string& body) { return "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body; }

constexpr const char* kFinalId = "lwcport-fuzz-final";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  size_t chunk = size_t{1} << (data[0] % 12);
  std::string input(reinterpret_cast<const char*>(data) + 1, size - 1);
  std::string final_request = frame(std::string(R"({"jsonrpc":"2.0","id":")") + kFinalId + R"(","method":"shutdown"})");
  ChunkedStream stream(input + final_request + frame(R"({"jsonrpc":"2.0","method":"exit"})"), chunk);
  std::istream in(&stream);
  std::ostringstream out;
  lwc::run_language_server(in, out);

  // Every message written is framed, JSON, and shows no library's internals.
  std::string written = out.str();
  bool answered = false;
  for (size_t at = 0; at < written.size();) {
    check(written.compare(at, 16, "Content-Length: ") == 0);
    size_t head = written.find("\r\n\r\n", at);
    check(head != std::string::npos);
    size_t length = std::stoul(written.substr(at + 16, head - at - 16));
    check(head + 4 + length <= written.size());
    nlohmann::json message = nlohmann::json::parse(written.substr(head + 4, length), nullptr, false);
    check(message.is_object());
    check(!shows_internals(message));
    answered |= message.value("id", nlohmann::json()) == kFinalId;
    at = head + 4 + length;
  }
  // The server read on past the input (no `exit` in it stopped it): it answered the request there.
  if (stream.taken() >= input.size() + final_request.size()) check(answered);
  return 0;
}
