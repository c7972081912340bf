#include "lsp/server.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/source.h"
#include "fix/apply.h"
#include "project/config.h"
#include "project/includes.h"
#include "rules/analyze.h"
#include "rules/rule.h"

namespace lwc {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// JSON-RPC and LSP error codes.
constexpr int kParseError = -32700, kInvalidRequest = -32600, kMethodNotFound = -32601, kInvalidParams = -32602,
              kServerNotInitialized = -32002;
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

// Where each line starts (LSP lines end at "\n"; a "\r" before it belongs to no column).
std::vector<size_t> line_starts(const std::string& text) {
  std::vector<size_t> starts = {0};
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') starts.push_back(i + 1);
  return starts;
}

// Bytes of the UTF-8 sequence that starts with `lead` (1 for a byte that starts none).
size_t sequence_length(unsigned char lead) { return lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 1; }

class Server {
 public:
  explicit Server(std::ostream& out) : out_(out) {}

  // Handles one message; the exit code once the client says `exit`.
  std::optional<int> handle(const json& message) {
    if (!message.contains("method") || !message["method"].is_string()) return std::nullopt;  // a response to us: none asked
    std::string method = message["method"];
    bool request = message.contains("id");
    json id = request ? message["id"] : json();
    const json params = message.value("params", json::object());
    if (method == "exit") return shut_down_ ? 0 : 1;
    if (!initialized_ && method != "initialize") {
      if (request) reply_error(id, kServerNotInitialized, "the server is not initialized yet");
      return std::nullopt;
    }
    if (shut_down_ && request) {
      reply_error(id, kInvalidRequest, "the server is shut down");
      return std::nullopt;
    }
    try {
      if (method == "initialize") reply(id, initialize(params));
      else if (method == "shutdown") shut_down_ = true, reply(id, nullptr);
      else if (method == "textDocument/didOpen") open(params.at("textDocument"));
      else if (method == "textDocument/didChange") change(params.at("textDocument"), params.at("contentChanges"));
      else if (method == "textDocument/didClose") close(params.at("textDocument").at("uri"));
      else if (method == "textDocument/codeAction") reply(id, code_actions(params));
      else if (method == "textDocument/hover") reply(id, hover(params));
      else if (method == "workspace/didChangeWatchedFiles" || method == "workspace/didChangeConfiguration") reload();
      else if (request) reply_error(id, kMethodNotFound, "no method " + method);
    } catch (const json::exception& e) {
      if (request) reply_error(id, kInvalidParams, std::string("bad parameters: ") + e.what());
    }
    return std::nullopt;
  }

  void reply_error(const json& id, int code, const std::string& message) {
    send({{"jsonrpc", "2.0"}, {"id", id}, {"error", {{"code", code}, {"message", message}}}});
  }

 private:
  struct Document {
    fs::path path;
    std::string text;
    int version = 0;
    std::optional<Lang> lang;
    AnalyzeOptions options;         // from the project, as of the last analysis
    std::vector<Finding> findings;  // of the last analysis: what code actions offer
  };

  json initialize(const json& params) {
    initialized_ = true;
    json offered = params.value("capabilities", json::object()).value("general", json::object()).value("positionEncodings", json::array());
    utf8_ = std::find(offered.begin(), offered.end(), "utf-8") != offered.end();
    return {{"capabilities",
             {{"positionEncoding", utf8_ ? "utf-8" : "utf-16"},
              {"textDocumentSync", {{"openClose", true}, {"change", 2}}},  // 2: incremental
              {"codeActionProvider", {{"codeActionKinds", {"quickfix", "source.fixAll.lwcport"}}}},
              {"hoverProvider", true}}},
            {"serverInfo", {{"name", "lwcport"}, {"version", "0.1.0"}}}};
  }

  void open(const json& item) {
    std::string uri = item.at("uri");
    Document& d = documents_[uri];
    d.path = path_of(uri);
    d.text = item.at("text");
    d.version = item.value("version", 0);
    std::string language = item.value("languageId", "");
    if (language == "hlsl") d.lang = Lang::hlsl;
    if (language == "glsl") d.lang = Lang::glsl;
    publish(uri, d);
  }

  void change(const json& item, const json& changes) {
    std::string uri = item.at("uri");
    auto it = documents_.find(uri);
    if (it == documents_.end()) return;
    Document& d = it->second;
    int version = item.value("version", d.version + 1);
    if (version <= d.version) return;  // stale: an edit the document already has
    for (const json& c : changes) {
      if (!c.contains("range")) {
        d.text = c.at("text");
        continue;
      }
      size_t begin = offset(d.text, c["range"].at("start")), end = offset(d.text, c["range"].at("end"));
      if (end < begin) std::swap(begin, end);
      d.text.replace(begin, end - begin, c.at("text").get<std::string>());
    }
    d.version = version;
    publish(uri, d);
  }

  void close(const std::string& uri) {
    documents_.erase(uri);
    send({{"jsonrpc", "2.0"}, {"method", "textDocument/publishDiagnostics"}, {"params", {{"uri", uri}, {"diagnostics", json::array()}}}});
  }

  // The byte offset of an LSP position, clamped to the document (a line past the end is its end,
  // a character past a line's end is that end).
  size_t offset(const std::string& text, const json& position) const {
    std::vector<size_t> starts = line_starts(text);
    long line = position.at("line").get<long>(), character = position.at("character").get<long>();
    if (line < 0) return 0;
    if (static_cast<size_t>(line) >= starts.size()) return text.size();
    size_t at = starts[line], end = static_cast<size_t>(line) + 1 < starts.size() ? starts[line + 1] - 1 : text.size();
    if (end > at && text[end - 1] == '\r') --end;
    for (long units = 0; at < end && units < character;) {
      size_t n = std::min(sequence_length(static_cast<unsigned char>(text[at])), end - at);
      units += units_of(n);
      at += n;
    }
    return at;
  }

  // A character of `bytes` UTF-8 bytes in the negotiated units (UTF-16: two beyond the BMP).
  long units_of(size_t bytes) const { return utf8_ ? static_cast<long>(bytes) : bytes == 4 ? 2 : 1; }

  json position(const std::string& text, const std::vector<size_t>& starts, size_t at) const {
    size_t line = static_cast<size_t>(std::upper_bound(starts.begin(), starts.end(), at) - starts.begin()) - 1;
    long units = 0;
    for (size_t i = starts[line]; i < at;) {
      size_t n = std::min(sequence_length(static_cast<unsigned char>(text[i])), at - i);
      units += units_of(n);
      i += n;
    }
    return {{"line", line}, {"character", units}};
  }

  static fs::path path_of(const std::string& uri) {
    std::string rest = uri.rfind("file://", 0) == 0 ? uri.substr(7) : uri;
    std::string out;
    for (size_t i = 0; i < rest.size(); ++i) {
      if (rest[i] == '%' && i + 2 < rest.size() && std::isxdigit(static_cast<unsigned char>(rest[i + 1])) &&
          std::isxdigit(static_cast<unsigned char>(rest[i + 2]))) {
        out += static_cast<char>(std::stoi(rest.substr(i + 1, 2), nullptr, 16));
        i += 2;
      } else {
        out += rest[i];
      }
    }
    return out;
  }

  // The document's findings, as the command line's `lint` gives them for the same text.
  void publish(const std::string& uri, Document& d) {
    json diagnostics = json::array();
    std::vector<size_t> starts = line_starts(d.text);
    auto range = [&](size_t begin, size_t end) {
      return json{{"start", position(d.text, starts, std::min(begin, d.text.size()))},
                  {"end", position(d.text, starts, std::min(end, d.text.size()))}};
    };
    try {
      std::shared_ptr<const ProjectConfig> config = configs_->for_dir(folder_of(d));
      AnalyzeOptions options = analysis_options(*config);
      if (d.lang) options.lang = d.lang;
      std::optional<FileSummary> summary;
      if (d.text.find("include") != std::string::npos) {
        summary = includes_->for_file(d.path, d.text, *config);
        options.includes = &*summary;
      }
      d.options = options;
      d.options.includes = nullptr;  // the summary lives for this analysis only
      d.findings = analyze(Source(d.path.string(), d.text), options);
      for (const Finding& f : d.findings) {
        int severity = f.severity == Severity::error ? 1 : f.severity == Severity::warning ? 2 : 3;
        diagnostics.push_back({{"range", range(f.span.begin, f.span.end)},
                               {"severity", severity},
                               {"code", f.rule},
                               {"codeDescription", {{"href", rule_doc_url(f.rule)}}},
                               {"source", "lwcport"},
                               {"message", f.hint.empty() ? f.message : f.message + "\n" + f.hint}});
      }
    } catch (const std::exception& e) {
      // One document's failure is that document's diagnostic, not a dead server.
      diagnostics = json::array({{{"range", range(0, 0)}, {"severity", 1}, {"source", "lwcport"},
                                  {"message", std::string("internal error while analysing this document: ") + e.what()}}});
    }
    send({{"jsonrpc", "2.0"},
          {"method", "textDocument/publishDiagnostics"},
          {"params", {{"uri", uri}, {"version", d.version}, {"diagnostics", diagnostics}}}});
  }

  // Quick fixes (each finding's rewrite; a safe one preferred, an unsafe one titled so), "ignore
  // <rule> for this line", and every safe fix at once (source.fixAll.lwcport), for the findings the
  // range touches. A rewrite that needs lwcport's library file written beside the document is left
  // to `lwcport fix`, which writes it.
  json code_actions(const json& params) {
    std::string uri = params.at("textDocument").at("uri");
    json actions = json::array();
    auto it = documents_.find(uri);
    if (it == documents_.end()) return actions;
    const Document& d = it->second;
    size_t from = offset(d.text, params.at("range").at("start")), to = offset(d.text, params.at("range").at("end"));
    std::vector<size_t> starts = line_starts(d.text);
    Source source(d.path.string(), d.text);
    // The edits as a workspace edit; `written`: their text is in the document's line endings already.
    auto edit_of = [&](const std::vector<Edit>& edits, bool written = false) {
      json list = json::array();
      for (const Edit& e : edits)
        list.push_back({{"range", {{"start", position(d.text, starts, e.span.begin)}, {"end", position(d.text, starts, e.span.end)}}},
                        {"newText", written ? e.text : in_line_endings(source, e.text)}});
      return json{{"changes", {{uri, list}}}};
    };
    for (const Finding& f : d.findings) {
      if (f.span.end < from || f.span.begin > to) continue;
      for (const Fix& fix : f.fixes) {
        if (!fix.library.empty()) continue;
        bool safe = fix.applicability == Applicability::safe;
        actions.push_back({{"title", safe ? fix.title : fix.title + " (unsafe: " + fix.reason + ")"},
                           {"kind", "quickfix"}, {"isPreferred", safe}, {"edit", edit_of(fix.edits)}});
      }
      if (f.rule != "lwc-input") {
        // A line of its own above the finding's line, indented as it is.
        Position at = source.position(f.span.begin);
        uint32_t line_start = source.offset({at.line, 1});
        std::string_view line = source.line_text(at.line);
        std::string indent(line.substr(0, line.find_first_not_of(" \t")));
        bool continued = line.ends_with('\\') || (at.line > 1 && source.line_text(at.line - 1).ends_with('\\'));
        if (!continued)
          actions.push_back({{"title", "ignore " + f.rule + " for this line"}, {"kind", "quickfix"},
                             {"edit", edit_of({{{line_start, line_start}, indent + "// lwcport-ignore: " + f.rule + "\n"}})}});
      }
    }
    bool any_safe = std::any_of(d.findings.begin(), d.findings.end(), [](const Finding& f) {
      return std::any_of(f.fixes.begin(), f.fixes.end(), [](const Fix& x) { return x.applicability == Applicability::safe; });
    });
    if (any_safe) {
      AnalyzeOptions options = d.options;
      std::optional<FileSummary> summary;
      if (d.text.find("include") != std::string::npos) {
        summary = includes_->for_file(d.path, d.text, *configs_->for_dir(folder_of(d)));
        options.includes = &*summary;
      }
      FixOutcome fixed = fix_source(source, options, false);
      if (fixed.applied > 0 && fixed.library.empty())
        actions.push_back({{"title", "lwcport: apply every safe fix"}, {"kind", "source.fixAll.lwcport"},
                           {"edit", edit_of({{{0, static_cast<uint32_t>(d.text.size())}, fixed.text}}, true)}});
    }
    return actions;
  }

  // A `.lwcport.json` (or an include) changed: every project setting and include summary is read
  // again, and every open document analysed again.
  void reload() {
    configs_ = std::make_unique<ConfigFinder>();
    includes_ = std::make_unique<IncludeSummaries>();
    for (auto& [uri, d] : documents_) publish(uri, d);
  }

  // On a finding: its message, its rule's summary and rationale, and the rule's page.
  json hover(const json& params) {
    auto it = documents_.find(params.at("textDocument").at("uri"));
    if (it == documents_.end()) return nullptr;
    const Document& d = it->second;
    size_t at = offset(d.text, params.at("position"));
    std::vector<size_t> starts = line_starts(d.text);
    for (const Finding& f : d.findings) {
      if (at < f.span.begin || at > f.span.end) continue;
      auto rule = std::find_if(all_rules().begin(), all_rules().end(), [&](const RuleInfo& r) { return r.id == f.rule; });
      std::string text = "**" + f.rule + "**: " + f.message;
      if (rule != all_rules().end()) text += "\n\n" + rule->summary + ". " + rule->rationale + "\n\n[" + f.rule + "](" + rule_doc_url(f.rule) + ")";
      return {{"contents", {{"kind", "markdown"}, {"value", text}}},
              {"range", {{"start", position(d.text, starts, f.span.begin)}, {"end", position(d.text, starts, f.span.end)}}}};
    }
    return nullptr;
  }

  static fs::path folder_of(const Document& d) {
    return d.path.has_parent_path() && d.path.is_absolute() ? d.path.parent_path() : fs::current_path();
  }

  void reply(const json& id, const json& result) { send({{"jsonrpc", "2.0"}, {"id", id}, {"result", result}}); }

  void send(const json& message) {
    // Text from the user's files may not be UTF-8: replaced, never a thrown dump.
    std::string body = message.dump(-1, ' ', false, json::error_handler_t::replace);
    out_ << "Content-Length: " << body.size() << "\r\n\r\n" << body;
    out_.flush();
  }

  std::ostream& out_;
  bool initialized_ = false, shut_down_ = false, utf8_ = false;
  std::map<std::string, Document> documents_;
  std::unique_ptr<ConfigFinder> configs_ = std::make_unique<ConfigFinder>();
  std::unique_ptr<IncludeSummaries> includes_ = std::make_unique<IncludeSummaries>();
};

}  // namespace

int run_language_server(std::istream& in, std::ostream& out) {
  Server server(out);
  for (;;) {
    Frame frame = read_frame(in);
    if (frame.end) return 1;  // the input ended without `exit`
    if (!frame.error.empty()) {
      server.reply_error(nullptr, kParseError, frame.error);
      continue;
    }
    json message = json::parse(frame.body, nullptr, false);
    if (message.is_discarded() || !message.is_object()) {
      server.reply_error(nullptr, kParseError, "the message is not a JSON object");
      continue;
    }
    if (std::optional<int> code = server.handle(message)) return *code;
  }
}

}  // namespace lwc
