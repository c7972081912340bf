#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "core/source.h"

namespace lwc {

// GLSL kept in JavaScript or TypeScript template literals: those tagged `glsl` (glsl`...`), those
// after a `/* glsl */` comment, those whose text starts with `#version`, and every literal of a
// `.glsl.js` / `.glsl.ts` file. The spans are the literals' contents (between the backticks).
std::vector<Span> glsl_template_literals(std::string_view path, std::string_view script);
// The same, with the `${...}` substitutions inside them.
std::vector<Span> glsl_template_literals(std::string_view path, std::string_view script, std::vector<Span>& substitutions);

// The script with everything outside those literals turned into spaces (line breaks kept), so the
// GLSL reads at the very byte offsets it has in the script: findings point into the script and
// fixes edit the literals. Each substitution becomes one identifier of its length.
std::string glsl_view(std::string_view script, const std::vector<Span>& literals, const std::vector<Span>& substitutions);

}  // namespace lwc
