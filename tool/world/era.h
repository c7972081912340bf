#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace lwc {

// The Unreal engine a shader builds against. The values are the stub's LWCPORT_UE_VERSION.
//   ue4    float world positions, world members in the View uniform buffer
//   ue5_0  UE 5.0 to 5.3: tile/offset (FLWC*) large-world types, world members in PrimaryView
//   ue5_4  UE 5.4 and later: DoubleFloat (FDF*) large-world types
enum class UnrealEra { ue4 = 427, ue5_0 = 500, ue5_4 = 504 };

// "4", "4.27", "5.0" ... "5.3" (tile/offset), "5.4" and later (DoubleFloat).
std::optional<UnrealEra> parse_unreal_era(std::string_view setting);
std::string_view era_name(UnrealEra era);  // "UE4", "UE 5.0-5.3", "UE 5.4+"

// The era a file's own code was written for: DoubleFloat names (or PrimaryView) -> 5.4, tile/offset
// names -> 5.0 (even beside DoubleFloat conversions, as 5.1-5.3 code has them), else UE4.
UnrealEra infer_unreal_era(std::string_view text);

// Unreal shader code: by its extension (.usf, .ush), or an include of the engine's (/Engine/).
bool is_unreal_source(std::string_view path, std::string_view text);

// The era a file is analysed for: the project's setting, or what the file uses.
struct UnrealTarget {
  UnrealEra era = UnrealEra::ue5_4;
  bool inferred = true;
  // "UE 5.4+", plus how it was decided, for messages.
  std::string describe() const;
};

// Preprocessor arms that say which engine they are for: `#if UE4_COMPAT` / `#else`,
// `#if ENGINE_MAJOR_VERSION >= 5`, `#ifdef UE5_...`, `#if USING_TESSELLATION` (UE4 only: UE 5.0
// removed hardware tessellation). Each arm guarded so, with its era (UE4, or
// ue5_0 standing for any UE5): a UE4 arm of code built against UE5 is UE4's, not debt.
struct EraArm {
  uint32_t begin, end;
  UnrealEra era;
};
std::vector<EraArm> era_guarded_arms(std::string_view text);

// Which Unreal era first defines each large-world API name (rules/world-space.json "unreal-api"):
// the engine's own DoubleFloat.ush, LargeWorldCoordinates.ush, LWCOperations.ush and
// WorldSpaceMath.ush, and PrimaryView.
class UnrealApi {
 public:
  static UnrealApi load(const nlohmann::json& table);
  // The first era defining `name`, or nullopt for a name Unreal does not define.
  std::optional<UnrealEra> first_era(std::string_view name) const;
  // Whether a name is of the large-world API's shape (DF*, LWC*, FDF*, PrimaryView...), so that
  // `first_era` answering nullopt means "not an engine name".
  bool looks_like_api(std::string_view name) const;

 private:
  std::map<std::string, UnrealEra, std::less<>> first_;
  std::set<std::string, std::less<>> shapes_;  // globs
};

}  // namespace lwc
