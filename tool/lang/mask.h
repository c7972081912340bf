#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/source.h"
#include "lang/macros.h"

namespace lwc {

enum class Lang;

// The text the grammar is given: the file rewritten byte for byte, so every node's offsets still
// match the file. Both languages: a UTF-8 BOM becomes spaces; preprocessor groups the grammar
// cannot read where they stand are resolved per variant (lang/conditionals.h); macros used as
// syntax are masked by their use (lang/macros.h: the table given plus the file's own #defines).
// HLSL (read with the C++ grammar): semantics, register/packoffset bindings, attributes and
// parameter/storage modifiers become spaces; `precise` becomes `mutable` so a qualifier node stays
// where it was; `cbuffer Name` becomes `extern"C"` (a block that needs no trailing semicolon);
// Niagara `{Placeholder}`s become identifiers and `%{placeholder}`s spaces. GLSL: `precision`
// statements and interface defaults (`layout(local_size_x = 64) in;`) become spaces.
class ParseReuse;

struct MaskOptions {
  const MacroTable* macros = nullptr;  // the macros known (default: known_macros); the file's own #defines are added
  int variant = 0;
  // The parser's budget (parse()): its error recovery on some broken input has no bound.
  double max_parse_seconds = 30;
  ParseReuse* reuse = nullptr;  // the last parse of this document, edited rather than parsed again (lang/syntax.h)
};

struct MaskResult {
  std::string text;
  std::optional<uint32_t> unterminated_comment;
  int variants = 1;                        // variants needed to see every arm of every resolved group
  std::vector<Span> resolved_conditionals;  // their byte ranges: no rewrite may touch them
  std::vector<Span> kept_arms;              // the arms of them this variant keeps (where variants differ)
};

MaskResult mask_source(std::string_view text, Lang lang, const MaskOptions& options = {});

}  // namespace lwc
