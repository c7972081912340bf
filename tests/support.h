#pragma once
#include <random>
#include <string>
#include <vector>

#include "core/finding.h"
#include "lang/syntax.h"

namespace lwc::test {

struct Run {
  int exit_code;
  std::string out;
};
// Runs a shell command, capturing standard output (standard error goes to the test log).
Run run(const std::string& command);
std::string read(const std::string& path);
void write(const std::string& path, const std::string& text);
// A fresh, empty scratch folder of this test process.
std::string scratch(const std::string& name);
// Findings for a code string in a language, optionally only one rule's.
std::vector<Finding> lint_text(const std::string& code, Lang lang, const std::string& rule = "");
std::string source_dir();
// An edit an editor makes: a random place, a quarter of the time up to 40 bytes cut there, and
// (two times in three) one of `pieces` typed.
std::string random_edit(const std::string& text, std::mt19937& rng, const std::vector<std::string>& pieces);
std::string binary();

}  // namespace lwc::test
