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
  const clang::FieldDecl* member = nullptr;  // the high half, beside which the low one is declared
};

// The rewrite, or why there is none ("the parameter struct is declared in another file").
std::variant<HighLowFix, std::string> high_low_fix(const Upload& up, clang::ASTContext& context);

// Whether the function holding `e` also writes `field`'s low half (a member named as the split
// names say: `PositionLow`, `position_low`): then `field` is the high half of a split made there.
bool writes_low_half(const clang::FieldDecl* field, const clang::Expr* e, clang::ASTContext& context, const Tables& tables);

// A check of uploads whose findings are ported: translated where the camera is in scope (the
// cheaper port: one float on the GPU, no pair arithmetic), else split high/low.
class PortedUploadCheck : public UploadCheck {
 public:
  using UploadCheck::UploadCheck;
  void upload(const Upload& up, const clang::ast_matchers::MatchFinder::MatchResult& match) override;

 protected:
  virtual bool reports(const Upload& up) const = 0;
  virtual const char* port() const = 0;  // the finding's "port" fact until a high/low fix replaces it
  // Adds the translated fix with the camera in scope: "" when added, else why not.
  virtual std::string translated(const Upload& up, const CameraInScope& camera, Finding& finding, Vars& vars,
                                 const clang::ast_matchers::MatchFinder::MatchResult& match) = 0;
};

}  // namespace lwc::host
