#pragma once
#include <string_view>
#include <vector>

namespace lwc {
struct EmbeddedFile {
  std::string_view name;
  std::string_view text;
};
// Every rules/*.json file, embedded at build time (see embed_rules.cmake).
const std::vector<EmbeddedFile>& embedded_rule_files();
}  // namespace lwc
