// lwc-tile-offset: UE 5.0-5.3 tile/offset types and operations, superseded by DoubleFloat.
#include <fmt/format.h>

#include <map>
#include <unordered_map>

#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class TileOffset : public Check {
  struct Site {  // one tile/offset type, operation or engine member read in the file
    int id;
    std::string what;  // "type", "operation", "value"
    std::string name;
    std::string replacement;
  };

 public:
  explicit TileOffset(const RuleInfo& rule)
      : types_(string_list(rule.data, "types")),
        functions_(string_list(rule.data, "functions")),
        excluded_(string_list(rule.data, "excluded")),
        mapping_(rule.data.value("mapping", nlohmann::json::object())),
        construct_(rule.data.value("constructors", nlohmann::json::object())),
        parts_(string_list(rule.data, "parts")),
        kept_(string_list(rule.data, "kept-tile-offset")) {
    for (const auto& [from, to] : mapping_.items()) renames_.emplace(from, to.get<std::string>());
  }

  void run(const CheckContext& ctx) const override {
    // A project set to build against UE 5.0-5.3 has no DoubleFloat to move to: there tile/offset is
    // the engine's own large-world API, and every use of it would be a finding the user cannot act on.
    if (ctx.unreal && !ctx.unreal->inferred && ctx.unreal->era == UnrealEra::ue5_0) return;
    const SyntaxTree& t = ctx.tree;
    std::vector<Site> sites;
    // Types, names and member reads, in source order (the first site without a counterpart is the
    // one a blocker names).
    for (int id : nodes_of(t, {"type_identifier", "identifier", "field_expression"})) {
      bool type = t.is(id, "type_identifier");
      bool call = t.is(id, "identifier") && t.is(t.at(id).parent, "call_expression") &&
                  t.child_by_field(t.at(id).parent, "function") == id;
      if (t.is(id, "field_expression")) {
        // The engine's tile/offset copy of a view member (`ResolvedView.TileOffset.PreViewTranslation`)
        // stays FLWC in UE 5.4; the member itself is its DoubleFloat twin.
        int field = t.child_by_field(id, "field"), parent = t.at(id).parent;
        if (field >= 0 && matches_any(kept_, t.text(field)) && t.is(parent, "field_expression") && t.child_by_field(parent, "argument") == id) {
          std::string base(t.text(t.child_by_field(id, "argument"))), member(t.text(t.child_by_field(parent, "field")));
          sites.push_back({parent, "value", std::string(t.text(parent)), base + "." + member});
        }
        continue;
      }
      if (!type && !call) continue;
      std::string name(t.text(id));
      if (matches_any(excluded_, name) || !matches_any(type ? types_ : functions_, name)) continue;
      sites.push_back({id, type ? "type" : "operation", name, mapping_.value(name, "")});
    }
    if (sites.empty()) return;
    // A rename is safe only when the whole file can move to DoubleFloat: every site has a
    // counterpart and no code reads the tile/offset parts, which FDF types do not have.
    std::string blocker = whole_file_blocker(t, sites);
    std::map<int, std::string> duplicates = renamed_into_existing_overloads(t);
    if (blocker.empty() && !duplicates.empty()) blocker = duplicates.begin()->second;
    for (const Site& s : sites) {
      int fn = t.ancestor(s.id, "function_definition");
      int body = fn >= 0 ? t.child_by_field(fn, "body") : -1;
      bool in_signature = fn >= 0 && (body < 0 || t.at(s.id).begin < t.at(body).begin);
      if (in_signature && duplicates.count(fn)) {
        Finding& f = ctx.report(t.span(s.id), {{"name", s.name}, {"what", s.what},
                                               {"replacement", "its FDF*/DF* counterpart"}, {"to", ""}, {"blocker", blocker}});
        f.withheld.push_back(duplicates.at(fn));
        continue;
      }
      const std::string& replacement = s.replacement;
      Vars vars{{"name", s.name},
                {"what", s.what},
                {"replacement", replacement.empty() ? "its FDF*/DF* counterpart" : "`" + replacement + "`"},
                {"to", replacement},
                {"blocker", blocker}};
      Finding& f = ctx.report(t.span(s.id), vars);
      if (replacement.empty()) continue;
      if (construct_.contains(s.name)) {
        // MakeLWC*(Tile, Offset) is Tile * TileSize + Offset: TwoSum makes that pair exactly.
        int call = t.at(s.id).parent;
        auto args = call_arguments(t, call);
        if (args.size() != 2) continue;
        std::string tile_size = construct_.at(s.name).get<std::string>();
        vars["tile-size"] = tile_size;
        vars["to"] = "DFTwoSum";
        bool simple = t.is(args[0], "identifier") || t.is(args[0], "field_expression") || t.is(args[0], "call_expression");
        std::string tile = simple ? std::string(t.text(args[0])) : "(" + std::string(t.text(args[0])) + ")";
        std::string text = fmt::format("DFTwoSum({} * {}, {})", tile, tile_size, t.text(args[1]));
        ctx.fix(f, "construct", vars, {{t.span(call), text}});
        continue;
      }
      ctx.fix(f, blocker.empty() ? "rename" : "rename-partial", vars, {rename_edit(t, s.id, replacement)});
    }
  }

 private:
  std::string whole_file_blocker(const SyntaxTree& t, const std::vector<Site>& sites) const {
    for (const Site& s : sites) {
      if (s.replacement.empty()) return fmt::format("`{}` has no DoubleFloat counterpart: port that code by hand, or the file will not compile after the rename", s.name);
      if (construct_.contains(s.name))
        return fmt::format("`{}` (line {}) builds a tile/offset value and its rewrite is unsafe; the renames compile only together with it", s.name,
                           t.source->position(t.at(s.id).begin).line);
    }
    for (int id : nodes_of(t, "field_expression")) {
      int field = t.child_by_field(id, "field");
      if (field >= 0 && matches_any(parts_, t.text(field)))
        return fmt::format("the code reads `.{}` (line {}), a part FDF types do not have: port it by hand, or the file will not compile after the rename", t.text(field),
                           t.source->position(t.at(field).begin).line);
    }
    return "";
  }

  // Functions whose signature, once its tile/offset types are renamed, is that of another
  // function of the file (an FLWCVector3 overload beside its FDFVector3 twin): the rename would
  // define it twice. Function node -> why.
  std::map<int, std::string> renamed_into_existing_overloads(const SyntaxTree& t) const {
    struct Signature {
      int fn;
      std::string written, renamed;
    };
    std::vector<Signature> all;
    bool any_renamed = false;
    for (int fn : nodes_of(t, "function_definition")) {
      int d = t.child_by_field(fn, "declarator");
      while (d >= 0 && !t.is(d, "function_declarator")) d = t.child_by_field(d, "declarator");
      int params = d >= 0 ? t.child_by_field(d, "parameters") : -1;
      int name = d >= 0 ? t.declarator_name(d) : -1;
      if (params < 0 || name < 0) continue;
      Signature sig{fn, std::string(t.text(name)) + "(", ""};
      sig.renamed = sig.written;
      for (int p = t.at(params).first_child; p >= 0; p = t.at(p).next_sibling) {
        if (!t.at(p).named) continue;
        int type = t.child_by_field(p, "type");
        std::string_view written = type >= 0 ? t.text(type) : std::string_view();
        auto renamed = renames_.find(written);
        any_renamed |= renamed != renames_.end();
        (sig.written += written) += ',';
        (sig.renamed += renamed != renames_.end() ? std::string_view(renamed->second) : written) += ',';
      }
      all.push_back(std::move(sig));
    }
    std::map<int, std::string> out;
    if (!any_renamed) return out;  // no signature names a tile/offset type
    std::unordered_map<std::string_view, int> last_written;  // a signature as written -> the last function with it
    for (const Signature& s : all) last_written[s.written] = s.fn;
    for (const Signature& a : all) {
      if (a.renamed == a.written) continue;  // no tile/offset type: the rename leaves it as it is
      auto b = last_written.find(a.renamed);
      if (b != last_written.end())
        out[a.fn] = fmt::format("renaming the types of `{}` (line {}) would define it a second time: the file already has that "
                                "DoubleFloat overload (line {}); remove the tile/offset one by hand",
                                a.written.substr(0, a.written.find('(')), line_of(t, a.fn), line_of(t, b->second));
    }
    return out;
  }

  // The rename of one site; a call converted to DoubleFloat at once (`DFFromTileOffset(LWCPromote(M))`)
  // loses the conversion, which would take the renamed DoubleFloat value as a tile/offset one.
  static Edit rename_edit(const SyntaxTree& t, int id, const std::string& replacement) {
    int call = t.at(id).parent;
    int list = t.is(call, "call_expression") ? t.at(call).parent : -1;
    int wrapper = t.is(list, "argument_list") ? t.at(list).parent : -1;
    std::string_view outer = wrapper >= 0 ? call_name(t, wrapper) : "";
    if ((outer == "DFFromTileOffset" || outer == "DFFromTileOffset_Hack") && call_arguments(t, wrapper).size() == 1)
      return {t.span(wrapper), replacement + std::string(t.text(t.child_by_field(call, "arguments")))};
    return {t.span(id), replacement};
  }

  std::vector<std::string> types_, functions_, excluded_;
  nlohmann::json mapping_, construct_;
  std::map<std::string, std::string, std::less<>> renames_;  // mapping_ as strings: looked up per parameter of every function
  std::vector<std::string> parts_, kept_;
};

}  // namespace

std::unique_ptr<Check> make_tile_offset(const RuleInfo& rule) { return std::make_unique<TileOffset>(rule); }

}  // namespace lwc::checks
