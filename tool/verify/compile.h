#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lang/syntax.h"

namespace lwc {

enum class Stage { vertex, fragment, compute, geometry, tess_control, tess_evaluation, task, mesh,
                   ray_generation, closest_hit, any_hit, miss, intersection, callable };

// A glslang diagnostic, positioned in the named source it came from.
struct CompileMessage {
  std::string source;  // the file name glslang was given, or the included name
  int line = 0;
  std::string text;
};

// An include found: the name messages and nested includes know it by (the real path where there
// is one, so relative includes inside it resolve from its folder), and its text.
struct IncludedFile {
  std::string name;
  std::string text;
};
// Resolves `#include "name"` written in the source named `from`; nullopt when not found.
using IncludeResolver = std::function<std::optional<IncludedFile>(const std::string& name, const std::string& from)>;

struct CompileInput {
  Lang lang = Lang::hlsl;
  Stage stage = Stage::fragment;
  std::string name;    // shown in messages
  std::string text;
  std::string preamble;  // declarations seen before `text` without shifting its line numbers
  std::string entry;   // entry point; HLSL needs one, GLSL uses main
  IncludeResolver include;
  bool spirv = false;  // also generate Vulkan SPIR-V (GLSL then needs a Vulkan-legal shader)
  bool debug_lines = false;  // with OpLine source lines in the SPIR-V
  bool vulkan = false; // GLSL for Vulkan (descriptor sets, push constants) rather than OpenGL
};

struct CompileResult {
  bool ok = false;
  std::string crashed;  // compile_shader_isolated: why glslang gave no answer (a crash, a hang)
  std::vector<CompileMessage> messages;
  std::vector<uint32_t> spirv;
};

// The messages as "source:line: text" lines, for logs and test failures.
std::string format_messages(const CompileResult& result);

// Parses, checks and links one shader with glslang (the library, no process), optionally to SPIR-V.
// glslang's error recovery can crash on invalid code: code that has not compiled before (a user's
// file) goes through compile_shader_isolated first.
CompileResult compile_shader(const CompileInput& input);
// The same in a child process: a crash or a hang comes back as `crashed`, not as this process's end.
CompileResult compile_shader_isolated(const CompileInput& input);

// Runs only glslang's preprocessor: the text with includes inlined, macros expanded and inactive
// #if branches gone (what the compiler itself sees). `spirv` and `entry` are ignored.
struct PreprocessResult {
  bool ok = false;
  std::string text;
  std::vector<CompileMessage> messages;
};
PreprocessResult preprocess_shader(const CompileInput& input);

// The stage a GLSL file's extension names (.vert, .frag, .comp, .geom, .tesc, .tese, .task,
// .mesh, .rgen, .rchit, .rahit, .rmiss, .rint, .rcall), if any.
std::optional<Stage> stage_from_extension(const std::string& path);

// The text without a leading UTF-8 byte-order mark, which glslang reads as a bad token (Unreal's
// editors write one in some headers).
std::string_view without_bom(std::string_view text);

// glslang's HLSL preprocessor has no variadic macros (`#define M(...) __VA_ARGS__`), which engine
// headers define (Unreal 5.0's platform layer, on every path): each becomes a macro of one
// argument, which covers a call whose arguments hold no top-level comma.
std::string with_single_argument_variadics(std::string text);
// Nor can glslang tell a ByteAddressBuffer parameter from a RWByteAddressBuffer one: an overload
// pair differing only there (Unreal 5.4's hair strands readers, under every material) is a
// redefinition to it. The writable one is renamed; a call with either buffer takes the other.
std::string with_distinct_buffer_overloads(std::string text);
// Nor evaluate an unsigned literal (`1u`) in an `#if`: a macro whose body is an integer
// expression of such literals, each below 2^31, loses the suffixes (the value is the same).
std::string with_signed_constant_macros(std::string text);

// A whole file compiled on its own, as `fix --check-build` and the corpus tests check it: HLSL
// through a do-nothing entry point appended after it (every function is type-checked; line
// numbers unchanged), Unreal code after the engine stub of an era (LWCPORT_UE_VERSION 427, 500,
// 504), GLSL as the stage its extension names, for OpenGL or for Vulkan.
struct FileBuild {
  Lang lang = Lang::hlsl;
  std::string name;
  std::optional<int> unreal_version;  // Unreal code: the era's stub comes first
  bool vulkan = false;                // GLSL: compile for Vulkan
  IncludeResolver include;
  std::vector<std::pair<std::string, std::string>> defines;  // the build's macros (.lwcport.json)
  std::vector<std::string> force_includes;                    // HLSL: included ahead of the file (.lwcport.json)
};
// `#define NAME VALUE` lines, for a preamble.
std::string define_lines(const std::vector<std::pair<std::string, std::string>>& defines);
// An HLSL text with `force_includes` included ahead of it, its own lines still its own (`#line`).
std::string with_forced_includes(const std::vector<std::string>& force_includes, const std::string& name, std::string_view text);
// Through compile_shader_isolated.
CompileResult compile_file(const FileBuild& build, const std::string& text);

}  // namespace lwc
