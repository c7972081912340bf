#pragma once
// The translated-world chain of lwc-float-world-position: a value that holds an absolute position
// moves to translated world together with everything it flows into (locals, parameters, returns,
// callers of this file), all or nothing, as edits of one fix. The shapes it moves through are in
// chain_shapes.h.
#include <string>
#include <utility>
#include <vector>

#include "rules/checks/util.h"

namespace lwc::checks {

// Unreal shader code by its file's extension (.usf, .ush).
bool unreal_code(const SyntaxTree& t);
// The semantic of an entry point's parameter (`ATTRIBUTE1`; not an `SV_` value), or "".
std::string input_semantic(const SyntaxTree& t, const Variable& p);

class TranslatedChain {
 public:
  // `primitive_objects`: the engine objects whose LocalToWorld is a primitive's; `wrappers`:
  // calls that return their operand, computed differently (`INVARIANT`); `translation_invariant`:
  // calls whose result a translation of their operand leaves be (`ddx`).
  TranslatedChain(std::vector<std::string> primitive_objects, std::vector<std::string> wrappers,
                  std::vector<std::string> translation_invariant)
      : primitive_objects_(std::move(primitive_objects)),
        wrappers_(std::move(wrappers)),
        translation_invariant_(std::move(translation_invariant)) {}

  // A local (with a value, or written by a helper's `out` parameter) moved to translated world.
  RewritePlan plan_translated(const CheckContext& ctx, int var, const DeclaredNames& names) const;

  // A parameter becomes translated under a translated name: its uses follow, and each call of its
  // function in this file (a whole program: nothing else calls it) passes the translated value.
  // Returns why not, or "".
  std::string move_parameter(const CheckContext& ctx, const DeclaredNames& names, int var, RewritePlan& plan, int depth) const;

  // A local holding an engine transform demoted to float (`float4x4 LocalToWorld =
  // DFHackToFloat(Primitive.LocalToWorld)`) becomes the translated transform, made from the
  // large-world one in the era's library (`DFFastToTranslatedWorld`, `LWCMultiplyTranslation`),
  // under a translated name; its uses follow: a point it transforms becomes translated (a
  // world-to-local transform takes a translated point), its rotation rows and 3x3 part stay, its
  // translation row is the translated origin. Returns why not, or "".
  std::string move_matrix(const CheckContext& ctx, const DeclaredNames& names, int var, RewritePlan& plan, int depth) const;
  // A transform parameter of a function of this file (a whole program) moves the same way under a
  // translated name: its uses follow, and each call passes a translated transform (a local or
  // parameter that moves with it, or the engine's transform made translated there). Returns why
  // not, or "".
  std::string move_matrix_parameter(const CheckContext& ctx, const DeclaredNames& names, int var, RewritePlan& plan, int depth) const;

  // Renames a function of this file to `new_name`, its returned values made translated, and
  // follows every call. Returns why not, or "".
  std::string translate_function(const CheckContext& ctx, int fn, const std::string& new_name, const DeclaredNames& names,
                                 RewritePlan& plan, int depth) const;

 private:
  // A primitive's local-to-world transform (this frame's or the previous one's), or "".
  std::string primitive_to_world(const SyntaxTree& t, int node) const;

  // One use of a transform that moves to translated world under `new_name` (move_matrix).
  void follow_matrix_use(const CheckContext& ctx, const DeclaredNames& names, int use, Kind kind, const std::string& new_name,
                         RewritePlan& plan, int depth) const;

  // A local becomes translated under a translated name: its value (when `with_value`; else the
  // value is a use already being moved), its declaration and every use. Returns why not, or "".
  std::string move_local(const CheckContext& ctx, const DeclaredNames& names, int var, bool with_value, RewritePlan& plan, int depth) const;

  // A uniform of this file that the host sets (a pass parameter, `float4 LightPositionAndInvRadius;`)
  // holding an absolute position, or a transform from world: its translated form is a new uniform
  // declared beside it, which the host must set (the plan's note says to what), as Epic's own passes
  // did; the uniform's other uses keep the absolute one. The text for `node`, or "" where none.
  // `by_use`: the chain knows from where the node stands that a uniform of no known kind is a world
  // point (the other side of a difference with one) or, a matrix, takes world points (it
  // transforms one: `LocalLightFunctionMatrix`).
  std::string host_twin(const CheckContext& ctx, const DeclaredNames& names, int node, RewritePlan& plan, bool by_use = false) const;

  // An absolute value's translated form, as edits: a transform whose matrix has a translated
  // twin or is a primitive's, or a translated value minus the pre-view translation (which goes).
  // Returns why not, or "".
  std::string translate_value(const CheckContext& ctx, const DeclaredNames& names, int value, RewritePlan& plan, int depth) const;

  // Why a function of this file cannot take `new_name` with its callers following, or "".
  static std::string movable(const SyntaxTree& t, const DeclaredNames& names, int fn, const std::string& new_name);

  // A use that needs the absolute point (an engine function that takes one, a height, a value
  // returned as absolute) reads it back from the translated one, rounded once
  // (`DFSubtractDemote(TranslatedP, PrimaryView.PreViewTranslation)`): the same float the code
  // read before, while the rest of the chain keeps its precision. False where the use stores into
  // the point, or the target has no large-world library (UE4).
  static bool bridge(const CheckContext& ctx, int use, const std::string& text, RewritePlan& plan);

  // The function `fn` is renamed `new_name`, and every call of it follows as a translated value.
  void rename_with_callers(const CheckContext& ctx, const DeclaredNames& names, int fn, const std::string& new_name, RewritePlan& plan, int depth) const;

  // Where some callers need the absolute value, the function splits as Epic's own port splits
  // them (VolumetricFog's ComputeCellWorldPosition): a translated copy under `new_name` (its body
  // with the return values moved, edits from `body_edits` on), and the original returning the
  // copy's value minus the pre-view translation, demoted with the era's marker. Every caller that
  // can follow calls the copy; the others keep the absolute function, which computes the same
  // float32 value as before. Unreal code only (the marker), float3 returns.
  bool split_function(const CheckContext& ctx, int fn, const std::string& new_name, const DeclaredNames& names, size_t body_edits,
                      RewritePlan& plan, int depth) const;

  // A call of a function of this file as the other point of a difference: it calls the
  // function's translated form, moving the function if this plan does not yet (in a trial).
  bool follow_partner_call(const CheckContext& ctx, const DeclaredNames& names, int partner, RewritePlan& plan, int depth) const;

  // Every use must stay meaningful in translated world: a difference with a camera term (whose
  // twin replaces it), a sum with the pre-view translation (the translated value itself), a
  // transform by a from-world matrix with a twin, the value of a local or the return of a function
  // of this file that follow in turn, or the argument of a helper in this file whose parameter can
  // follow (it is renamed and becomes translated).
  // A statement that moves the variable to translated world itself (`V += PreViewTranslation`, run
  // whenever the code reaches it) goes: the value is translated from the start, and every use after
  // it already took it so, and is only renamed.
  // The value a local declared without one is given by its first use, a plain assignment in the
  // same block with no other store after it; or -1.
  static int assigned_once(const CheckContext& ctx, int var, const std::vector<int>& uses);
  // (`assigned`: a use that is the one store of the variable's value, renamed and not followed.)
  void follow_translated(const CheckContext& ctx, const DeclaredNames& names, int var, const std::string& new_name, RewritePlan& plan, int depth,
                         int assigned = -1) const;

  // One use of a value that becomes translated (a variable, or a call of a function that now
  // returns translated), written `text` there: the variable's new name, or the renamed call.
  void follow_use(const CheckContext& ctx, const DeclaredNames& names, int use, const std::string& text, RewritePlan& plan, int depth) const;

  // A local whose value is the use (`float3 P = use;`): it becomes translated under a translated
  // name, and its own uses follow.
  bool follow_into_local(const CheckContext& ctx, const DeclaredNames& names, int expr, RewritePlan& plan, int depth) const;

  // The other point of a difference, when it is a local of this function holding an absolute
  // position of its own: both move to translated world together (the difference is the same).
  bool follow_partner(const CheckContext& ctx, const DeclaredNames& names, int partner, RewritePlan& plan, int depth) const;

  // The function a returned use leaves through: its value is already translated (the use is), so
  // only the name and the callers change.
  std::string translate_function_of_use(const CheckContext& ctx, int fn, const std::string& new_name, const DeclaredNames& names,
                                        RewritePlan& plan, int depth) const;

  // A use passed whole to a function (of this file or an included one) that uses its point
  // parameters only in differences with one another (WorldModel::difference_group): the other
  // points it is passed move to translated world too, and the function stays as it is.
  bool follow_into_difference_group(const CheckContext& ctx, const DeclaredNames& names, int use, RewritePlan& plan, int depth) const;

  // A use passed whole to a function defined in this file, called only with values being made
  // translated: its parameter follows. The parameter's own finding is then fixed by this one.
  bool follow_into_helper(const CheckContext& ctx, const DeclaredNames& names, int use, RewritePlan& plan, int depth) const;

  // A local declared without a value and written by one call of a helper of this file through an
  // `out` parameter, before any read: the parameter moves with it (renamed, every value assigned to
  // it made translated) and the local follows. Returns why not, or "".
  std::string move_out_local(const CheckContext& ctx, const DeclaredNames& names, int var, RewritePlan& plan, int depth) const;

  std::vector<std::string> primitive_objects_, wrappers_, translation_invariant_;
};

}  // namespace lwc::checks
