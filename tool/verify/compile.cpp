#include "verify/compile.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <fmt/format.h>

#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <csignal>
#include <cstring>
#include <deque>
#include <map>
#include <mutex>
#include <regex>
#include <set>
#include <sstream>

#include "core/fd_io.h"
#include "core/fork_gate.h"
#include "lang/tokens.h"
#include "shaderlib/shaderlib.h"

namespace lwc {
namespace {

void initialize_glslang() {
  static std::once_flag once;
  std::call_once(once, [] {
    glslang::InitializeProcess();
    std::atexit([] { glslang::FinalizeProcess(); });
  });
}

EShLanguage to_glslang(Stage stage) {
  switch (stage) {
    case Stage::vertex: return EShLangVertex;
    case Stage::fragment: return EShLangFragment;
    case Stage::compute: return EShLangCompute;
    case Stage::geometry: return EShLangGeometry;
    case Stage::tess_control: return EShLangTessControl;
    case Stage::tess_evaluation: return EShLangTessEvaluation;
    case Stage::task: return EShLangTask;
    case Stage::mesh: return EShLangMesh;
    case Stage::ray_generation: return EShLangRayGen;
    case Stage::closest_hit: return EShLangClosestHit;
    case Stage::any_hit: return EShLangAnyHit;
    case Stage::miss: return EShLangMiss;
    case Stage::intersection: return EShLangIntersect;
    case Stage::callable: return EShLangCallable;
  }
  return EShLangFragment;
}

// Hands glslang the text the caller's resolver finds; keeps it alive until glslang releases it.
class Includer : public glslang::TShader::Includer {
 public:
  // The file compiled counts as included once already when it says `#pragma once` (a forced
  // include of the engine's Common.ush, compiling Common.ush itself).
  explicit Includer(const CompileInput& input) : input_(input) {
    if (has_pragma_once(input.text)) included_once_.insert(input.name);
  }
  IncludeResult* includeLocal(const char* name, const char* from, size_t) override { return find(name, from); }
  IncludeResult* includeSystem(const char* name, const char* from, size_t) override { return find(name, from); }
  void releaseInclude(IncludeResult*) override {}

 private:
  IncludeResult* find(const char* name, const char* from) {
    if (!input_.include) return nullptr;
    std::optional<IncludedFile> found = input_.include(name, from ? from : "");
    if (!found) return nullptr;
    found->text.erase(0, found->text.size() - without_bom(found->text).size());
    if (input_.lang == Lang::hlsl)
      found->text = with_signed_constant_macros(with_distinct_buffer_overloads(with_single_argument_variadics(std::move(found->text))));
    // glslang ignores `#pragma once` (Unreal's headers rely on it): a second include of such a
    // file is empty here, else the engine's include graph is read again on every path into it.
    if (included_once_.count(found->name)) found->text.clear();
    else if (has_pragma_once(found->text)) included_once_.insert(found->name);
    // A bound on what one compile reads, so no include graph exhausts memory.
    if ((bytes_ += found->text.size()) > kMaxIncludedBytes) return nullptr;
    // glslang's HLSL preprocessor marks no include's start or end in its output: `#line`s around
    // the text keep every later message (and the harness's cut of the output) on the real file
    // and line. (Its GLSL preprocessor writes them itself.)
    std::string includer = from ? from : "";
    if (input_.lang == Lang::hlsl) {
      std::string back;
      if (int line = include_line(includer, name); line > 0) back = fmt::format("\n#line {} \"{}\"\n", line + 1, includer);
      found->text = fmt::format("#line 1 \"{}\"\n{}{}", found->name, found->text, back);
    }
    files_.push_back(std::move(*found));
    texts_[files_.back().name] = &files_.back().text;
    results_.emplace_back(files_.back().name, files_.back().text.data(), files_.back().text.size(), nullptr);
    return &results_.back();
  }
  // The line of the next `#include` of `name` in the file `includer` (glslang asks in order), or 0.
  int include_line(const std::string& includer, const std::string& name) {
    const std::string* text = includer == input_.name ? &input_.text : texts_.count(includer) ? texts_[includer] : nullptr;
    if (!text) return 0;
    size_t& from = next_include_[includer];
    for (size_t at = text->find(name, from); at != std::string::npos; at = text->find(name, at + 1)) {
      size_t begin = text->rfind('\n', at);
      begin = begin == std::string::npos ? 0 : begin + 1;
      TokenText head(std::string_view(*text).substr(begin, at - begin));
      if (head.size() < 3 || head[0] != "#" || head[1] != "include") continue;
      from = at + name.size();
      int line = 1 + static_cast<int>(std::count(text->begin(), text->begin() + static_cast<std::ptrdiff_t>(begin), '\n'));
      return text == &input_.text ? line : line - 1;  // an include's text starts with our `#line 1`
    }
    return 0;
  }
  static bool has_pragma_once(std::string_view text) {
    for (size_t at = text.find("once"); at != std::string_view::npos; at = text.find("once", at + 4)) {
      size_t line = text.rfind('\n', at);
      line = line == std::string_view::npos ? 0 : line + 1;
      std::string head;
      for (char c : text.substr(line, at + 4 - line))
        if (c != ' ' && c != '\t') head += c;
      if (head == "#pragmaonce") return true;
    }
    return false;
  }
  static constexpr size_t kMaxIncludedBytes = 256u << 20;
  const CompileInput& input_;
  std::set<std::string> included_once_;
  std::map<std::string, const std::string*> texts_;  // what each included name read, for include_line
  std::map<std::string, size_t> next_include_;       // per includer, where the next search starts
  size_t bytes_ = 0;
  std::deque<IncludedFile> files_;
  std::deque<IncludeResult> results_;
};

// The strings glslang reads when it parses: they must outlive the parse.
// GLSL `#include`, which lint resolves, is a glslang extension: turned on for every GLSL file (an
// engine's own preprocessor, or the file's `#extension` line, usually does).
struct SourceStrings {
  explicit SourceStrings(const CompileInput& input)
      : text(input.text.c_str()), name(input.name.c_str()), length(static_cast<int>(input.text.size())),
        preamble((input.lang == Lang::hlsl ? "" : "#extension GL_GOOGLE_include_directive : enable\n") + input.preamble) {}
  const char* text;
  const char* name;
  int length;
  std::string preamble;
};

// The source, preamble and input language; `vulkan`: compile for Vulkan SPIR-V (HLSL always is).
void set_source(glslang::TShader& shader, const CompileInput& input, SourceStrings& s, EShLanguage stage, bool vulkan) {
  shader.setStringsWithLengthsAndNames(&s.text, &s.length, &s.name, 1);
  bool hlsl = input.lang == Lang::hlsl;
  if (!s.preamble.empty()) shader.setPreamble(s.preamble.c_str());
  shader.setEnvInput(hlsl ? glslang::EShSourceHlsl : glslang::EShSourceGlsl, stage,
                     vulkan ? glslang::EShClientVulkan : glslang::EShClientNone, 100);
  if (vulkan) {
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
  }
}

// glslang's info log: "ERROR: name:line: message" (or "ERROR: message" without a place).
void read_log(const char* log, std::vector<CompileMessage>& out) {
  std::istringstream in(log ? log : "");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("ERROR: ", 0) != 0) continue;
    if (line.find("compilation errors.  No code generated") != std::string::npos) continue;
    out.push_back({"", 0, line.substr(7)});
    // The place is the first ":digits: " after the prefix.
    for (size_t colon = line.find(':', 7); colon != std::string::npos; colon = line.find(':', colon + 1)) {
      int number = 0;
      auto [end, error] = std::from_chars(line.data() + colon + 1, line.data() + line.size(), number);
      if (error != std::errc() || std::string_view(end, line.data() + line.size()).substr(0, 2) != ": ") continue;
      out.back() = {line.substr(7, colon - 7), number, std::string(end + 2)};
      break;
    }
  }
}

// The lowest desktop GLSL version that has the stage. glslang refuses an explicit `#version` below
// it with an error, but for a text without one it sets up the stage's built-ins at its default
// (110), fails, and prints the whole built-in text to standard output, into lwcport's report.
int minimum_version(Stage stage) {
  switch (stage) {
    case Stage::vertex:
    case Stage::fragment: return 110;
    case Stage::geometry: return 150;
    case Stage::tess_control:
    case Stage::tess_evaluation: return 400;
    case Stage::compute: return 430;
    default: return 450;  // mesh, task and ray tracing: 450 with their extensions
  }
}

// The version glslang assumes for a text without `#version`: GLSL's own 110 where the stage has it.
int default_version(const CompileInput& input) {
  if (input.lang == Lang::hlsl) return 500;
  return std::max(110, minimum_version(input.stage));
}

}  // namespace

namespace {

CompileResult compile_shader_here(const CompileInput& input) {
  initialize_glslang();
  CompileResult result;
  EShLanguage stage = to_glslang(input.stage);
  glslang::TShader shader(stage);
  SourceStrings strings(input);
  bool hlsl = input.lang == Lang::hlsl;
  bool vulkan = input.spirv || input.vulkan;
  set_source(shader, input, strings, stage, vulkan || hlsl);
  shader.setEntryPoint(hlsl ? input.entry.c_str() : "main");
  auto messages = static_cast<EShMessages>(EShMsgDefault | (hlsl ? EShMsgReadHlsl : EShMsgDefault) |
                                           (vulkan ? EShMsgSpvRules | EShMsgVulkanRules : EShMsgDefault) |
                                           (input.debug_lines ? EShMsgDebugInfo : EShMsgDefault));
  Includer includer(input);
  if (!shader.parse(GetDefaultResources(), default_version(input), false, messages, includer)) {
    read_log(shader.getInfoLog(), result.messages);
    return result;
  }
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages)) {
    read_log(program.getInfoLog(), result.messages);
    return result;
  }
  if (input.spirv) {
    glslang::SpvOptions options;
    options.disableOptimizer = true;  // the driver must see every operation as written
    options.generateDebugInfo = input.debug_lines;
    glslang::GlslangToSpv(*program.getIntermediate(stage), result.spirv, &options);
  }
  result.ok = true;
  return result;
}

}  // namespace

PreprocessResult preprocess_shader(const CompileInput& input) {
  ForkGateHold hold;
  initialize_glslang();
  PreprocessResult result;
  EShLanguage stage = to_glslang(input.stage);
  glslang::TShader shader(stage);
  SourceStrings strings(input);
  bool hlsl = input.lang == Lang::hlsl;
  // GLSL as written (an ES 3.00 shader is not SPIR-V-legal, and need not be to be preprocessed).
  set_source(shader, input, strings, stage, hlsl);
  auto messages = static_cast<EShMessages>(EShMsgDefault | (hlsl ? EShMsgReadHlsl : EShMsgDefault));
  Includer includer(input);
  result.ok = shader.preprocess(GetDefaultResources(), default_version(input), ENoProfile, false, false, messages, &result.text, includer);
  if (!result.ok) read_log(shader.getInfoLog(), result.messages);
  return result;
}

std::string format_messages(const CompileResult& result) {
  std::string out;
  for (const CompileMessage& m : result.messages) out += m.source + ":" + std::to_string(m.line) + ": " + m.text + "\n";
  return out;
}

std::optional<Stage> stage_from_extension(const std::string& path) {
  static const std::pair<const char*, Stage> stages[] = {
      {".vert", Stage::vertex},         {".frag", Stage::fragment},     {".comp", Stage::compute},
      {".geom", Stage::geometry},       {".tesc", Stage::tess_control}, {".tese", Stage::tess_evaluation},
      {".task", Stage::task},           {".mesh", Stage::mesh},         {".rgen", Stage::ray_generation},
      {".rchit", Stage::closest_hit},   {".rahit", Stage::any_hit},     {".rmiss", Stage::miss},
      {".rint", Stage::intersection},   {".rcall", Stage::callable},    {".vsh", Stage::vertex},
      {".fsh", Stage::fragment}};
  for (auto [ext, stage] : stages)
    if (path.ends_with(ext)) return stage;
  return std::nullopt;
}

std::string define_lines(const std::vector<std::pair<std::string, std::string>>& defines) {
  std::string out;
  for (const auto& [name, value] : defines) out += "#define " + name + (value.empty() ? "" : " " + value) + "\n";
  return out;
}

std::string with_single_argument_variadics(std::string text) {
  static const std::regex variadic(R"(^([ \t]*#[ \t]*define[ \t]+\w+\([^)]*)\.\.\.\))", std::regex::multiline);
  if (text.find("...)") == std::string::npos) return text;
  std::string out;
  size_t done = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), variadic); it != std::sregex_iterator(); ++it) {
    size_t begin = static_cast<size_t>(it->position(0));
    size_t end = text.find('\n', begin);  // the definition's line, and its continuations
    while (end != std::string::npos && end > 0 && text[end - 1] == '\\') end = text.find('\n', end + 1);
    if (end == std::string::npos) end = text.size();
    std::string definition = (*it)[1].str() + "LWCPORT_VA_ARGS)" + text.substr(begin + it->length(0), end - begin - it->length(0));
    for (size_t at = definition.find("__VA_ARGS__"); at != std::string::npos; at = definition.find("__VA_ARGS__", at))
      definition.replace(at, 11, "LWCPORT_VA_ARGS");
    out += text.substr(done, begin - done) + definition;
    done = end;
  }
  return out + text.substr(done);
}

std::string with_distinct_buffer_overloads(std::string text) {
  if (text.find("RWByteAddressBuffer") == std::string::npos) return text;
  static const std::regex head(R"(\b([A-Za-z_]\w*)\s*\(([^;{}()]*(?:\([^;{}()]*\)[^;{}()]*)*)\)\s*\{)");
  static const std::regex read_only(R"((^|[^\w])ByteAddressBuffer\b)");
  std::set<std::string> read_only_overloads;
  std::vector<std::pair<size_t, std::string>> writable;  // where a definition's name starts, and the name
  for (auto it = std::sregex_iterator(text.begin(), text.end(), head); it != std::sregex_iterator(); ++it) {
    std::string params = (*it)[2].str();
    if (params.find("RWByteAddressBuffer") != std::string::npos) writable.emplace_back(static_cast<size_t>(it->position(1)), (*it)[1].str());
    else if (std::regex_search(params, read_only)) read_only_overloads.insert((*it)[1].str());
  }
  // From the end, so earlier positions stay right.
  for (auto w = writable.rbegin(); w != writable.rend(); ++w)
    if (read_only_overloads.count(w->second)) text.insert(w->first + w->second.size(), "_LwcportWritable");
  return text;
}

std::string with_signed_constant_macros(std::string text) {
  // A #define whose whole body is an integer expression with unsigned literals below 2^31.
  static const std::regex define(R"(^([ \t]*#[ \t]*define[ \t]+\w+[ \t]+)([-+*/%<>&|^~() \t0-9a-fA-FxXuU]*[0-9][uU][-+*/%<>&|^~() \t0-9a-fA-FxXuU]*)$)",
                                 std::regex::multiline);
  static const std::regex literal(R"(\b(0[xX][0-9a-fA-F]+|[0-9]+)[uU]\b)");
  // Most headers have no such macro: the regular expression only runs where a #define line holds
  // a digit followed by `u`.
  bool candidate = false;
  for (size_t at = text.find("#define"); at != std::string::npos && !candidate; at = text.find("#define", at + 7)) {
    size_t end = std::min(text.find('\n', at), text.size());
    for (size_t i = at + 8; i + 1 < end && !candidate; ++i)
      candidate = std::isdigit(static_cast<unsigned char>(text[i])) && (text[i + 1] == 'u' || text[i + 1] == 'U');
  }
  if (!candidate) return text;
  std::string out;
  size_t done = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), define); it != std::sregex_iterator(); ++it) {
    std::string body = (*it)[2].str();
    bool small = true;
    for (auto l = std::sregex_iterator(body.begin(), body.end(), literal); l != std::sregex_iterator(); ++l)
      small &= std::stoull((*l)[1].str(), nullptr, 0) < (1ull << 31);
    if (!small) continue;
    out += text.substr(done, static_cast<size_t>(it->position(2)) - done) + std::regex_replace(body, literal, "$1");
    done = static_cast<size_t>(it->position(2) + it->length(2));
  }
  return out + text.substr(done);
}

std::string_view without_bom(std::string_view text) { return text.starts_with("\xEF\xBB\xBF") ? text.substr(3) : text; }

std::string with_forced_includes(const std::vector<std::string>& force_includes, const std::string& name, std::string_view text) {
  std::string out;
  for (const std::string& include : force_includes) out += fmt::format("#include \"{}\"\n", include);
  return out + fmt::format("#line 1 \"{}\"\n", name) + std::string(without_bom(text));
}

CompileResult compile_file(const FileBuild& build, const std::string& text) {
  CompileInput in;
  in.lang = build.lang;
  in.name = build.name;
  in.text = build.lang == Lang::hlsl ? with_forced_includes(build.force_includes, build.name, text) : std::string(without_bom(text));
  in.include = build.include;
  in.vulkan = build.vulkan;
  in.preamble = define_lines(build.defines);
  if (build.lang == Lang::hlsl) {
    in.stage = Stage::fragment;
    in.entry = "lwcport_compile_check";
    in.text += "\nvoid lwcport_compile_check() {}\n";
    if (build.unreal_version)
      in.preamble += "#define LWCPORT_UE_VERSION " + std::to_string(*build.unreal_version) + "\n#define LWCPORT_VIEW_STORAGE static\n" +
                     unreal_environment_text(text);
  } else {
    std::optional<Stage> stage = stage_from_extension(build.name);
    in.stage = stage.value_or(Stage::fragment);
    // A GLSL include (no stage in its name, no main): checked as a unit of its own.
    TokenText t(text);
    bool has_main = false;
    for (size_t i = 0; i < t.size() && !has_main; ++i) has_main = t.spells(i, {"void", "main", "("});
    if (!stage && !has_main) in.text += "\nvoid main() {}\n";
  }
  return compile_shader_isolated(in);
}

namespace {

// A result through a pipe: ok, the messages, the SPIR-V words.
void put(std::string& out, std::string_view bytes) {
  uint32_t size = static_cast<uint32_t>(bytes.size());
  out.append(reinterpret_cast<const char*>(&size), sizeof size).append(bytes);
}
bool take(std::string_view& in, std::string& bytes) {
  uint32_t size = 0;
  if (in.size() < sizeof size) return false;
  std::memcpy(&size, in.data(), sizeof size);
  in.remove_prefix(sizeof size);
  if (in.size() < size) return false;
  bytes.assign(in.substr(0, size));
  in.remove_prefix(size);
  return true;
}
std::string serialise(const CompileResult& r) {
  std::string out(1, r.ok ? '1' : '0');
  put(out, std::to_string(r.messages.size()));
  for (const CompileMessage& m : r.messages) {
    put(out, m.source);
    put(out, std::to_string(m.line));
    put(out, m.text);
  }
  put(out, std::string_view(reinterpret_cast<const char*>(r.spirv.data()), r.spirv.size() * sizeof(uint32_t)));
  return out;
}
std::optional<CompileResult> deserialise(std::string_view in) {
  CompileResult r;
  if (in.empty()) return std::nullopt;
  r.ok = in.front() == '1';
  in.remove_prefix(1);
  std::string field;
  if (!take(in, field)) return std::nullopt;
  size_t count = std::stoul(field);
  for (size_t i = 0; i < count; ++i) {
    CompileMessage m;
    std::string line;
    if (!take(in, m.source) || !take(in, line) || !take(in, m.text)) return std::nullopt;
    m.line = std::stoi(line);
    r.messages.push_back(std::move(m));
  }
  if (!take(in, field)) return std::nullopt;
  r.spirv.resize(field.size() / sizeof(uint32_t));
  std::memcpy(r.spirv.data(), field.data(), r.spirv.size() * sizeof(uint32_t));
  return r;
}

}  // namespace

// glslang's error recovery crashes on some invalid HLSL (a missing member of a uniform struct that
// holds textures, used as an initializer), and what is compiled here is a user's code: each
// compile runs in a child process, so a crash or a hang costs that compile only.
// glslang's tables sit behind its own mutex, which a compile child also takes: held under the
// fork gate (core/fork_gate.h).
CompileResult compile_shader(const CompileInput& input) {
  ForkGateHold hold;
  return compile_shader_here(input);
}

CompileResult compile_shader_isolated(const CompileInput& input) {
  constexpr int kSeconds = 120;
  int fds[2];
  if (::pipe(fds) != 0) return compile_shader(input);
  pid_t pid = fork_alone();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return compile_shader(input);
  }
  if (pid == 0) {
    // Other threads' pipes and driver sockets stay theirs: a copy held here would keep their
    // reader from seeing the end of its answer until this compile ends.
    if (fds[1] != 3 && ::dup2(fds[1], 3) == 3) fds[1] = 3;
    ::close_range(fds[1] + 1, ~0U, 0);
    write_all(fds[1], serialise(compile_shader_here(input)));
    ::_exit(0);
  }
  ::close(fds[1]);
  std::string bytes;
  bool timed_out = false;
  auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kSeconds);
  for (char buffer[65536];;) {
    auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
    pollfd p{fds[0], POLLIN, 0};
    int ready = left > 0 ? ::poll(&p, 1, static_cast<int>(left)) : 0;
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) {
      timed_out = true;
      break;
    }
    ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    bytes.append(buffer, static_cast<size_t>(n));
  }
  ::close(fds[0]);
  if (timed_out) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (std::optional<CompileResult> r = deserialise(bytes); r && !timed_out) return *r;
  CompileResult failed;
  failed.crashed = timed_out ? fmt::format("glslang did not finish in {} s", kSeconds)
                   : WIFSIGNALED(status) ? fmt::format("glslang crashed (signal {})", WTERMSIG(status))
                                         : "glslang's process ended without an answer";
  failed.messages.push_back({input.name, 0, failed.crashed});
  return failed;
}

}  // namespace lwc
