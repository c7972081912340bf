#include "rules/checks/util.h"

namespace lwc::checks {

std::vector<int> nodes_of(const SyntaxTree& tree, std::string_view type) {
  std::vector<int> out;
  for (int id = 0; id < static_cast<int>(tree.nodes.size()); ++id)
    if (type == tree.nodes[id].type) out.push_back(id);
  return out;
}

std::string_view call_name(const SyntaxTree& tree, int call) {
  int fn = tree.child_by_field(call, "function");
  return fn >= 0 && tree.is(fn, "identifier") ? tree.text(fn) : std::string_view();
}

std::vector<int> call_arguments(const SyntaxTree& tree, int call) {
  int args = tree.child_by_field(call, "arguments");
  return args >= 0 ? tree.named_children(args) : std::vector<int>{};
}

std::vector<std::string> string_list(const nlohmann::json& data, const char* key) {
  std::vector<std::string> out;
  if (data.contains(key))
    for (const auto& v : data.at(key)) out.push_back(v.get<std::string>());
  return out;
}

bool matches_any(const std::vector<std::string>& globs, std::string_view text) {
  for (const auto& g : globs)
    if (glob_match(g, text)) return true;
  return false;
}

bool is_definition_name(const SyntaxTree& tree, int identifier) {
  int parent = tree.at(identifier).parent;
  if (parent < 0) return false;
  std::string_view type = tree.at(parent).type;
  if (type == "preproc_def" || type == "preproc_function_def") return tree.child_by_field(parent, "name") == identifier;
  return type == "function_declarator" && tree.child_by_field(parent, "declarator") == identifier;
}

}  // namespace lwc::checks
