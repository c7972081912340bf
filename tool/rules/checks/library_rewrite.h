#pragma once
#include <string>
#include <vector>

#include "rules/checks/util.h"

namespace lwc::checks {

// A large-world value (a member UE5 holds as FDF*/FLWC*, or what a hack marker demotes) where the
// code uses it as a float.
struct LargeWorldValue {
  int node = -1;               // the expression used as a float: `M`, `M.xyz`, `DFHackToFloat(M)`
  std::string text;            // the large-world value, as the library call takes it
  Kind kind = Kind::unknown;   // absolute or camera-offset position, or a to- or from-world matrix
  std::string object, member;  // when it is `Object.Member`: the view's translated twins
};

// That use rewritten into the era's large-world library, the arithmetic done on the large-world
// value and rounded to float once (DFSubtractDemote, DFToFloat3x3, DFMultiply, a translated-twin
// projection; the LWC* names for UE 5.0-5.3). `fix` names the rule's fix kind ("demote",
// "rotation", "transform", "translated-twin"); empty when there is none, `blocker` then saying why
// where lwcport knows.
struct LibraryRewrite {
  std::string fix;
  Vars vars;  // "call", and "twin" for a translated-twin projection
  std::vector<Edit> edits;
  std::string blocker;
};
// In a sum or difference with a large-world position (`use` stands for it, of kind `kind`), the
// float operand when it is itself an absolute position: by its kind, or by the arithmetic (what
// the pre-view translation is added to; what an absolute position is subtracted from, or takes
// away). Beside such an operand one exact term gains nothing, as the two float32 roundings of the
// original often cancel: both must move to translated world together. -1 when there is none.
int absolute_partner(const CheckContext& ctx, int use, Kind kind);

LibraryRewrite library_rewrite(const CheckContext& ctx, const LargeWorldValue& value, bool double_float);

}  // namespace lwc::checks
