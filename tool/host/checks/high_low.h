#pragma once
#include <string>
#include <variant>
#include <vector>

#include "host/check.h"
#include "host/checks/narrowing.h"

namespace lwc::host {

// The high/low rewrite of `Object.Member = <narrowing>;`: the member keeps the high half (the float
// nearest the value, which is what the narrowing already gives) and a new member declared beside it
// gets the rest, so the GPU can add the two back together. Unreal units that declare UE 5.4's
// DoubleFloat types (FDFVector3, FDFMatrix) get those; others get the split written out in double.
struct HighLowFix {
  std::vector<Reporter::Change> changes;
  std::string low;   // the new member: `ActorPositionLow`, `LocalToWorldPostTranslation`
  std::string form;  // what splits it: "`FDFVector3`", "`FDFMatrix::MakeToRelativeWorldMatrix`", "a difference in double"
  std::string read;  // how a shader reads the pair: "`MakeDFVector3(ObjectOrigin, ObjectOriginLow)`"
};

// The rewrite, or why there is none ("the parameter struct is declared in another file").
std::variant<HighLowFix, std::string> high_low_fix(const Upload& up, clang::ASTContext& context);

// Whether the function holding `e` also writes `field`'s low half (a member named as the split
// names say: `PositionLow`, `position_low`): then `field` is the high half of a split made there.
bool writes_low_half(const clang::FieldDecl* field, const clang::Expr* e, clang::ASTContext& context, const Tables& tables);

// Adds the high/low rewrite to a finding (message variables `low` and `form`), or says in its
// withheld list why there is none.
void offer_high_low(const Upload& up, Finding& finding, Vars& vars, const clang::ast_matchers::MatchFinder::MatchResult& match,
                    const RuleInfo& rule, Reporter& out);

}  // namespace lwc::host
