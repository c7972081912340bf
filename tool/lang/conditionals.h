#pragma once
#include <string_view>
#include <vector>

#include "core/source.h"
#include "lang/lexer.h"

namespace lwc {

// Preprocessor conditionals the grammar cannot read where they stand: a group inside a parameter
// list, an argument list, an expression or an initialiser, between `}` and `else`, one whose arms
// are not balanced on their own (`#if A` / `void F(int a) {` / `#else` / `void F() {`), and every
// `#if 0`. Such a group is resolved per variant: variant v keeps the v-th arm (the last one when
// there are fewer; an absent `#else` counts as an empty arm; an `#if 0` arm is never kept) and
// drops the others and the directives, so each variant is one coherent program and together they
// cover every arm. Groups where the grammar copes are left alone and seen in one pass.
struct ConditionalPlan {
  int variants = 1;                // how many variants cover every arm of every resolved group
  std::vector<bool> dropped;       // per token: not part of this variant
  std::vector<Span> regions;       // byte ranges of the resolved groups, directives included
  std::vector<Span> kept_arms;     // the arms this variant keeps where other variants keep others
};

// At most this many variants are parsed; arms past the last are seen in none (rare: a group
// with more than four arms inside an expression).
inline constexpr int kMaxVariants = 4;

ConditionalPlan plan_conditionals(std::string_view text, const std::vector<Token>& tokens, int variant);

}  // namespace lwc
