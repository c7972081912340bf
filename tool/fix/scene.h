#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/finding.h"

namespace lwc {

// What a scene needs (docs/scenes.md): distances in centimetres (Unreal units).
struct SceneNumbers {
  double world_extent = 8796093022208.0;  // largest coordinate magnitude: UE_LARGE_WORLD_MAX, 2^43 cm
  double view_distance = 1048576.0;       // farthest distance from the camera that is drawn: 2^20 cm
  double precision = 0.0625;              // largest acceptable absolute error: 1/16 cm
};

struct SceneOverride {
  std::vector<std::string> paths;  // gitignore-style globs against the file's path
  std::optional<double> world_extent, view_distance, precision;
};

struct Scene {
  std::string name = "Unreal full world (default)";
  SceneNumbers numbers;
  std::vector<SceneOverride> overrides;

  // The numbers for one file: the last override whose globs match wins, field by field.
  SceneNumbers for_path(std::string_view path) const;
};

// Reads a scene profile. Throws std::runtime_error naming the file, and the line and column for
// malformed JSON, or the key for a bad value.
Scene load_scene(const std::string& path);
Scene parse_scene(std::string_view text, const std::string& path);
// "100 km", "2^43 cm", "0.5 mm", "1e5 m": a distance in centimetres; nullopt if malformed.
std::optional<double> parse_distance(std::string_view text);
// A distance in the unit that reads best ("0.39 cm", "100 km").
std::string format_distance(double cm);

// The largest rounding error of a float32 holding a magnitude up to m: half its ULP,
// 2^(floor(log2 m) - 24).
double float32_error(double magnitude);

enum class Strategy { automatic, translated, df };
std::optional<Strategy> parse_strategy(std::string_view name);

// The planner: for each scene-dependent finding, decides whether the scene needs it fixed and
// which candidate rewrite meets the precision at the least cost, keeps that one fix, and writes
// the decision with its numbers. Other findings keep their first candidate.
void plan_fixes(std::vector<Finding>& findings, const SceneNumbers& scene, Strategy strategy);

}  // namespace lwc
