#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace lwc {

// HLSL-only syntax rewritten, byte for byte, into text the C++ grammar accepts, so every node's
// offsets still match the file: semantics, register/packoffset bindings, cbuffer/tbuffer blocks,
// attributes and parameter/storage modifiers become spaces; `precise` becomes `mutable` so a
// qualifier node stays where it was; `cbuffer Name` becomes `extern"C"` (a block that needs no
// trailing semicolon). A UTF-8 BOM becomes spaces in both languages.
struct MaskResult {
  std::string text;
  std::optional<uint32_t> unterminated_comment;
};
MaskResult mask_hlsl(std::string_view text);
MaskResult mask_glsl(std::string_view text);

}  // namespace lwc
