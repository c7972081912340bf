// lwc-hack-marker: the searchable markers of shortcuts taken while porting to LWC. Where the
// demoted value is only used camera-relative (a difference with the camera, or a sum with the
// pre-view translation), the translated twins compute the same thing at full precision.
#include <fmt/format.h>

#include <set>

#include "rules/checks/library_rewrite.h"
#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class HackMarker : public Check {
 public:
  explicit HackMarker(const RuleInfo& rule)
      : markers_(rule.data.at("markers")), demotions_(string_list(rule.data, "demotions")), conversions_(rule.data.at("conversions")) {
    for (const auto& [name, loss] : markers_.items()) marker_names_.insert(name);
  }

  void run(const CheckContext& ctx) const override {
    const SyntaxTree& t = ctx.tree;
    for (int id : nodes_of(t, "identifier")) {
      if (!marker_names_.contains(t.text(id)) || is_definition_name(t, id)) continue;
      std::string name(t.text(id));
      Finding& f = ctx.report(t.span(id), {{"marker", name}, {"loss", markers_.at(name).get<std::string>()}});
      if (matches_any(demotions_, name)) offer_fix(ctx, f, id);
      if (conversions_.contains(name)) offer_drop(ctx, f, id, conversions_.at(name).get<std::string>());
    }
  }

 private:
  // The argument of a one-argument demotion call, when `node` is such a call; else -1.
  int demoted(const SyntaxTree& t, int node) const {
    if (!t.is(node, "call_expression") || !matches_any(demotions_, call_name(t, node))) return -1;
    auto args = call_arguments(t, node);
    return args.size() == 1 ? args[0] : -1;
  }

  // A camera term of a difference, demoted or not: its translated twin, or "".
  std::string camera_twin(const CheckContext& ctx, int node, Kind want) const {
    int inner = demoted(ctx.tree, node);
    int value = inner >= 0 ? inner : node;
    return ctx.world.kind(value) == want ? translated_twin(ctx, value) : "";
  }

  void offer_fix(const CheckContext& ctx, Finding& f, int marker) const {
    const SyntaxTree& t = ctx.tree;
    int call = t.at(marker).parent;
    int value = demoted(t, call);
    if (value < 0) return;
    int use = call, parent = t.at(call).parent;
    while (t.is(parent, "parenthesized_expression")) use = parent, parent = t.at(use).parent;
    std::string twin = translated_twin(ctx, value);
    std::string op = t.is(parent, "binary_expression") ? std::string(t.text(t.child_by_field(parent, "operator"))) : "";
    if (twin.empty()) {
      if (offer_library(ctx, f, marker, call, value)) return;
      if (ctx.world.kind(value) == Kind::camera_offset)
        f.withheld.push_back(fmt::format("translated world: `{}` is the translation into translated world itself, so it has no twin: the "
                                         "code it is handed to must add it in the large-world library, or be ported to translated world",
                                         t.text(value)));
      else
        f.withheld.push_back(fmt::format("translated world: `{}` has no translated twin lwcport knows, so the demotion stays until the code "
                                         "around it is ported (to translated world or DoubleFloat)",
                                         t.text(value)));
      return;
    }
    if (op != "-" && op != "+") {
      if (!offer_library(ctx, f, marker, call, value))
        f.withheld.push_back(fmt::format("translated world: the demoted value is used as `{}` (line {}), not as a difference with the "
                                         "camera, so its translated twin would change the result",
                                         t.text(parent), line_of(t, parent)));
      return;
    }
    bool first = t.child_by_field(parent, "left") == use;
    int other = t.child_by_field(parent, first ? "right" : "left");
    // X - camera and camera - X: both sides move by the same pre-view translation.
    if (std::string camera = op == "-" ? camera_twin(ctx, other, Kind::absolute) : ""; !camera.empty()) {
      std::string text = first ? twin + " - " + camera : camera + " - " + twin;
      ctx.fix(f, "translated", {{"marker", std::string(t.text(marker))}, {"text", text}}, {{t.span(parent), text}});
      return;
    }
    // X + PreViewTranslation is the translated position itself.
    if (op == "+" && is_pre_view(ctx, other)) {
      ctx.fix(f, "translated", {{"marker", std::string(t.text(marker))}, {"text", twin}}, {{t.span(parent), twin}});
      return;
    }
    if (!offer_library(ctx, f, marker, call, value))
      f.withheld.push_back(fmt::format("translated world: `{}` is combined with `{}` (line {}), which is not the camera, so its "
                                       "translated twin would change the result",
                                       t.text(value), t.text(other), line_of(t, parent)));
  }

  // No translated twin fits: the demoted value's float arithmetic is done in the library of the
  // marker's own era instead (DFHackToFloat: DoubleFloat; LWCHackToFloat: tile/offset), rounded
  // once. The value stays absolute; only the demotion and its rounding go.
  bool offer_library(const CheckContext& ctx, Finding& f, int marker, int call, int value) const {
    const SyntaxTree& t = ctx.tree;
    std::string_view name = t.text(marker);
    if (name != "DFHackToFloat" && name != "LWCHackToFloat") return false;
    // Beside another float32 absolute value the two roundings often cancel; one exact operand
    // only moves the error, so the pair must move to translated world together.
    Kind kind = large_world_kind(ctx, value);
    if (int other = absolute_partner(ctx, call, kind); other >= 0) {
      f.withheld.push_back(fmt::format("DoubleFloat: `{}` is itself a float32 absolute position (line {}): taking `{}` exactly beside it "
                                       "gains nothing, so both must move to translated world together (where `{}` is produced, it must become translated or large-world first)",
                                       shortened(t.text(other)), line_of(t, other), t.text(value), shortened(t.text(other))));
      return true;
    }
    Member m = member_of(t, value);
    LargeWorldValue v{call, std::string(t.text(value)), kind, m.object, m.member};
    LibraryRewrite r = library_rewrite(ctx, v, name == "DFHackToFloat");
    if (r.fix.empty() && !r.blocker.empty()) f.withheld.push_back(r.blocker);
    if (r.fix.empty()) return !r.blocker.empty();
    r.vars["marker"] = name;
    ctx.fix(f, r.fix, r.vars, r.edits);
    return true;
  }

  // What a demoted value is: its kind, else what its declared large-world type says.
  static Kind large_world_kind(const CheckContext& ctx, int value) {
    Kind kind = ctx.world.kind(value);
    if (kind != Kind::unknown && kind != Kind::local) return kind;
    int var = ctx.tree.is(value, "identifier") ? ctx.world.variable_at(value) : -1;
    std::string type = var >= 0 ? ctx.world.variables()[static_cast<size_t>(var)].type : "";
    if (type == "FDFVector3" || type == "FLWCVector3") return Kind::absolute;
    if (type == "FDFMatrix" || type == "FLWCMatrix") return Kind::world_matrix;
    if (type == "FDFInverseMatrix" || type == "FLWCInverseMatrix") return Kind::from_world_matrix;
    return kind;
  }

  // A tile/offset <-> DoubleFloat conversion whose argument already has the target type (a
  // function whose return the fix moved to DoubleFloat, a variable declared so): the call goes.
  void offer_drop(const CheckContext& ctx, Finding& f, int marker, const std::string& target) const {
    const SyntaxTree& t = ctx.tree;
    int call = t.at(marker).parent;
    if (!t.is(call, "call_expression")) return;
    std::vector<int> args = call_arguments(t, call);
    if (args.size() != 1) return;
    std::string type;
    if (t.is(args[0], "identifier")) {
      if (int v = ctx.world.variable_at(args[0]); v >= 0) type = ctx.world.variables()[static_cast<size_t>(v)].type;
    } else if (t.is(args[0], "call_expression")) {
      type = ctx.world.function_return_type(std::string(call_name(t, args[0])));
    }
    if (!type.starts_with(target)) return;
    std::string text(t.text(args[0]));
    ctx.fix(f, "drop", {{"marker", std::string(t.text(marker))}, {"text", text}, {"type", type}}, {{t.span(call), text}});
  }

  // The pre-view translation, demoted or not (it has no twin of its own: it is the translation).
  bool is_pre_view(const CheckContext& ctx, int node) const {
    int inner = demoted(ctx.tree, node);
    return ctx.world.kind(inner >= 0 ? inner : node) == Kind::camera_offset;
  }

  nlohmann::json markers_;               // marker -> what it loses
  std::set<std::string, std::less<>> marker_names_;  // its keys: every identifier of a file is looked up
  std::vector<std::string> demotions_;  // markers that demote one value to float
  nlohmann::json conversions_;          // conversion marker -> the type prefix it converts to
};

}  // namespace

std::unique_ptr<Check> make_hack_marker(const RuleInfo& rule) { return std::make_unique<HackMarker>(rule); }

}  // namespace lwc::checks
