#pragma once
#include <optional>
#include <string>
#include <vector>

#include "rules/checks/util.h"

namespace lwc::checks {

// UE4's way to a translated transform: a float4x4 local copied from a world matrix, whose
// translation row then gets the pre-view translation added, one coordinate per statement
// (`M[3][0] += T.x; M[3][1] += T.y; M[3][2] += T.z;`) or at once (`M[3].xyz += T;`), before any
// other use. UE5 builds that matrix in one call from the large-world transform.
struct TranslationRow {
  int local = -1;               // the float4x4 variable
  int matrix = -1;              // its initial value, under any demotion
  std::vector<int> statements;  // the statements that add the translation, in source order
  int translation = -1;         // the translation added (`ResolvedView.PrevPreViewTranslation`)
};

// The translation row of the local `var`, or nullopt when the code is not that shape.
std::optional<TranslationRow> translation_row_of(const CheckContext& ctx, int var);
// The translation row a member read takes part in: the translation added (`T` in `M[3][0] += T.x`)
// or the world matrix the local is copied from (`float4x4 M = X.LocalToWorld;`).
std::optional<TranslationRow> translation_row_at(const CheckContext& ctx, int member);

}  // namespace lwc::checks
