#pragma once
// Reading compiled SPIR-V: how big the code is, and whether the error-free steps kept their
// NoContraction decoration (what `precise` compiles to) all the way into the binary.
#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace lwc {

struct SpirvFunction {
  std::string name;          // the source name, without glslang's "(f1;f1;" parameter suffix
  std::string signature;     // the full OpName
  int float_ops = 0;         // OpFAdd, OpFSub, OpFMul, OpFDiv
  int no_contraction = 0;    // of those, the ones decorated NoContraction
  // Source lines (from OpLine; 0 where there is none) of conversions to a 32-bit float type.
  std::vector<int> narrowing_lines;
};

struct SpirvSummary {
  int instructions = 0;      // instructions inside function bodies
  std::vector<SpirvFunction> functions;
};

SpirvSummary inspect_spirv(const std::vector<uint32_t>& words);

// The library's error-free transformations: every float operation in them must be NoContraction.
const std::set<std::string>& error_free_functions();

// The error-free functions in `summary` with a float operation that lost NoContraction, as
// "DFTwoSum(f1;f1;: 0 of 6 float operations carry NoContraction".
std::vector<std::string> contraction_losses(const SpirvSummary& summary);

}  // namespace lwc
