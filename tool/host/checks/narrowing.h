#pragma once
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <clang/ASTMatchers/ASTMatchFinder.h>

#include "host/check.h"
#include "host/world.h"

namespace lwc::host {

// A double world value narrowed to float on its way to the GPU: what lwc-host-narrowed-world-upload
// (positions) and lwc-host-narrowed-world-matrix (matrices) report.
struct Upload {
  const clang::Expr* narrowing = nullptr;  // the float value: the cast or the construction
  const clang::Expr* value_expr = nullptr;  // the double value it narrows
  Value value;
  std::string narrowing_type;  // `FVector3f`, `float`, `vec`
  std::string sink;            // where it goes, e.g. "shader parameter `ActorPosition` of `FParameters`"
  std::string field;           // the member it is stored in ("" for an upload call)
  bool gpu = true;             // false: stored in a member of CPU-side data (lwc-host-float-world-storage)
  bool vertex = false;         // the member's struct is a vertex layout (GpuSinks::vertex_layout)
};

// The matchers of every narrowing: conversions to a float vector or matrix type, casts to float,
// implicit double-to-float conversions. Each match is bound to "narrowing".
void register_narrowings(clang::ast_matchers::MatchFinder& finder, clang::ast_matchers::MatchFinder::MatchCallback* callback, const Tables& tables);

// `v.cast<float>()`: a call of one of the tables' narrowing methods with a float scalar as its template argument.
bool narrowing_method_call(const clang::Expr* e, const World& world);

// Where values reach the GPU in one unit: the tables' sinks, and the structs the unit copies into
// mapped GPU memory (`memcpy(frame.mapped, &globals, ...)`) or hands to an upload call by address
// (`glBufferSubData(..., &globals)`), whatever they are named. Those are found by one walk of the
// unit, made the first time a narrowed world value reaches a member of a struct not named as a GPU
// block.
class GpuSinks {
 public:
  explicit GpuSinks(const Tables& tables) : tables(tables) {}
  bool uploaded(const clang::RecordDecl* record, clang::ASTContext& context) const;
  // Whether the unit gives `sizeof(record)` as a vertex stride (`glVertexAttribPointer(..., sizeof(V), ...)`,
  // `binding.stride = sizeof(V)`): then the struct is a vertex layout, which no shader block mirrors.
  bool vertex_layout(const clang::RecordDecl* record, clang::ASTContext& context) const;
  const Tables& tables;

 private:
  mutable std::optional<std::set<const clang::Decl*>> uploaded_, strides_;
};

// The upload a match is, when its value is a world value (a position, a world matrix or a
// model-view product) and it reaches a GPU sink or a member of CPU-side data (`gpu` says which).
std::optional<Upload> find_upload(const clang::ast_matchers::MatchFinder::MatchResult& match, const GpuSinks& sinks);

// A check that reads the uploads the narrowing matchers find. The engine registers those matchers
// once; each match is worked out once (find_upload) and handed to every such check.
class UploadCheck : public Check {
 public:
  using Check::Check;
  void register_matchers(clang::ast_matchers::MatchFinder&) override {}
  void run(const clang::ast_matchers::MatchFinder::MatchResult&) override {}
  virtual void upload(const Upload& up, const clang::ast_matchers::MatchFinder::MatchResult& match) = 0;
};

// One per unit.
struct NarrowingFan : clang::ast_matchers::MatchFinder::MatchCallback {
  explicit NarrowingFan(const Tables& tables) : sinks(tables) {}
  GpuSinks sinks;
  std::vector<UploadCheck*> checks;
  void run(const clang::ast_matchers::MatchFinder::MatchResult& match) override {
    if (in_template_pattern(match.Nodes)) return;
    if (std::optional<Upload> up = find_upload(match, sinks))
      for (UploadCheck* check : checks) check->upload(*up, match);
  }
};

// How the function holding an upload reaches the camera (a parameter or local of a view type,
// rules/host-world.json "views"): `code` is added to a world position (PreViewTranslation) or,
// with `subtract`, subtracted from it (a camera origin).
struct CameraInScope {
  std::string code;  // e.g. `View.ViewMatrices.GetPreViewTranslation()`
  bool subtract = false;
};
std::optional<CameraInScope> camera_in_scope(const clang::Expr* e, clang::ASTContext& context, const Tables& tables);

// An upload reported as `rule`'s finding (message variables narrowing, type, value, sink, field;
// facts shader-parameter and `port`). Null when not in a reported file.
Finding* report_upload(const Upload& up, const clang::ast_matchers::MatchFinder::MatchResult& match, const RuleInfo& rule, Reporter& out,
                       const Tables& tables, const std::string& port, Vars& vars);

}  // namespace lwc::host
