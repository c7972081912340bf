#pragma once
#include <optional>
#include <set>
#include <string>
#include <string_view>

#include "lang/syntax.h"

namespace lwc {

// lwcport's DoubleFloat shader library (tool/shaderlib/src/doublefloat.lwclib), emitted for one
// language. `names` are the types and functions the caller's code uses; the text holds those and
// everything they need, in dependency order, and nothing else.
std::string library_text(Lang lang, const std::set<std::string>& names);
// Every type and function of the library.
std::string full_library_text(Lang lang);
// The names the library defines that occur as identifiers in `code`.
std::set<std::string> library_names_used(Lang lang, std::string_view code);
// The file `lwcport fix` writes beside fixed code: lwc_doublefloat.hlsl / lwc_doublefloat.glsl.
std::string library_file_name(Lang lang);
// True for a library file `lwcport fix` wrote (its header says so): lint skips it, and fix may
// regenerate it; any other file of that name is the user's.
bool is_written_library(std::string_view text);
// The library file's text once `names` are added to what `existing` (the file's text now, if there
// is one) holds: what fix writes beside fixed code. None when `existing` is not a file lwcport wrote.
std::optional<std::string> library_file_text(Lang lang, const std::set<std::string>& names, const std::optional<std::string>& existing);

// An Unreal environment for compiling Unreal-era shaders without the engine: the library plus
// declarations of the View / PrimaryView / ResolvedView / Primitive members, the LWC tile/offset
// (FLWC*) types and functions, and the hack markers the rules touch (tool/shaderlib/src/unreal_stub.ush).
// `code`: the file compiled in it (a file that declares the material template's parameter structs
// itself does not get the stub's). `library`: the HLSL library text to put first ("" = lwcport's own).
std::string unreal_environment_text(std::string_view code = {}, const std::string& library = "");
// What an `/Engine/...` include that lwcport does not read gives: the engine's everyday macros
// (loop attributes, stereo declarations), and its small helpers (PI, Square, ConvertFromDeviceZ)
// unless the engine's own headers are read (unreal_engine_header.ush).
std::string unreal_engine_header_text(bool engine_headers_read);

}  // namespace lwc
