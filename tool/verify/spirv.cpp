#include "verify/spirv.h"

#include <fmt/format.h>

#include <map>

namespace lwc {

namespace {

// Opcodes and enumerants from the SPIR-V specification (unified 1.x).
enum : uint32_t {
  OpName = 5, OpLine = 8, OpTypeFloat = 22, OpTypeVector = 23, OpFunction = 54, OpFunctionEnd = 56, OpDecorate = 71,
  OpFConvert = 115, OpFAdd = 129, OpFSub = 131, OpFMul = 133, OpFDiv = 136, OpNoLine = 317,
};
constexpr uint32_t kNoContraction = 42;

std::string literal_string(const std::vector<uint32_t>& words, size_t at, size_t end) {
  std::string out;
  for (size_t i = at; i < end; ++i)
    for (int b = 0; b < 4; ++b) {
      char c = static_cast<char>((words[i] >> (8 * b)) & 0xff);
      if (!c) return out;
      out += c;
    }
  return out;
}

}  // namespace

SpirvSummary inspect_spirv(const std::vector<uint32_t>& words) {
  SpirvSummary summary;
  std::map<uint32_t, std::string> names;
  std::set<uint32_t> no_contraction, float32_types;
  // First pass: names, decorations and types. Second: function bodies.
  for (int pass = 0; pass < 2; ++pass) {
    SpirvFunction* current = nullptr;
    int line = 0;
    for (size_t i = 5; i < words.size();) {
      uint32_t count = words[i] >> 16, op = words[i] & 0xffff;
      if (count == 0 || i + count > words.size()) break;  // malformed: stop reading
      if (pass == 0) {
        if (op == OpName && count >= 3) names[words[i + 1]] = literal_string(words, i + 2, i + count);
        if (op == OpDecorate && count >= 3 && words[i + 2] == kNoContraction) no_contraction.insert(words[i + 1]);
        if (op == OpTypeFloat && count >= 3 && words[i + 2] == 32) float32_types.insert(words[i + 1]);
        if (op == OpTypeVector && count >= 4 && float32_types.count(words[i + 2])) float32_types.insert(words[i + 1]);
      } else if (op == OpLine || op == OpNoLine) {
        line = op == OpLine && count >= 4 ? static_cast<int>(words[i + 2]) : 0;
      } else if (op == OpFunction && count >= 3) {
        std::string signature = names.count(words[i + 2]) ? names[words[i + 2]] : "";
        summary.functions.push_back({signature.substr(0, signature.find('(')), signature, 0, 0, {}});
        current = &summary.functions.back();
      } else if (op == OpFunctionEnd) {
        current = nullptr;
      } else if (current) {
        ++summary.instructions;
        if (op == OpFConvert && count >= 4 && float32_types.count(words[i + 1])) current->narrowing_lines.push_back(line);
        // fma is fused by definition: NoContraction means nothing on it, so it is not counted.
        if (op == OpFAdd || op == OpFSub || op == OpFMul || op == OpFDiv) {
          ++current->float_ops;
          if (no_contraction.count(words[i + 2])) ++current->no_contraction;
        }
      }
      i += count;
    }
  }
  return summary;
}

const std::set<std::string>& error_free_functions() {
  static const std::set<std::string> names = {"DFTwoSum", "DFFastTwoSum", "DFSplit", "DFTwoProductDekker",
                                              "DFTwoProductFMA"};
  return names;
}

std::vector<std::string> contraction_losses(const SpirvSummary& summary) {
  std::vector<std::string> out;
  for (const SpirvFunction& f : summary.functions)
    if (error_free_functions().count(f.name) && f.no_contraction < f.float_ops)
      out.push_back(fmt::format("{}: {} of {} float operations carry NoContraction", f.signature, f.no_contraction,
                                f.float_ops));
  return out;
}

}  // namespace lwc
