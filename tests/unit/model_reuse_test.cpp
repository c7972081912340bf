#include <gtest/gtest.h>

#include <random>
#include <set>

#include <nlohmann/json.hpp>

#include "rules/analyze.h"
#include "support.h"

namespace lwc {
namespace {

// Everything a model tells its readers, for one tree: the kind and variable of every node, the
// variables, the holders in order, what nests too deeply, and the summary for includers.
void expect_same_model(const WorldModel& replayed, const WorldModel& fresh, const std::string& where) {
  const SyntaxTree& tree = fresh.tree();
  for (int id = 0; id < static_cast<int>(tree.nodes.size()); ++id) {
    ASSERT_EQ(replayed.kind(id), fresh.kind(id)) << where << ": node " << id << " `" << tree.text(id).substr(0, 40) << "`";
    ASSERT_EQ(replayed.variable_at(id), fresh.variable_at(id)) << where << ": node " << id;
  }
  ASSERT_TRUE(replayed.variables() == fresh.variables()) << where;
  ASSERT_EQ(replayed.absolute_holders().size(), fresh.absolute_holders().size()) << where;
  for (size_t i = 0; i < fresh.absolute_holders().size(); ++i) {
    const AbsoluteHolder &a = replayed.absolute_holders()[i], &b = fresh.absolute_holders()[i];
    ASSERT_TRUE(a.site == b.site && a.name == b.name && a.type == b.type && a.kind == b.kind && a.what == b.what) << where << ": holder " << i;
  }
  ASSERT_EQ(replayed.too_deep(), fresh.too_deep()) << where;
  FileSummary x = replayed.summary(), y = fresh.summary();
  ASSERT_TRUE(x.globals == y.globals && x.function_returns == y.function_returns && x.function_return_types == y.function_return_types &&
              x.field_types == y.field_types && x.parameter_kinds == y.parameter_kinds)
      << where;
}

// Typing inside function bodies, at the start of a line: blanks, a comment, a local holding a
// world position, and what changes what a function gives the others: a store of a world value into
// a global or a struct field, a return of one. With `breaking`, also what breaks the syntax or the
// structure (a letter, a brace) until it is taken back.
std::string edit_inside_a_function(const std::string& text, Lang lang, std::mt19937& rng, bool breaking) {
  Source source("t." + std::string(lang == Lang::hlsl ? "hlsl" : "glsl"), text);
  SyntaxTree tree = parse(source, lang);
  WorldModel model(tree, world_data(lang, nlohmann::json::array()));
  std::vector<std::string> globals, fields, world = {lang == Lang::hlsl ? "View.WorldCameraOrigin" : "cameraPosition"};
  for (const Variable& v : model.variables()) {
    if (v.role == Variable::Role::global && !v.uniform) globals.push_back(v.name);
    if (v.role == Variable::Role::field) fields.push_back(v.name);
    if (v.role == Variable::Role::global && holds_absolute(v.kind)) world.push_back(v.name);
  }
  std::string value = world[rng() % world.size()];
  std::vector<std::string> pieces = {" ", "\n", "\t", "// note\n", "float3 WorldPos = " + value + ";\n", "return " + value + ";\n"};
  if (!globals.empty()) pieces.push_back(globals[rng() % globals.size()] + " = " + value + ";\n");
  if (!fields.empty()) pieces.push_back("Data." + fields[rng() % fields.size()] + " = " + value + ";\n");
  if (breaking)
    for (const char* p : {"x", "return Q;\n", "}", "{", "P = mul(float4(P, 1), M);\n"}) pieces.push_back(p);
  std::vector<size_t> bodies;  // just after a line break inside a function's body
  for (int id = 0; id < static_cast<int>(tree.nodes.size()); ++id) {
    if (!tree.is(id, "function_definition")) continue;
    int body = tree.child_by_field(id, "body");
    if (body < 0) continue;
    for (uint32_t i = tree.at(body).begin; i + 1 < tree.at(body).end; ++i)
      if (text[i] == '\n') bodies.push_back(i + 1);
  }
  size_t at = bodies.empty() ? text.size() / 2 : bodies[rng() % bodies.size()];
  size_t cut = breaking && rng() % 3 == 0 ? std::min<size_t>(rng() % 20, text.size() - at) : 0;
  return text.substr(0, at) + pieces[rng() % pieces.size()] + text.substr(at + cut);
}

// A model that replays the document's last one where an edit left a function's inputs alone is
// the model a fresh analysis gives, edit after edit, in every variant; and while the edits keep
// the syntax, most functions the edit did not touch are replayed, not analysed again.
TEST(ModelReuse, GivesTheModelAFreshAnalysisGives) {
  std::mt19937 rng(20261124);
  int replayed = 0, unchanged = 0;  // functions replayed; functions in declarations the parse copied
  for (const char* file : {"corpus/ue4/DeferredLightPixelShaders.usf", "corpus/ue4/LocalVertexFactory.ush", "corpus/d3d/Terrain.hlsl",
                           "corpus/glsl/forward.vert", "corpus/glsl/lighting.glsl", "corpus/ue5.4/DoubleFloatHelpers.ush",
                           "corpus/negative/UnrealOtherSpaces.usf"}) {
    std::string text = test::read(test::source_dir() + "/" + file);
    Lang lang = lang_from_path(file).value();
    const WorldData& data = world_data(lang, nlohmann::json::array());
    ParseReuse parses;
    ModelReuse models;
    for (int edit = 0; edit < 60; ++edit) {
      bool breaking = edit >= 40;
      text = edit_inside_a_function(text, lang, rng, breaking);
      Source source(file, text);
      for (int variant = 0, variants = 1; variant < variants; ++variant) {
        SyntaxTree edited = parse(source, lang, {nullptr, variant, 10.0, &parses});
        SyntaxTree fresh = parse(source, lang, {nullptr, variant, 10.0, nullptr});
        variants = fresh.variants;
        ModelContext context = model_context(source, lang, nullptr);
        WorldModel reference(fresh, data, context);
        context.reuse = &models;
        context.variant = variant;
        WorldModel model(edited, data, context);
        expect_same_model(model, reference, std::string(file) + " edit " + std::to_string(edit) + " variant " + std::to_string(variant));
        if (HasFatalFailure()) return;
        if (!breaking && edit > 0) {
          replayed += model.replayed_functions();
          for (const SyntaxTree::Reused& r : edited.reused)
            for (int id = r.here; id < r.here + r.count; ++id) unchanged += edited.is(id, "function_definition");
        }
      }
    }
  }
  // What is not replayed reads what the edit changed (calls the edited function, reads a global
  // it writes), or the edit changed the declarations outside functions.
  EXPECT_GT(replayed, 0.8 * unchanged) << replayed << " replayed of " << unchanged << " unchanged functions";
}

// Unreal-style texts in turn as one document's versions: each model, with the document's last
// one to replay, equals a fresh model; per version, the functions analysed again by name, and
// "(replayed)" once for each function replayed.
std::vector<std::multiset<std::string>> analysed_per_version(const std::vector<std::string>& versions) {
  const WorldData& data = world_data(Lang::hlsl, nlohmann::json::array());
  ParseReuse parses;
  ModelReuse models;
  std::vector<std::multiset<std::string>> out;
  for (size_t i = 0; i < versions.size(); ++i) {
    Source source("t.usf", versions[i]);
    SyntaxTree edited = parse(source, Lang::hlsl, {nullptr, 0, 10.0, &parses});
    SyntaxTree fresh = parse(source, Lang::hlsl);
    ModelContext context = model_context(source, Lang::hlsl, nullptr);
    WorldModel reference(fresh, data, context);
    context.reuse = &models;
    WorldModel model(edited, data, context);
    expect_same_model(model, reference, "version " + std::to_string(i));
    std::multiset<std::string> analysed;
    for (int fn : model.analysed_functions()) analysed.insert(std::string(edited.text(edited.declarator_name(edited.child_by_field(fn, "declarator")))));
    for (int k = 0; k < model.replayed_functions(); ++k) analysed.insert("(replayed)");
    out.push_back(std::move(analysed));
  }
  return out;
}

// Only what an edit can change is analysed again: the edited function, and the functions that
// read what it changed (a global it stores into, the return of a callee); the rest is replayed.
TEST(ModelReuse, AnalysesAgainWhatReadsWhatTheEditChanged) {
  auto text = [](const std::string& store, const std::string& ret, const std::string& note) {
    return "static float3 G;\n"
           "void Writer() {\n  G = " + store + ";\n}\n"
           "float3 Callee(float3 P) {\n  return " + ret + ";\n}\n"
           "void Reader() {\n  // " + note + "\n  float3 Copy = G;\n}\n"
           "void Caller() {\n  float3 R = Callee(float3(1, 2, 3));\n}\n"
           "void Bystander() {\n  float3 B = float3(0, 0, 1);\n}\n";
  };
  struct Step {
    std::string text;
    std::set<std::string> analysed;  // the functions analysed again
  };
  std::vector<Step> steps = {
      {text("float3(0, 0, 0)", "P", "a"), {"Callee", "Writer", "Reader", "Caller", "Bystander"}},
      {text("float3(0, 0, 0)", "P", "b"), {"Reader"}},
      {text("View.WorldCameraOrigin", "P", "b"), {"Writer", "Reader"}},
      {text("View.WorldCameraOrigin", "View.WorldCameraOrigin", "b"), {"Callee", "Caller"}},
      {text("View.WorldCameraOrigin", "View.WorldCameraOrigin", "c"), {"Reader"}},
      {text("float3(0, 0, 0)", "P", "c"), {"Callee", "Writer", "Reader", "Caller"}},
      // A callee that reads the global: unchanged, but what it returns changed, and so did its
      // caller's call.
      {text("float3(0, 0, 0)", "G", "c"), {"Callee", "Caller"}},
      {text("View.WorldCameraOrigin", "G", "c"), {"Writer", "Reader", "Callee", "Caller"}},
  };
  std::vector<std::string> versions;
  for (const Step& step : steps) versions.push_back(step.text);
  std::vector<std::multiset<std::string>> analysed = analysed_per_version(versions);
  for (size_t i = 0; i < steps.size(); ++i) {
    std::multiset<std::string> expected(steps[i].analysed.begin(), steps[i].analysed.end());
    while (expected.size() < 5) expected.insert("(replayed)");  // the other functions of the five
    EXPECT_EQ(analysed[i], expected) << "version " << i;
  }
}

// Which function a call reaches is part of what a caller read: an overload that takes the call
// after an edit (the last of the arity), and a function that takes the name of one the call could
// not find, analyse the caller again.
TEST(ModelReuse, ACallThatReachesAnotherFunctionAnalysesTheCallerAgain) {
  auto text = [](const std::string& second_pick, const std::string& other) {
    return "float3 Pick(float3 P) {\n  return P;\n}\n" + second_pick +
           "void UsesPick() {\n  float3 R = Pick(float3(1, 2, 3));\n}\n"
           "void UsesHelper() {\n  float3 H = Helper(float3(1, 2, 3));\n}\n" + other;
  };
  std::string two = "float3 Pick(float3 P, float3 Q) {\n  return Q;\n}\n", one = "float3 Pick(float3 Q) {\n  return View.WorldCameraOrigin;\n}\n";
  std::string other = "float3 Other(float3 P) {\n  return P;\n}\n", helper = "float3 Helper(float3 P) {\n  return View.WorldCameraOrigin;\n}\n";
  std::vector<std::pair<std::string, std::multiset<std::string>>> steps = {
      {text(two, other), {"Pick", "Pick", "UsesPick", "UsesHelper", "Other"}},
      {text(one, other), {"Pick", "UsesPick"}},
      {text(one, helper), {"Pick", "Pick", "UsesPick", "UsesHelper", "Helper"}},
  };
  std::vector<std::string> versions;
  for (const auto& step : steps) versions.push_back(step.first);
  std::vector<std::multiset<std::string>> analysed = analysed_per_version(versions);
  for (size_t i = 0; i < steps.size(); ++i) {
    std::multiset<std::string> expected = steps[i].second;
    while (expected.size() < 5) expected.insert("(replayed)");
    EXPECT_EQ(analysed[i], expected) << "version " << i;
  }
}

}  // namespace
}  // namespace lwc
