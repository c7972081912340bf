#include "support.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

#include "rules/analyze.h"

namespace lwc::test {

Run run(const std::string& command) {
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + command);
  std::string out;
  char buf[65536];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  int status = ::pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

std::string random_edit(const std::string& text, std::mt19937& rng, const std::vector<std::string>& pieces) {
  size_t at = std::uniform_int_distribution<size_t>(0, text.size())(rng);
  size_t cut = std::uniform_int_distribution<int>(0, 3)(rng) == 0 ? std::uniform_int_distribution<size_t>(0, 40)(rng) : 0;
  cut = std::min(cut, text.size() - at);
  std::string piece = std::uniform_int_distribution<int>(0, 2)(rng) == 0 ? "" : pieces[rng() % pieces.size()];
  return text.substr(0, at) + piece + text.substr(at + cut);
}

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write(const std::string& path, const std::string& text) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

std::string scratch(const std::string& name) {
  // Per process: ctest runs tests in parallel, and two runs may share a machine.
  std::filesystem::path p =
      std::filesystem::temp_directory_path() / ("lwcport-test-" + std::to_string(::getpid()) + "-" + name);
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p.string();
}

std::vector<Finding> lint_text(const std::string& code, Lang lang, const std::string& rule) {
  AnalyzeOptions o;
  o.lang = lang;
  if (!rule.empty()) o.select = {rule};
  return analyze(Source(lang == Lang::hlsl ? "test.hlsl" : "test.glsl", code), o);
}

std::string source_dir() { return LWCPORT_SOURCE_DIR; }
std::string binary() { return LWCPORT_BINARY; }

}  // namespace lwc::test
