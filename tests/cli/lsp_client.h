#pragma once
// A scripted JSON-RPC client for `lwcport lsp`: framed messages in, every reply and notification
// read back in order, and what a client computes itself (positions in UTF-16 units, edits applied).
#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lsp/server.h"
#include "support.h"

namespace lwc::lsp_client {

using nlohmann::json;

inline std::string frame(const json& message) {
  std::string body = message.dump();
  return "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
}

struct Session {
  int exit_code = -1;
  std::vector<json> messages;  // what the server wrote, in order
};

// Every message framed in a server's output, in order.
inline std::vector<json> read_messages(const std::string& out) {
  std::vector<json> messages;
  for (size_t at = 0; at < out.size();) {
    size_t head = out.find("\r\n\r\n", at);
    if (head == std::string::npos) break;
    size_t length = std::stoul(out.substr(out.find(':', at) + 1, head - at));
    messages.push_back(json::parse(out.substr(head + 4, length)));
    at = head + 4 + length;
  }
  return messages;
}

// Runs the server in this process on `input` (already framed) and reads every message it writes.
inline Session serve_here(const std::string& input) {
  std::istringstream in(input);
  std::ostringstream out;
  int code = run_language_server(in, out);
  return {code, read_messages(out.str())};
}

// Runs `lwcport lsp` (with `arguments`) on `input` (already framed) and reads every message it writes.
inline Session serve(const std::string& input, const std::string& arguments = "") {
  std::string dir = test::scratch("lsp");
  test::write(dir + "/in", input);
  test::Run r = test::run(test::binary() + " lsp " + arguments + " < " + dir + "/in");
  return {r.exit_code, read_messages(r.out)};
}

inline json request(int id, const std::string& method, const json& params = json::object()) {
  return {{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", params}};
}
inline json notification(const std::string& method, const json& params = json::object()) {
  return {{"jsonrpc", "2.0"}, {"method", method}, {"params", params}};
}
inline json initialize(const json& capabilities = json::object()) { return request(1, "initialize", {{"capabilities", capabilities}}); }
inline std::string end_session() { return frame(request(99, "shutdown")) + frame(notification("exit")); }

inline const json* reply_to(const Session& s, int id) {
  for (const json& m : s.messages)
    if (m.contains("id") && m["id"] == id) return &m;
  return nullptr;
}
// Every notification of one method, in order.
inline std::vector<json> notifications(const Session& s, const std::string& method) {
  std::vector<json> out;
  for (const json& m : s.messages)
    if (m.value("method", "") == method && !m.contains("id")) out.push_back(m["params"]);
  return out;
}
inline std::vector<json> diagnostics(const Session& s) {
  std::vector<json> out;
  for (const json& m : s.messages)
    if (m.value("method", "") == "textDocument/publishDiagnostics") out.push_back(m["params"]);
  return out;
}

// The UTF-8 bytes of the character at `at`, and its UTF-16 units: what a client counts.
inline size_t bytes_at(const std::string& text, size_t at) {
  unsigned char lead = static_cast<unsigned char>(text[at]);
  return lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 1;
}
inline size_t utf16_units(size_t bytes) { return bytes == 4 ? 2 : 1; }

// The byte offset of a (line, UTF-16 character) position.
inline size_t byte_offset(const std::string& text, size_t line, size_t character) {
  // Lines end at "\n", "\r\n" or a lone "\r"; a position never falls inside a line's end.
  auto ends_line = [&](size_t i) { return text[i] == '\n' || text[i] == '\r'; };
  size_t at = 0;
  for (size_t l = 0; l < line && at < text.size(); ++at)
    if (ends_line(at) && !(text[at] == '\r' && at + 1 < text.size() && text[at + 1] == '\n')) ++l;
  for (size_t units = 0; at < text.size() && !ends_line(at) && units < character;) {
    size_t n = bytes_at(text, at);
    units += utf16_units(n);
    at += n;
  }
  return at;
}

// Applies LSP text edits (positions in UTF-16 units) to a text.
inline std::string apply(std::string text, const json& edits) {
  auto at = [&](const json& p) { return byte_offset(text, p["line"].get<size_t>(), p["character"].get<size_t>()); };
  std::vector<json> sorted(edits.begin(), edits.end());
  std::sort(sorted.begin(), sorted.end(), [&](const json& a, const json& b) { return at(a["range"]["start"]) > at(b["range"]["start"]); });
  for (const json& e : sorted) {
    size_t begin = at(e["range"]["start"]), end = at(e["range"]["end"]);
    text.replace(begin, end - begin, e["newText"].get<std::string>());
  }
  return text;
}

// The LSP position (UTF-16 units) of a byte offset, as a client computes it.
inline json position_of(const std::string& text, size_t at) {
  size_t line = 0, line_start = 0;
  for (size_t i = 0; i < at; ++i)
    if (text[i] == '\n' || (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n'))) ++line, line_start = i + 1;
  size_t units = 0;
  for (size_t i = line_start; i < at;) {
    size_t n = bytes_at(text, i);
    units += utf16_units(n);
    i += n;
  }
  return {{"line", line}, {"character", units}};
}

}  // namespace lwc::lsp_client
