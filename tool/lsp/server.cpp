#include "lsp/server.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/source.h"
#include "core/uri.h"
#include "fix/apply.h"
#include "lang/formats.h"
#include "lsp/params.h"
#include "lsp/positions.h"
#include "lsp/transport.h"
#include "project/config.h"
#include "project/files.h"
#include "project/includes.h"
#include "rules/analyze.h"
#include "rules/rule.h"
#include "shaderlib/shaderlib.h"

namespace lwc {
namespace {

using namespace lsp;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr const char* kFixAllCommand = "lwcport.fixAll";

class Server {
 public:
  Server(std::ostream& out, Inbox& inbox, const ServerOptions& options) : out_(out), inbox_(inbox) {
    if (!options.log_file.empty()) log_.open(options.log_file, std::ios::app);
    log("lwcport language server started");
  }

  // Handles one message; the exit code once the client says `exit`.
  std::optional<int> handle(const json& message) {
    bool request = message.contains("id");
    json id = request ? message["id"] : json();
    std::string bad_id = request ? id_problem(id) : "";
    if (!message.contains("method") || !message["method"].is_string()) {
      if (message.contains("result") || message.contains("error")) {
        response_received(message);
        return std::nullopt;
      }
      log("an invalid request: it has no method (a string), nor a result");
      reply_error(bad_id.empty() ? id : json(), kInvalidRequest, "the message is no request: it has no method (a string), nor a result");
      return std::nullopt;
    }
    std::string method = message["method"];
    if (!bad_id.empty()) {  // answered as JSON-RPC says, never with an id other than it came with
      log("an invalid request: " + method + ": " + bad_id);
      reply_error(nullptr, kInvalidRequest, bad_id);
      return std::nullopt;
    }
    const json params = message.contains("params") ? message["params"] : json::object();
    auto started = Clock::now();
    replied_ = false;
    log(fmt::format("<- {}{}", method, request ? " (" + json_text(id) + ")" : ""));
    if (method == "exit") return shut_down_ ? 0 : 1;
    if (!initialized_ && method != "initialize") {
      if (request) reply_error(id, kServerNotInitialized, "the server is not initialized yet");
      return std::nullopt;
    }
    if (shut_down_ && request) {
      reply_error(id, kInvalidRequest, "the server is shut down");
      return std::nullopt;
    }
    if (request && inbox_.take_cancel(id)) {
      log(fmt::format("   cancelled ({})", json_text(id)));
      reply_error(id, kRequestCancelled, "cancelled by the client");
      return std::nullopt;
    }
    try {
      if (method == "initialize") reply(id, initialize(params));
      else if (method == "initialized") register_watchers();
      else if (method == "shutdown") shut_down_ = true, reply(id, nullptr);
      else if (method == "textDocument/didOpen") open(params);
      else if (method == "textDocument/didChange") change(params);
      else if (method == "textDocument/didSave") saved(string_member(params, "textDocument.uri"));
      else if (method == "textDocument/didClose") close(string_member(params, "textDocument.uri"));
      else if (method == "textDocument/diagnostic") reply(id, pulled_diagnostics(params));
      else if (method == "textDocument/codeAction") reply(id, code_actions(params));
      else if (method == "codeAction/resolve") resolve_action(id, params);
      else if (method == "textDocument/hover") reply(id, hover(params));
      else if (method == "workspace/executeCommand") execute(id, params);
      else if (method == "workspace/didChangeConfiguration") settings(value_at(params, {"settings"})), reload();
      else if (method == "workspace/didChangeWatchedFiles") reload();
      else if (request) reply_error(id, kMethodNotFound, "no method " + method);
      // Other notifications ($/setTrace, $/cancelRequest for what is answered...) need nothing.
    } catch (const BadParams& e) {
      log(method + ": bad parameters: " + e.what());
      if (request) reply_error(id, kInvalidParams, std::string("bad parameters: ") + e.what());
    } catch (const json::exception& e) {
      log(method + ": bad parameters: " + plain_words(e));
      if (request) reply_error(id, kInvalidParams, "bad parameters: " + plain_words(e));
    } catch (const std::exception& e) {
      log_message(1, method + " failed: " + plain_words(e));
      if (request) reply_error(id, kInternalError, method + " failed: " + plain_words(e));
    }
    // A notification sent with an id is still a request: JSON-RPC owes it one answer.
    if (request && !replied_) reply_error(id, kInvalidRequest, method + " is a notification, not a request");
    log(fmt::format("   {} done in {:.1f} ms", method, ms_since(started)));
    return std::nullopt;
  }

  void reply_error(const json& id, int code, const std::string& message) {
    replied_ = true;
    send({{"jsonrpc", "2.0"}, {"id", id}, {"error", {{"code", code}, {"message", message}}}});
  }

  void log(const std::string& line) {
    if (log_.is_open()) log_ << fmt::format("[{:10.1f} ms] ", ms_since(started_)) << line << std::endl;
  }

  // A framing error or a message that could not be read: the log gets what was dropped, the client
  // a warning (once initialized: before, the protocol lets a server send it nothing) and, when no
  // message could be read, the error JSON-RPC answers it with.
  void unsound(const Incoming& in) {
    std::string what = in.error.empty() ? "a message was read despite its framing: " + in.framing : in.error;
    log(what + (in.dropped.empty() ? "" : "; dropped: " + in.dropped));
    if (initialized_) send({{"jsonrpc", "2.0"}, {"method", "window/logMessage"}, {"params", {{"type", 2}, {"message", "lwcport: " + what}}}});
    if (!in.error.empty()) reply_error(nullptr, in.code, in.error);
  }

 private:
  // A diagnostic as JSON text, in two parts: before its document version and after it.
  struct DiagnosticText {
    std::string before_version, after_version;
  };

  struct Document {
    std::string uri;  // as the client names it
    fs::path path;
    std::string text;
    std::vector<size_t> lines = {0};  // where each line of `text` starts
    long version = 0;
    std::optional<Lang> lang;
    bool analysed = false;          // the findings are of `text`
    long result = 0;                // which analysis the findings come from (pull diagnostics' result id)
    std::vector<Finding> findings;  // of the last analysis: what code actions offer
    std::string failure;            // the analysis could not run: why
    std::vector<fs::path> includes;  // the files its includes reach, as of the last analysis
    std::string help_uri_base;  // its project's "help-uri-base": where its diagnostics' rule pages are
    std::shared_ptr<ParseReuse> parses = std::make_shared<ParseReuse>();  // its last parse, which the next one edits
    std::shared_ptr<ModelReuse> models = std::make_shared<ModelReuse>();  // its last models, which the next ones replay
    // What its includes declare (options_for), for these include lines and include generation.
    std::shared_ptr<const FileSummary> summary;
    std::vector<std::string> summary_includes;
    long summary_generation = -1;
    // The last "fix all" edit, for (analysis, unsafe): editors ask for code actions at every move.
    std::optional<std::pair<long, bool>> fix_all_for;
    std::optional<json> fix_all;
    // The diagnostics last published, as text, with what their text was made of (diagnostics_text).
    struct Sent {
      std::vector<size_t> inputs;
      std::vector<std::string> words;
      DiagnosticText text;
    };
    mutable std::vector<Sent> sent;
  };

  static double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }
  // This thread's CPU time (the machines that measure the server are shared and noisy).
  static double cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) / 1e6;
  }

  json initialize(const json& params) {
    initialized_ = true;
    const json capabilities = value_at(params, {"capabilities"});
    utf8_ = holds(value_at(capabilities, {"general", "positionEncodings"}), "utf-8");
    pull_ = value_at(capabilities, {"textDocument", "diagnostic"}).is_object();
    refresh_ = value_at(capabilities, {"workspace", "diagnostics", "refreshSupport"}) == true;
    lazy_edits_ = holds(value_at(capabilities, {"textDocument", "codeAction", "resolveSupport", "properties"}), "edit");
    watch_ = value_at(capabilities, {"workspace", "didChangeWatchedFiles", "dynamicRegistration"}) == true;
    create_files_ = value_at(capabilities, {"workspace", "workspaceEdit", "documentChanges"}) == true &&
                    holds(value_at(capabilities, {"workspace", "workspaceEdit", "resourceOperations"}), "create");
    settings(value_at(params, {"initializationOptions"}));
    log_message(3, fmt::format("lwcport {}: {} positions, {} diagnostics", LWCPORT_VERSION, utf8_ ? "UTF-8" : "UTF-16", pull_ ? "pulled" : "pushed"));
    json provider = {{"codeActionKinds", {"quickfix", "source.fixAll.lwcport"}}, {"resolveProvider", true}};
    json result = {{"capabilities",
                    {{"positionEncoding", utf8_ ? "utf-8" : "utf-16"},
                     {"textDocumentSync", {{"openClose", true}, {"change", 2}, {"save", true}}},  // 2: incremental
                     {"codeActionProvider", provider},
                     {"executeCommandProvider", {{"commands", {kFixAllCommand}}}},
                     {"hoverProvider", true}}},
                   {"serverInfo", {{"name", "lwcport"}, {"version", LWCPORT_VERSION}}}};
    if (pull_) result["capabilities"]["diagnosticProvider"] = {{"identifier", "lwcport"}, {"interFileDependencies", true}, {"workspaceDiagnostics", false}};
    return result;
  }

  // Client settings (initializationOptions, or `lwcport` in didChangeConfiguration's settings):
  // `unsafeFixes` lets "fix all" apply unsafe rewrites too.
  void settings(const json& given) {
    if (!given.is_object()) return;
    const json& ours = given.contains("lwcport") && given["lwcport"].is_object() ? given["lwcport"] : given;
    if (ours.contains("unsafeFixes") && ours["unsafeFixes"].is_boolean()) unsafe_fixes_ = ours["unsafeFixes"];
  }

  // Asks the client to report changes of project settings and shader files, when it can.
  void register_watchers() {
    if (!watch_) return;
    // Every shader extension lwcport reads by default: "**/*{.usf,.ush,...}".
    std::string extensions = FormatTable::defaults().extensions();
    extensions.erase(std::remove(extensions.begin(), extensions.end(), ' '), extensions.end());
    json watchers = json::array({{{"globPattern", "**/.lwcport.json"}}, {{"globPattern", "**/*{" + extensions + "}"}, {"kind", 7}}});
    send({{"jsonrpc", "2.0"},
          {"id", fmt::format("lwcport/{}", ++requests_)},
          {"method", "client/registerCapability"},
          {"params", {{"registrations", {{{"id", "lwcport-watch"}, {"method", "workspace/didChangeWatchedFiles"},
                                          {"registerOptions", {{"watchers", watchers}}}}}}}}});
  }

  // A reply to one of our requests: a failed edit is worth a line in the log.
  void response_received(const json& message) {
    if (message.contains("error")) log("the client refused a request: " + json_text(message["error"]));
    json reason = value_at(message, {"result", "failureReason"});
    if (value_at(message, {"result", "applied"}) == false)
      log_message(2, "the editor did not apply lwcport's fixes: " + (reason.is_string() ? reason.get<std::string>() : "no reason given"));
  }

  void open(const json& params) {
    std::string uri = string_member(params, "textDocument.uri");
    // Read in full before it replaces anything: a malformed open leaves no half-made document.
    Document d;
    d.uri = uri;
    d.path = path_of_uri(uri);
    d.text = string_member(params, "textDocument.text");
    d.lines = line_starts(d.text);
    d.version = integer_member_or(params, "textDocument.version", 0);
    d.lang = parse_lang(string_member_or(params, "textDocument.languageId", ""));
    Document& opened = documents_[uri] = std::move(d);
    analyse_and_publish(uri, opened);
    text_changed(uri, opened, opened.text);
  }

  void change(const json& params) {
    std::string uri = string_member(params, "textDocument.uri");
    const json& changes = member(params, "contentChanges");
    if (!changes.is_array()) throw BadParams("`contentChanges` must be an array, not " + type_in_words(changes));
    auto it = documents_.find(uri);
    if (it == documents_.end()) return;
    Document& d = it->second;
    long version = integer_member_or(params, "textDocument.version", d.version + 1);
    if (version <= d.version) return;  // stale: an edit the document already has
    // Applied to a copy: a malformed change leaves the document as it was.
    Document edited;
    edited.text = d.text;
    edited.lines = d.lines;
    for (size_t i = 0; i < changes.size(); ++i) {
      std::string item = fmt::format("contentChanges.{}", i);
      if (!changes[i].contains("range")) {
        edited.text = string_member(params, item + ".text");
        edited.lines = line_starts(edited.text);
        continue;
      }
      size_t begin = offset(edited, params, item + ".range.start"), end = offset(edited, params, item + ".range.end");
      if (end < begin) std::swap(begin, end);
      edited.text.replace(begin, end - begin, string_member(params, item + ".text"));
      edited.lines = line_starts(edited.text);
    }
    d.text = std::move(edited.text);
    d.lines = std::move(edited.lines);
    d.version = version;
    d.analysed = false;
    // While the client is still typing (a later change already waits), the analysis waits too.
    if (!inbox_.change_waits(uri)) analyse_and_publish(uri, d);
    text_changed(uri, d, d.text);
  }

  void saved(const std::string& uri) {
    auto it = documents_.find(uri);
    if (it != documents_.end() && !it->second.analysed) analyse_and_publish(uri, it->second);
  }

  void close(const std::string& uri) {
    auto it = documents_.find(uri);
    if (it == documents_.end()) return;
    std::erase(summarised_, &it->second);
    Document closed = std::move(it->second);
    documents_.erase(it);
    if (!pull_) send({{"jsonrpc", "2.0"}, {"method", "textDocument/publishDiagnostics"}, {"params", {{"uri", uri}, {"diagnostics", json::array()}}}});
    text_changed(uri, closed, std::nullopt);
  }

  // An open document is the text its includers see: the other open documents whose includes
  // reach it are analysed again.
  void text_changed(const std::string& uri, const Document& d, std::optional<std::string> text) {
    if (!d.path.is_absolute()) return;
    fs::path file = includes_->canonical(d.path);
    try {
      if (includes_->set_text(d.path, std::move(text), *configs_->for_dir(folder_of(d)))) ++include_generation_;
    } catch (const std::exception& e) {
      log("include not re-read: " + plain_words(e));
      return;
    }
    for (auto& [other_uri, other] : documents_) {
      if (other_uri == uri || std::find(other.includes.begin(), other.includes.end(), file) == other.includes.end()) continue;
      other.analysed = false;
      analyse_and_publish(other_uri, other);
    }
  }

  // The byte offset of the LSP position at `path` in `params`, in the document (clamped to it).
  size_t offset(const Document& d, const json& params, const std::string& path) const {
    long line = integer_member(params, path + ".line"), character = integer_member(params, path + ".character");
    return offset_at(d.text, d.lines, line, character, utf8_);
  }

  std::pair<size_t, long> line_and_column(const Document& d, size_t at) const { return lsp::line_and_column(d.text, d.lines, at, utf8_); }

  json position(const Document& d, size_t at) const {
    auto [line, column] = line_and_column(d, at);
    return {{"line", line}, {"character", column}};
  }

  json range(const Document& d, Span span) const { return {{"start", position(d, span.begin)}, {"end", position(d, span.end)}}; }

  // The options a document is analysed with (its project's, with what its includes declare). What
  // its includes declare is kept for the last few documents analysed (typing re-analyses one
  // document many times; a summary of Unreal's includes is large), until its include lines or an
  // include change.
  AnalyzeOptions options_for(Document& d) {
    std::shared_ptr<const ProjectConfig> config = configs_->for_dir(folder_of(d));
    AnalyzeOptions options = analysis_options(*config);
    if (d.help_uri_base != config->help_uri_base) d.sent.clear();  // the diagnostics' links change
    d.help_uri_base = config->help_uri_base;
    if (d.lang) options.lang = d.lang;
    options.reuse = d.parses.get();
    options.model_reuse = d.models.get();  // it read the summary it was made with: replaced with it below
    if (d.text.find("include") == std::string::npos) {
      d.includes.clear();
      return options;
    }
    std::vector<std::string> wanted = include_paths(d.text);
    if (!d.summary || d.summary_includes != wanted || d.summary_generation != include_generation_) {
      d.summary = std::make_shared<FileSummary>(includes_->for_file(d.path, d.text, *config));
      d.models = std::make_shared<ModelReuse>();
      options.model_reuse = d.models.get();
      d.summary_includes = std::move(wanted);
      d.summary_generation = include_generation_;
      d.includes = d.path.is_absolute() ? includes_->included_files(d.path, d.text, *config) : std::vector<fs::path>{};
      std::erase(summarised_, &d);
      summarised_.push_back(&d);
      if (summarised_.size() > 4) {
        summarised_.front()->summary.reset();
        summarised_.pop_front();
      }
    }
    options.includes = d.summary.get();
    options.engine_file = d.path.is_absolute() && engine_file(includes_->canonical(d.path), *config);
    return options;
  }

  // The document's findings, as the command line's `lint` gives them for the same text.
  void analyse(Document& d) {
    auto started = Clock::now();
    double cpu = cpu_ms();
    d.findings.clear();
    d.failure.clear();
    try {
      AnalyzeOptions options = options_for(d);
      d.findings = analyze(Source(d.path.string(), d.text), options);
    } catch (const std::exception& e) {
      // One document's failure is that document's diagnostic, not a dead server.
      d.failure = plain_words(e);
      log_message(1, fmt::format("{}: {}", d.path.string(), d.failure));
    }
    d.analysed = true;
    d.result = ++analyses_;
    log(fmt::format("   analysed {} (version {}): {} findings in {:.2f} ms (CPU {:.2f} ms)", d.path.string(), d.version, d.findings.size(),
                    ms_since(started), cpu_ms() - cpu));
  }

  void ensure_analysed(const std::string& uri, Document& d) {
    if (!d.analysed) analyse_and_publish(uri, d);
  }

  void analyse_and_publish(const std::string& uri, Document& d) {
    analyse(d);
    if (!pull_)
      send_text(fmt::format(R"({{"jsonrpc":"2.0","method":"textDocument/publishDiagnostics","params":{{"uri":{},"version":{},"diagnostics":{}}}}})",
                            json_quoted(uri), d.version, diagnostics_text(d)));
  }

  // Written directly rather than built as a json value: every edit sends every finding of the
  // document again, and building them was a fifth of a keystroke's work.
  DiagnosticText diagnostic_parts(const Document& d, size_t index) const {
    const Finding& f = d.findings[index];
    auto range_text = [&](Span span) {
      auto [line, column] = line_and_column(d, span.begin);
      auto [end_line, end_column] = line_and_column(d, span.end);
      return fmt::format(R"({{"start":{{"line":{},"character":{}}},"end":{{"line":{},"character":{}}}}})", line, column, end_line, end_column);
    };
    int severity = f.severity == Severity::error ? 1 : f.severity == Severity::warning ? 2 : 3;
    DiagnosticText out;
    std::string url = rule_doc_url(f.rule, d.help_uri_base);
    out.before_version = fmt::format(
        R"({{"range":{},"severity":{},"code":{},{}"source":"lwcport","message":{},"data":{{"version":)", range_text(f.span), severity,
        json_quoted(f.rule), url.empty() ? "" : R"("codeDescription":{"href":)" + json_quoted(url) + "},",
        json_quoted(f.hint.empty() ? f.message : f.message + "\n" + f.hint));
    out.after_version = fmt::format(R"(,"finding":{},"fixes":{}}})", index, f.fixes.size());
    for (size_t i = 0; i < f.related.size(); ++i)
      out.after_version += fmt::format(R"({}{{"location":{{"uri":{},"range":{}}},"message":{}}})", i == 0 ? ",\"relatedInformation\":[" : ",",
                                       json_quoted(d.uri), range_text(f.related[i].first), json_quoted(f.related[i].second));
    out.after_version += f.related.empty() ? "}" : "]}";
    return out;
  }

  std::string diagnostic_text(const Document& d, size_t index) const {
    DiagnosticText parts = diagnostic_parts(d, index);
    return parts.before_version + std::to_string(d.version) + parts.after_version;
  }

  json diagnostic(const Document& d, size_t index) const { return json::parse(diagnostic_text(d, index)); }

  // What a diagnostic's text is made of, but offsets: an edit moves the offsets of every finding
  // after it while most keep their lines, columns and words, and their text is sent again as it was.
  std::vector<size_t> text_inputs(const Document& d, const Finding& f) const {
    std::vector<size_t> at;
    auto add = [&](Span span) {
      for (uint32_t offset : {span.begin, span.end}) {
        auto [line, column] = line_and_column(d, offset);
        at.push_back(line);
        at.push_back(static_cast<size_t>(column));
      }
    };
    add(f.span);
    for (const auto& r : f.related) add(r.first);
    at.push_back(static_cast<size_t>(f.severity));
    at.push_back(f.fixes.size());
    return at;
  }
  // Its rule, message, hint and related messages, in that order.
  static std::vector<std::string_view> words(const Finding& f) {
    std::vector<std::string_view> out{f.rule, f.message, f.hint};
    for (const auto& r : f.related) out.push_back(r.second);
    return out;
  }

  std::string diagnostics_text(const Document& d) const {
    if (!d.failure.empty())
      return json_text(json::array({{{"range", range(d, {0, 0})}, {"severity", 1}, {"source", "lwcport"}, {"code", std::string(kInputRule)},
                                     {"message", "lwcport could not analyse this document: " + d.failure}}}));
    std::vector<Document::Sent>& sent = d.sent;
    sent.resize(d.findings.size());
    std::string out = "[";
    std::string version = std::to_string(d.version);
    for (size_t i = 0; i < d.findings.size(); ++i) {
      if (i > 0) out += ',';
      std::vector<size_t> inputs = text_inputs(d, d.findings[i]);
      std::vector<std::string_view> now = words(d.findings[i]);
      Document::Sent& s = sent[i];
      if (s.inputs != inputs || !std::equal(s.words.begin(), s.words.end(), now.begin(), now.end())) {
        s.text = diagnostic_parts(d, i);
        s.inputs = std::move(inputs);
        s.words.assign(now.begin(), now.end());
      }
      out += s.text.before_version;
      out += version;
      out += s.text.after_version;
    }
    return out + "]";
  }

  // textDocument/diagnostic: the document's findings, or "unchanged" when the client already has
  // this analysis's.
  json pulled_diagnostics(const json& params) {
    std::string uri = string_member(params, "textDocument.uri");
    auto it = documents_.find(uri);
    if (it == documents_.end()) return {{"kind", "full"}, {"items", json::array()}};
    Document& d = it->second;
    ensure_analysed(uri, d);
    std::string id = std::to_string(d.result);
    if (string_member_or(params, "previousResultId", "") == id) return {{"kind", "unchanged"}, {"resultId", id}};
    return {{"kind", "full"}, {"resultId", id}, {"items", json::parse(diagnostics_text(d))}};
  }

  // One code action's edit, from its `data`: a finding's fix, the line's suppression, or every
  // fix at once. None when the document moved on since the action was offered.
  std::optional<json> action_edit(const std::string& uri, const json& data) {
    auto it = documents_.find(uri);
    if (it == documents_.end()) return std::nullopt;
    Document& d = it->second;
    ensure_analysed(uri, d);
    if (integer_member_or(data, "version", -1) != d.version) return std::nullopt;
    std::string action = string_member(data, "action");
    if (action == "fixAll") return fix_all_edit(uri, d, bool_member_or(data, "unsafe", false));
    long index = integer_member(data, "finding");
    if (index < 0 || static_cast<size_t>(index) >= d.findings.size()) return std::nullopt;
    const Finding& f = d.findings[index];
    Source source(d.path.string(), d.text);
    if (action == "fix") {
      long k = integer_member(data, "fix");
      if (k < 0 || static_cast<size_t>(k) >= f.fixes.size()) return std::nullopt;
      const Fix& fix = f.fixes[k];
      return workspace_edit(uri, d, fix.edits, source, false, {fix.library.begin(), fix.library.end()});
    }
    // A line of its own above the finding's line, indented as it is.
    Position at = source.position(f.span.begin);
    uint32_t line_start = source.offset({at.line, 1});
    std::string_view line = source.line_text(at.line);
    std::string indent(line.substr(0, line.find_first_not_of(" \t")));
    return workspace_edit(uri, d, {{{line_start, line_start}, indent + "// lwcport-ignore: " + f.rule + "\n"}}, source);
  }

  // The edits as a workspace edit; `written`: their text is in the document's line endings already.
  // With `library` (the DoubleFloat functions the new code calls), lwcport's library file beside
  // the document gets them too (created when missing); none when the client cannot create files or
  // a file of that name exists that lwcport did not write, or when a new text holds bytes that are
  // not UTF-8 (JSON would carry them as U+FFFD: the edit would lose them).
  std::optional<json> workspace_edit(const std::string& uri, const Document& d, const std::vector<Edit>& edits, const Source& source,
                                     bool written = false, const std::set<std::string>& library = {}) const {
    json list = json::array();
    if (std::any_of(edits.begin(), edits.end(), [](const Edit& e) { return find_invalid_utf8(e.text).has_value(); })) return std::nullopt;
    for (const Edit& e : edits) list.push_back({{"range", range(d, e.span)}, {"newText", written ? e.text : in_line_endings(source, e.text)}});
    if (library.empty()) return json{{"changes", {{uri, list}}}};
    std::optional<json> changes = library_changes(d, library);
    if (!changes) return std::nullopt;
    changes->push_back({{"textDocument", {{"uri", uri}, {"version", d.version}}}, {"edits", list}});
    return json{{"documentChanges", *changes}};
  }

  // The library file beside a document with `names` added to what it holds (what `lwcport fix`
  // writes there), as document changes: the file created when missing, then its whole text.
  std::optional<json> library_changes(const Document& d, const std::set<std::string>& names) const {
    std::optional<Lang> lang = d.lang ? d.lang : lang_from_path(d.path.string());
    if (!create_files_ || !lang || !d.path.is_absolute()) return std::nullopt;
    fs::path file = d.path.parent_path() / library_file_name(*lang);
    std::string uri = "file://" + uri_encode(file.string());
    std::optional<std::string> before;
    if (auto open = documents_.find(uri); open != documents_.end()) before = open->second.text;
    else if (std::error_code ec; fs::exists(file, ec)) {
      ReadResult r = read_file(file, SIZE_MAX);
      if (!r.error.empty()) return std::nullopt;
      before = std::move(r.text);
    }
    std::optional<std::string> text = library_file_text(*lang, names, before);
    if (!text) return std::nullopt;
    json changes = json::array();
    if (!before) changes.push_back({{"kind", "create"}, {"uri", uri}, {"options", {{"ignoreIfExists", true}}}});
    std::string old = before.value_or("");
    size_t last_line = static_cast<size_t>(std::count(old.begin(), old.end(), '\n'));
    size_t tail = old.size() - (old.rfind('\n') == std::string::npos ? 0 : old.rfind('\n') + 1);
    json end = {{"line", last_line}, {"character", tail}};  // the library is ASCII: bytes are characters
    changes.push_back({{"textDocument", {{"uri", uri}, {"version", nullptr}}},
                       {"edits", {{{"range", {{"start", {{"line", 0}, {"character", 0}}}, {"end", end}}}, {"newText", *text}}}}});
    return changes;
  }

  // Every fix `lwcport fix` would apply (safe ones, and unsafe ones when asked), as one edit (with
  // lwcport's library file beside the document when a rewrite calls it); none when nothing applies.
  std::optional<json> fix_all_edit(const std::string& uri, Document& d, bool unsafe) {
    if (d.fix_all_for == std::pair{d.result, unsafe}) return d.fix_all;
    AnalyzeOptions options = options_for(d);
    Source source(d.path.string(), d.text);
    FixOutcome fixed = fix_source(source, options, unsafe);
    d.fix_all_for = {d.result, unsafe};
    d.fix_all = fixed.applied == 0 ? std::nullopt
                                   : workspace_edit(uri, d, {{{0, static_cast<uint32_t>(d.text.size())}, fixed.text}}, source, true, fixed.library);
    return d.fix_all;
  }

  // Quick fixes (each finding's rewrite; a safe one preferred, an unsafe one titled so), "ignore
  // <rule> for this line", and every fix at once (source.fixAll.lwcport), for the findings the
  // range touches. A rewrite that needs lwcport's library file beside the document is offered when
  // the client can create files (else `lwcport fix` writes it). With a client that resolves lazily
  // the edits come on codeAction/resolve.
  json code_actions(const json& params) {
    std::string uri = string_member(params, "textDocument.uri");
    json actions = json::array();
    auto it = documents_.find(uri);
    if (it == documents_.end()) return actions;
    Document& d = it->second;
    ensure_analysed(uri, d);
    size_t from = offset(d, params, "range.start"), to = offset(d, params, "range.end");
    json only = value_at(params, {"context", "only"});
    auto wanted = [&](const std::string& kind) {
      if (!only.is_array()) return true;
      return std::any_of(only.begin(), only.end(), [&](const json& k) {
        std::string prefix = k.is_string() ? k.get<std::string>() : "";
        return kind == prefix || kind.rfind(prefix + ".", 0) == 0;
      });
    };
    Source source(d.path.string(), d.text);
    auto add = [&](const std::string& title, const std::string& kind, std::optional<size_t> finding, json data) {
      data["uri"] = uri;
      data["version"] = d.version;
      json action = {{"title", title}, {"kind", kind}};
      if (finding) action["diagnostics"] = json::array({diagnostic(d, *finding)});
      if (lazy_edits_) {
        action["data"] = data;
      } else {
        std::optional<json> edit = action_edit(uri, data);
        if (!edit) return;
        action["edit"] = *edit;
      }
      return actions.push_back(action);
    };
    if (wanted("quickfix")) {
      for (size_t i = 0; i < d.findings.size(); ++i) {
        const Finding& f = d.findings[i];
        if (f.span.end < from || f.span.begin > to) continue;
        for (size_t k = 0; k < f.fixes.size(); ++k) {
          const Fix& fix = f.fixes[k];
          if (!fix.library.empty() && !create_files_) continue;
          bool safe = fix.applicability == Applicability::safe;
          add(safe ? fix.title : fix.title + " (unsafe: " + fix.reason + ")", "quickfix", i, {{"action", "fix"}, {"finding", i}, {"fix", k}});
          if (safe) actions.back()["isPreferred"] = true;
        }
        Position at = source.position(f.span.begin);
        bool continued = source.line_text(at.line).ends_with('\\') || (at.line > 1 && source.line_text(at.line - 1).ends_with('\\'));
        if (f.rule != kInputRule && !continued)
          add("ignore " + f.rule + " for this line", "quickfix", i, {{"action", "ignore"}, {"finding", i}});
      }
    }
    bool any_fix = std::any_of(d.findings.begin(), d.findings.end(), [&](const Finding& f) {
      return std::any_of(f.fixes.begin(), f.fixes.end(), [&](const Fix& x) { return unsafe_fixes_ || x.applicability == Applicability::safe; });
    });
    if (any_fix && !find_invalid_utf8(d.text) && wanted("source.fixAll.lwcport"))
      add(unsafe_fixes_ ? "lwcport: apply every fix (unsafe ones too)" : "lwcport: apply every safe fix", "source.fixAll.lwcport", std::nullopt,
          {{"action", "fixAll"}, {"unsafe", unsafe_fixes_}});
    return actions;
  }

  void resolve_action(const json& id, const json& action) {
    json data = value_at(action, {"data"});
    if (!data.is_object()) return reply(id, action);
    std::optional<json> edit = action_edit(string_member_or(data, "uri", ""), data);
    if (!edit) return reply_error(id, kContentModified, "the document changed since this action was offered; ask again");
    json resolved = action;
    resolved["edit"] = *edit;
    reply(id, resolved);
  }

  // workspace/executeCommand `lwcport.fixAll` [uri] or [{uri, unsafe}]: every fix in the file,
  // sent to the client as workspace/applyEdit.
  void execute(const json& id, const json& params) {
    std::string command = string_member(params, "command");
    if (command != kFixAllCommand) return reply_error(id, kInvalidParams, "no command " + command);
    const json& arguments = value_at(params, {"arguments"});
    if (!arguments.is_array() || arguments.empty()) return reply_error(id, kInvalidParams, std::string(kFixAllCommand) + " needs the document's URI");
    bool named = arguments[0].is_object();  // [uri] or [{uri, unsafe}]
    std::string uri = string_member(params, named ? "arguments.0.uri" : "arguments.0");
    bool unsafe = named ? bool_member_or(params, "arguments.0.unsafe", unsafe_fixes_) : unsafe_fixes_;
    auto it = documents_.find(uri);
    if (it == documents_.end()) return reply_error(id, kInvalidParams, "the document is not open: " + uri);
    Document& d = it->second;
    ensure_analysed(uri, d);
    std::optional<json> edit = fix_all_edit(uri, d, unsafe);
    reply(id, nullptr);
    if (!edit && find_invalid_utf8(d.text))
      return log_message(2, "lwcport: " + d.path.filename().string() + " is not UTF-8, and an edit of it would lose those bytes; save it as UTF-8, or run `lwcport fix` on it");
    if (!edit) return log_message(3, "lwcport: nothing to fix in " + d.path.filename().string());
    send({{"jsonrpc", "2.0"}, {"id", fmt::format("lwcport/{}", ++requests_)}, {"method", "workspace/applyEdit"},
          {"params", {{"label", "lwcport: fix all"}, {"edit", *edit}}}});
  }

  // A `.lwcport.json` (or an include) changed: every project setting and include summary is read
  // again, and every open document analysed again (or, when the client pulls, it is asked to).
  void reload() {
    configs_ = std::make_unique<ConfigFinder>();
    includes_ = std::make_unique<IncludeSummaries>();
    ++include_generation_;
    for (auto& [uri, d] : documents_)
      if (d.path.is_absolute()) try {
          includes_->set_text(d.path, d.text, *configs_->for_dir(folder_of(d)));
        } catch (const std::exception& e) {
          log("include not re-read: " + plain_words(e));  // its analysis reports the config's problem
        }
    for (auto& [uri, d] : documents_) {
      d.analysed = false;
      if (!pull_) analyse_and_publish(uri, d);
    }
    if (pull_ && refresh_) send({{"jsonrpc", "2.0"}, {"id", fmt::format("lwcport/{}", ++requests_)}, {"method", "workspace/diagnostic/refresh"}});
  }

  // On a finding: its message, its rule's summary and rationale, and the rule's page. Elsewhere:
  // the world-space kind of the value under the cursor and where it came from.
  json hover(const json& params) {
    std::string uri = string_member(params, "textDocument.uri");
    auto it = documents_.find(uri);
    if (it == documents_.end()) return nullptr;
    Document& d = it->second;
    ensure_analysed(uri, d);
    size_t at = offset(d, params, "position");
    if (std::optional<json> include = include_hover(d, at)) return *include;
    std::string text;
    std::optional<Span> covered;
    for (const Finding& f : d.findings) {
      if (at < f.span.begin || at > f.span.end) continue;
      const RuleInfo* rule = find_rule(f.rule);
      text = "**" + f.rule + "**: " + f.message;
      if (rule) text += "\n\n" + rule->summary + ". " + rule->rationale;
      if (std::string url = rule_doc_url(f.rule, d.help_uri_base); rule && !url.empty()) text += "\n\n[" + f.rule + "](" + url + ")";
      covered = f.span;
      break;
    }
    try {
      AnalyzeOptions options = options_for(d);
      Source source(d.path.string(), d.text);
      if (std::optional<ValueDescription> value = describe_value(source, options, static_cast<uint32_t>(at))) {
        text = value->markdown + (text.empty() ? "" : "\n\n---\n\n" + text);
        if (!covered) covered = value->span;
      }
    } catch (const std::exception& e) {
      log("hover: " + plain_words(e));
    }
    if (text.empty()) return nullptr;
    return {{"contents", {{"kind", "markdown"}, {"value", text}}}, {"range", range(d, *covered)}};
  }

  // On an #include line: where the include resolves (virtual roots, the including folder, include
  // dirs), or where lwcport looked, as `lint` resolves it.
  std::optional<json> include_hover(const Document& d, size_t at) {
    size_t line = static_cast<size_t>(std::upper_bound(d.lines.begin(), d.lines.end(), at) - d.lines.begin()) - 1;
    size_t begin = d.lines[line], end = line + 1 < d.lines.size() ? d.lines[line + 1] : d.text.size();
    std::vector<std::string> written = include_paths(std::string_view(d.text).substr(begin, end - begin));
    if (written.size() != 1) return std::nullopt;
    std::shared_ptr<const ProjectConfig> config = configs_->for_dir(folder_of(d));
    std::optional<fs::path> found = d.path.is_absolute() ? includes_->resolve(written[0], d.path, *config) : std::nullopt;
    std::string text;
    if (found) {
      text = fmt::format("`{}` resolves to `{}`", written[0], found->string());
    } else {
      std::string roots, dirs;
      for (const auto& [prefix, folder] : config->virtual_roots) roots += fmt::format("{}`{}` -> `{}`", roots.empty() ? "" : ", ", prefix, folder.string());
      for (const fs::path& dir : config->include_dirs) dirs += fmt::format("{}`{}`", dirs.empty() ? "" : ", ", dir.string());
      text = fmt::format("`{}` is not found: lwcport looked {}beside the file{}{}. What it declares is unknown to the analysis; map "
                         "its root in .lwcport.json (\"virtual-roots\", \"include-dirs\")",
                         written[0], roots.empty() ? "" : "under the virtual roots (" + roots + "), ", dirs.empty() ? "" : ", in the include dirs (", dirs.empty() ? "" : dirs + ")");
      if (written[0].rfind("/Engine/", 0) == 0 || written[0].rfind("/Plugin/", 0) == 0) text += ", or open the file inside a `Shaders` folder";
    }
    while (end > begin && (d.text[end - 1] == '\n' || d.text[end - 1] == '\r')) --end;
    return json{{"contents", {{"kind", "markdown"}, {"value", text}}}, {"range", range(d, {static_cast<uint32_t>(begin), static_cast<uint32_t>(end)})}};
  }

  static fs::path folder_of(const Document& d) {
    return d.path.has_parent_path() && d.path.is_absolute() ? d.path.parent_path() : fs::current_path();
  }

  // window/logMessage (1 error, 2 warning, 3 info), and the log file.
  void log_message(int type, const std::string& text) {
    log(text);
    send({{"jsonrpc", "2.0"}, {"method", "window/logMessage"}, {"params", {{"type", type}, {"message", text}}}});
  }

  void reply(const json& id, const json& result) {
    replied_ = true;
    send({{"jsonrpc", "2.0"}, {"id", id}, {"result", result}});
  }

  void send(const json& message) { send_text(json_text(message)); }

  void send_text(const std::string& body) { write_frame(out_, body); }

  std::ostream& out_;
  Inbox& inbox_;
  std::ofstream log_;
  Clock::time_point started_ = Clock::now();
  bool initialized_ = false, shut_down_ = false;
  // What the client can do (from initialize) and wants (settings).
  bool utf8_ = false, pull_ = false, refresh_ = false, lazy_edits_ = false, watch_ = false, unsafe_fixes_ = false, create_files_ = false;
  long analyses_ = 0, requests_ = 0;
  long include_generation_ = 0;  // raised whenever what includes declare may have changed
  std::deque<Document*> summarised_;  // the documents that keep their includes' summary, oldest first
  bool replied_ = false;  // the message being handled has had its answer
  std::map<std::string, Document> documents_;
  std::unique_ptr<ConfigFinder> configs_ = std::make_unique<ConfigFinder>();
  std::unique_ptr<IncludeSummaries> includes_ = std::make_unique<IncludeSummaries>();
};

}  // namespace

int run_language_server(std::istream& in, std::ostream& out, const ServerOptions& options) {
  Inbox inbox(in);
  Server server(out, inbox, options);
  while (std::optional<Incoming> incoming = inbox.next()) {
    if (!incoming->error.empty() || !incoming->framing.empty()) server.unsound(*incoming);
    if (!incoming->error.empty()) continue;
    if (std::optional<int> code = server.handle(incoming->message)) return *code;
  }
  server.log("the input ended without `exit`");
  return 1;
}

}  // namespace lwc
