#include <gtest/gtest.h>

#include <random>

#include "lang/syntax.h"
#include "support.h"

namespace lwc {
namespace {

// Every field of every node, and the tree's error summary, as a fresh parse gives them.
void expect_same_tree(const SyntaxTree& reused, const SyntaxTree& fresh, const std::string& where) {
  ASSERT_EQ(reused.nodes.size(), fresh.nodes.size()) << where;
  EXPECT_EQ(reused.error_count, fresh.error_count) << where;
  EXPECT_EQ(reused.first_error, fresh.first_error) << where;
  EXPECT_EQ(reused.variants, fresh.variants) << where;
  for (size_t i = 0; i < fresh.nodes.size(); ++i) {
    const Node& a = reused.nodes[i];
    const Node& b = fresh.nodes[i];
    bool same = std::string_view(a.type) == b.type && (a.field == nullptr) == (b.field == nullptr) &&
                (!a.field || std::string_view(a.field) == b.field) && a.begin == b.begin && a.end == b.end &&
                a.parent == b.parent && a.first_child == b.first_child && a.next_sibling == b.next_sibling &&
                a.depth == b.depth && a.named == b.named && a.error == b.error;
    ASSERT_TRUE(same) << where << ": node " << i << " (" << b.type << " at " << b.begin << ") differs: reused " << a.type << " "
                      << a.begin << "-" << a.end << " parent " << a.parent << " child " << a.first_child << " sibling "
                      << a.next_sibling;
  }
}

// Edits an editor makes: characters typed and deleted, lines split and joined, braces and
// preprocessor lines that change the structure around them, whole declarations removed.
std::string random_edit(const std::string& text, std::mt19937& rng) {
  static const std::vector<std::string> pieces = {" ", "x", "\n", ";", "{", "}", "(", "float3 P = Q;\n", "#if A\n", "#endif\n", "/*", "*/", "// c\n", "é"};
  return test::random_edit(text, rng, pieces);
}

// The document's last trees edited and reparsed (and top-level declarations copied from the last
// flattening) give exactly the nodes a fresh parse gives, variant by variant, edit after edit.
TEST(ParseReuse, GivesTheTreeAFreshParseGives) {
  std::mt19937 rng(20261124);
  std::vector<std::pair<std::string, std::string>> inputs;
  for (const char* file : {"corpus/ue4/DeferredLightPixelShaders.usf", "corpus/ue4/LocalVertexFactory.ush", "corpus/d3d/Terrain.hlsl",
                           "corpus/glsl/forward.vert", "corpus/glsl/lighting.glsl", "corpus/negative/Suppressions.usf"})
    inputs.emplace_back(file, test::read(test::source_dir() + "/" + file));
  for (const auto& [file, original] : inputs) {
    std::string text = original;
    Lang lang = lang_from_path(file).value();
    ParseReuse reuse;
    for (int edit = 0; edit < 150; ++edit) {
      text = edit % 50 == 49 ? original : random_edit(text, rng);
      Source source(file, text);
      int variants = 1;
      for (int variant = 0; variant < variants; ++variant) {
        SyntaxTree reused = parse(source, lang, {nullptr, variant, 10.0, &reuse});
        SyntaxTree fresh = parse(source, lang, {nullptr, variant, 10.0, nullptr});
        variants = fresh.variants;
        expect_same_tree(reused, fresh, file + " edit " + std::to_string(edit) + " variant " + std::to_string(variant));
        if (HasFatalFailure()) return;
      }
    }
  }
}

// What deepest_covering means, as the plain descent from the root reads it.
int covering_by_descent(const SyntaxTree& t, uint32_t begin, uint32_t end) {
  int node = 0;
  for (bool deeper = true; deeper;) {
    deeper = false;
    for (int c = t.at(node).first_child; c >= 0; c = t.at(c).next_sibling) {
      if (t.at(c).begin <= begin && end <= t.at(c).end && t.at(c).end > t.at(c).begin) {
        node = c;
        deeper = true;
        break;
      }
    }
  }
  return node;
}

// On every node's span, on spans across nodes and on empty spans, of corpus files and of broken
// edits of them (error nodes, missing tokens).
TEST(SyntaxTree, DeepestCoveringIsTheDescentFromTheRoot) {
  std::mt19937 rng(20261124);
  int spans = 0;
  for (const char* file : {"corpus/ue4/DeferredLightPixelShaders.usf", "corpus/ue5.4/EngineSpaces.usf", "corpus/glsl/lighting.glsl",
                           "corpus/d3d/Terrain.hlsl"}) {
    std::string text = test::read(test::source_dir() + "/" + file);
    for (int edit = 0; edit < 30; ++edit, text = random_edit(text, rng)) {
      Source source(file, text);
      SyntaxTree t = parse(source, lang_from_path(file).value(), {nullptr, 0, 10.0, nullptr});
      std::vector<Span> wanted;
      for (size_t n = 0; n < t.nodes.size(); ++n) wanted.push_back(t.span(static_cast<int>(n)));
      for (int k = 0; k < 200; ++k) {
        uint32_t a = std::uniform_int_distribution<uint32_t>(0, static_cast<uint32_t>(text.size()))(rng);
        uint32_t b = std::uniform_int_distribution<uint32_t>(0, static_cast<uint32_t>(text.size()))(rng);
        wanted.push_back({std::min(a, b), std::max(a, b)});
        wanted.push_back({a, a});
      }
      for (Span s : wanted) {
        ASSERT_EQ(t.deepest_covering(s.begin, s.end), covering_by_descent(t, s.begin, s.end)) << file << " edit " << edit << " span " << s.begin << "-" << s.end;
        ++spans;
      }
    }
  }
  EXPECT_GT(spans, 50000);
}

}  // namespace
}  // namespace lwc
