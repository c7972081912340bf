#pragma once
// The per-function harness (docs/verify.md): one function of a shader run on the device in each
// of its forms (the original in float32, each rewrite) and as a float64 reference, on the stiff
// and extreme cases of LWC-BRIEF §6, with errors measured in one frame and run time per invocation.
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fix/scene.h"
#include "lang/syntax.h"
#include "verify/compile.h"
#include "verify/vulkan.h"
#include "world/model.h"

namespace lwc {

class WorkerDevice;
struct DriverProbes;

// One form of the file: its whole text, and the engine era it compiles against (Unreal files).
struct FileVariant {
  std::string label;     // "original (float32)", "translated world", "DoubleFloat"
  std::string text;
  int ue_version = 504;  // LWCPORT_UE_VERSION for Unreal files
  // Lines (1-based) of a fixed text in a top-level item (a function, a declaration) that still
  // holds a finding with no automatic fix, and its rules: a compile error there means the rewrite
  // is incomplete, not wrong.
  std::map<int, std::string> hand_fixes;
  bool writable = true;  // a text fix writes (a DFFast* form is measured, never written)
};

// What a variant's text gives before any function is cut from it, shared by the functions of
// one file (they may be verified side by side): preprocessing, the whole-file compile check.
class VariantCache;
std::shared_ptr<VariantCache> make_variant_cache();

// What lint's analysis says about a file's functions, which the judge goes by rather than names.
struct FunctionFacts {
  // What each function returns, by the world-space model: a position is judged in world units
  // whatever the function is called; otherwise its name decides.
  std::map<std::string, Kind> returns;
  // Functions holding an error-free transformation (lwc-missing-precise's fact): its operation,
  // "sum", "fast-sum", "product" or "split". Their (high, low) result is judged by the defining
  // property against an exact CPU reference, not against a float64 promotion (whose low part is 0).
  std::map<std::string, std::string> error_free;
  // The model's kinds of the file's globals, and of each function's parameters (its first
  // definition's, in order): an input's role comes from them where they say something.
  std::map<std::string, Kind> globals;
  std::map<std::string, std::vector<Kind>> parameters;
  // The world-space data (rules/world-space.json and the project's sources): the kinds of engine
  // members and other paths (`*.WorldPosition_CamRelative` is translated), naming conventions aside.
  const WorldData* world = nullptr;
};

struct HarnessSetup {
  Lang lang = Lang::hlsl;
  std::string display;   // the file, for messages
  Stage stage = Stage::fragment;
  bool unreal = false;
  // Unreal code compiled against the engine's own headers ("engine-shaders"), of this era, rather
  // than lwcport's stub.
  std::optional<UnrealEra> engine;
  IncludeResolver include;
  std::vector<std::pair<std::string, std::string>> defines;  // the build's macros (.lwcport.json)
  std::vector<std::string> force_includes;                    // HLSL: included ahead of the file (.lwcport.json)
  FunctionFacts facts;
  // Library functions that fail the library's own check on this driver (library_faults): a kernel
  // calling one is not judged; the library is at fault, not the code.
  std::map<std::string, std::string> library_faults;
  std::string unreal_library;  // the HLSL library of the Unreal environment ("" = lwcport's own; a test injects faults)
  SceneNumbers scene;
  int invocations = 16384;  // per dispatch
  TimingPlan timing;        // how the variants are timed against each other
  std::shared_ptr<VariantCache> cache = make_variant_cache();
};

struct VariantResult {
  std::string label;
  // "pass"; "fail" (its own arithmetic misses the target); "input-limited" (its arithmetic is
  // within the target, but inputs it keeps from the original, as the original's callers hand them
  // over, are not); "incomplete: ..." (it does not compile where a finding has no automatic fix);
  // or why it could not be measured.
  std::string status;
  double max_error = 0;     // world units (cm): positions, offsets, distances; clip as a world offset
  bool world_outputs = false;  // some output is in world units (else only ULPs and decisions apply)
  double median_error = 0;
  double max_ulps = 0;      // of the reference value, float32 ULPs (values below 1 count as 1)
  double own_max_error = 0; // against the reference run on the inputs as this variant receives them
  double own_max_ulps = 0;
  int mismatches = 0;       // integer and bool results (decisions) that differ from the reference
  double worst_over_target = 0;  // the worst result's error over the target (ULPs over 16 where not world units)
  double ns_per_invocation = 0;  // median over the interleaved rounds
  double cost_spread = 0;        // the width of that median's 95% confidence interval over it
  double pipeline_seconds = 0;   // shader module + pipeline creation and the first dispatch (lavapipe's JIT)
  int spirv_instructions = 0;
  uint64_t spirv_hash = 0;     // of the kernel's SPIR-V: the same code costs the same
  std::vector<std::string> contraction_losses;
  std::string worst;        // the case, its inputs, what was expected and what came out
  std::string inherited_rounding;  // input-limited: which inherited inputs round, and by how much
  bool measured = false;    // it ran and was compared
  bool pareto = false;      // on the error/time front of the passing variants fix can write
  bool writable = true;     // as FileVariant::writable

  bool passed() const { return status == "pass"; }
  bool input_limited() const { return status == "input-limited"; }
  // Shown wrong: it misses the target, does not compile, or hung or crashed the driver. (A form
  // the harness cannot run or compare, or an incomplete one, is neither passed nor refuted.)
  bool refuted() const {
    return status.starts_with("fail") || status.starts_with("does not compile") || status.starts_with("did not run");
  }
};

struct FunctionResult {
  std::string file, function;
  std::vector<VariantResult> variants;  // variants[0] is the original
  std::string reference;   // how the reference was computed, or why it could not be
  std::vector<std::string> inputs;  // each input of the original: its role and how it is filled (verify --explain)
  std::string pick;        // which variant the scene picks, and why
  int timing_rounds = 0;   // interleaved rounds the costs come from
  std::string timing;      // "" or why the variants could not be timed
  // Where the time went, over every kernel of the function (the reference included).
  double compile_seconds = 0;   // glslang: preprocessing, the compile check, the kernel to SPIR-V
  double pipeline_seconds = 0;  // Vulkan pipeline creation and the one dispatch of each correctness run (lavapipe's JIT)
  double dispatch_seconds = 0;  // the timed rounds
};

// Marks the error/time Pareto front and writes the scene's pick, over the variants that pass and
// that fix can write; costs within the measurement's spread (and 25%) count as
// equal, the fewest SPIR-V instructions then decide.
void pick_variant(FunctionResult& result, double precision);

// The named cases every function runs on (LWC-BRIEF §6), in order.
std::vector<std::string> harness_case_names();

// Verifies `function` in every variant against the original promoted to float64.
FunctionResult verify_function(WorkerDevice& device, const DriverProbes& probes, const HarnessSetup& setup,
                               const std::string& function, const std::vector<FileVariant>& variants);

}  // namespace lwc
