#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "rules/rule.h"
#include "world/pattern.h"

namespace lwc::checks {

// Every node of a type, in source order.
std::vector<int> nodes_of(const SyntaxTree& tree, std::string_view type);
// The called name of a call_expression when it is a plain identifier, else "".
std::string_view call_name(const SyntaxTree& tree, int call);
std::vector<int> call_arguments(const SyntaxTree& tree, int call);
// A rule-data list of strings (globs allowed) and a match against it.
std::vector<std::string> string_list(const nlohmann::json& data, const char* key);
bool matches_any(const std::vector<std::string>& globs, std::string_view text);
// True when an identifier is the name being declared or defined (a macro, a function), not a use.
bool is_definition_name(const SyntaxTree& tree, int identifier);

}  // namespace lwc::checks
