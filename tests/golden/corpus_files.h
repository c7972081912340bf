#pragma once
#include <string>
#include <vector>

namespace lwc::test {
// Every corpus shader (paths relative to the source folder, sorted), example scenes and golden
// outputs left out.
std::vector<std::string> corpus_shaders();
}  // namespace lwc::test
