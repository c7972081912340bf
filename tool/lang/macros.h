#pragma once
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

namespace lwc {

enum class Lang;

// How a macro is used as syntax, so the masker can turn it into something the grammar reads
// without moving a byte (lwcport never expands macros):
//   qualifier    expands to qualifiers or nothing: `INVARIANT_OUTPUT float4 P` -> blanked
//   attribute    a statement attribute, maybe with arguments: `UNROLL_N(3) for` -> blanked
//   suffix       a swizzle after an expression: `Tex.Load(P) STENCIL_COMPONENT_SWIZZLE` -> blanked
//   declaration  expands to declarations: `DECLARE_SCALAR_ARRAY(float, W, 5);` -> blanked
//   type         a type built from arguments: `MSTextureType(float4, 4) Tex` -> the name is the type
//   loop         a for loop with commas for semicolons: `Substrate_for(i = 0, i < n, ++i)`
enum class MacroUse : uint8_t { qualifier, attribute, suffix, declaration, type, loop };

std::optional<MacroUse> parse_macro_use(std::string_view name);
std::string_view macro_use_name(MacroUse use);

using MacroTable = std::map<std::string, MacroUse, std::less<>>;

// The built-in table (rules/macros.json) for a language.
const MacroTable& known_macros(Lang lang);

// Adds a JSON object {"NAME": "qualifier", ...} (from rule data or .lwcport.json "macros") to a
// table. Throws std::runtime_error naming `where` and the bad entry.
void add_macros(const nlohmann::json& table, std::string_view where, MacroTable& into);

// What the `#define` lines of a text teach: an object-like macro that expands to nothing or only
// to qualifiers is a qualifier, one that expands to a swizzle (`.x`) a suffix, one that expands to
// an attribute (`[unroll]`, or a known attribute macro) an attribute, a function-like macro whose
// body is a `for` a loop. `known` is consulted for bodies that name other macros.
void learn_macros(std::string_view text, const MacroTable& known, MacroTable& into);

}  // namespace lwc
