#include "corpus_files.h"

#include <algorithm>
#include <filesystem>

#include "lang/syntax.h"
#include "support.h"

namespace fs = std::filesystem;

namespace lwc::test {

std::vector<std::string> corpus_shaders() {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(source_dir() + "/corpus")) {
    std::string rel = fs::relative(e.path(), source_dir()).generic_string();
    bool golden = e.path().stem().extension() == ".fixed" || e.path().filename().string().find(".fixed-") != std::string::npos;
    if (e.is_regular_file() && lang_from_path(rel) && rel.find("/scenes/") == std::string::npos && !golden)
      out.push_back(rel);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace lwc::test
