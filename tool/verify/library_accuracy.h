#pragma once
// `lwcport verify --shaderlib`: every DoubleFloat operation of lwcport's library run on the
// device over random and adversarial inputs, against a double-double CPU reference, with the
// measured error set beside the published bound (LWC-BRIEF §4).
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "lang/syntax.h"
#include "verify/double_double.h"
#include "verify/probes.h"

namespace lwc {

class WorkerDevice;

// The inputs an operation is checked on: the shape of its operands and the relation between them.
enum class InputFamily {
  sum,          // any magnitudes and signs, half of them close enough to cancel
  ordered,      // |a| >= |b| (Fast2Sum's precondition)
  same_sign,    // both operands of one sign (SloppyDWPlusDW's precondition)
  opposite,     // opposite signs, close magnitudes (where SloppyDWPlusDW has no bound)
  close,        // same sign, within a factor of 2 (a camera-relative difference)
  product,      // magnitudes 2^-40..2^40: no overflow in Dekker's split, no underflow in the error
  quotient,     // as product, divisor nonzero
  positive,     // one positive operand (square roots)
  uncanonical,  // one pair whose Low may be larger than an ULP of High (what DFDemote must round)
  tile_offset,  // a UE 5.0 tile (an integer) and an offset (up to three tiles: not normalised)
  world,        // one pair of world magnitude (to 2^43), with tile edges and half-tile ties
};

// How the error is judged. u = 2^-24.
struct Bound {
  // offset: one rounding of an offset within half a tile, |error| <= u * 2^20.
  enum Kind { exact, relative, rounded, offset, none } kind = none;
  double u2 = 0;             // relative: |error| <= u2 * u^2 * |exact|; rounded: the u^2 term below
  enum Scale { sum, product, quotient } scale = sum;
  // rounded: |error| <= roundings * u * |exact| + u2 * u^2 * scale, where scale is |A| + |B|,
  // |A * B| or |A / B|: the roundings of a float result plus those of the low parts.
  std::string text;          // as published: "3u^2 + 13u^3 (AccurateDWPlusDW)"
  double roundings = 1;      // rounded: float roundings of the result
};

struct LibraryOp {
  std::string call;          // in the shader: A, B are pairs, a, b floats (A.High, B.High)
  std::string glsl_call;     // the same in GLSL, where its types are spelled differently ("" = call)
  std::string label;         // how reports name it, where the call is long ("" = call)
  const std::string& name() const { return label.empty() ? call : label; }
  bool pair_operands[2] = {false, false};
  int operands = 2;
  bool pair_result = true;
  // The result is a UE 5.0 tile and offset (`DFToTileOffset`'s out parameters), read as
  // Tile * 2^21 + Offset, with |Offset| at most half a tile beyond the input's low part.
  bool tile_result = false;
  InputFamily inputs = InputFamily::sum;
  Bound bound;
  bool needs_fused_fma = false;
  dd::Value (*reference)(dd::Value, dd::Value) = nullptr;
};

// The operations `verify --shaderlib` checks, in the order it prints them.
const std::vector<LibraryOp>& library_ops();

struct OpMeasurement {
  std::string status;        // "pass", "fail", "reported: <why>", or "error: <why>"
  double max_relative = 0;   // max |error| / |exact|
  double median_relative = 0;
  double max_bound_ratio = 0;  // max |error| / allowed error (> 1 fails)
  int non_canonical = 0;     // pair results with High + Low != High in float32
  // Inputs outside the library's domain, counted apart from the judged inputs: beyond Dekker's
  // split limit where the operation multiplies with it (world values stay below 2^43 cm), and
  // denormal low parts on a driver that flushes denormals (Vulkan allows it; world values stay
  // far above 2^-100 cm).
  struct Outside {
    size_t inputs = 0, misses = 0;
    std::string example;  // the first input there outside the bound
  };
  Outside beyond_split_limit, denormal_range;
  size_t inputs = 0;
  std::string worst;         // the worst input: its case, operands, expected and measured results
};

struct OpReport {
  const LibraryOp* op = nullptr;
  std::map<Lang, OpMeasurement> by_lang;
};

struct LibraryAccuracy {
  std::vector<OpReport> ops;
  std::map<Lang, std::vector<std::string>> contraction_losses;  // from the SPIR-V of every kernel
  std::map<Lang, int> error_free_functions_checked;
  double pipeline_seconds = 0, dispatch_seconds = 0;
  bool failed() const;
};

struct LibraryCheckOptions {
  std::vector<Lang> langs = {Lang::glsl, Lang::hlsl};
  std::map<Lang, std::string> library;  // the library text per language; default: lwcport's own
  std::vector<LibraryOp> ops;           // default: library_ops()
  size_t inputs = 131072;               // per operation, adversarial cases first
};

LibraryAccuracy check_library(WorkerDevice& device, const DriverProbes& probes, const LibraryCheckOptions& options);

// The library functions that fail their own check in `lang`, each with the check's verdict: a
// kernel calling one cannot be judged (the library is at fault, not the code).
std::map<std::string, std::string> library_faults(const LibraryAccuracy& accuracy, Lang lang);

// Plain float operands for a shader's own error-free transformation (a TwoSum or Split helper):
// the family's adversarial cases (inputs beyond Dekker's split limit left out, and denormal low
// parts where the driver flushes them: outside the domain, as in check_library), then random
// ones; the same every run.
struct FloatOperands {
  float a = 0, b = 0;
  int case_index = -1;  // into adversarial_case_names(family); -1: random
};
std::vector<FloatOperands> float_operands(InputFamily family, size_t count, bool flushes_denormals);

// The named adversarial cases of a family (LWC-BRIEF §6), for docs and messages.
std::vector<std::string> adversarial_case_names(InputFamily family);

}  // namespace lwc
