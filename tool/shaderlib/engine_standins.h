#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "world/era.h"

namespace lwc {

// What Unreal's shader compiler writes for each shader at compile time, which no engine folder
// holds: the compilation environment's macros and the `/Engine/Generated/` headers. With the
// engine's own `Shaders` folder ("engine-shaders" in .lwcport.json), lwcport compiles against the
// engine's headers and stands in for these, from its own tables of the era
// (tool/shaderlib/src/unreal_view_members.txt); every stand-in says it is one.

// The era an engine `Shaders` folder holds, from its headers: Private/DoubleFloat.ush (5.4+),
// Private/LargeWorldCoordinates.ush (5.0-5.3), else UE4. None when it holds no Private/Common.ush.
std::optional<UnrealEra> engine_shaders_era(const std::filesystem::path& folder);

// The macros the shader compiler defines for every shader, for the platform the harness imitates
// (Shader Model 5 on D3D: Platform.ush then reads Platform/D3D/D3DCommon.ush).
std::vector<std::pair<std::string, std::string>> engine_compile_defines(UnrealEra era);

// The text of `/Engine/Generated/<name>` where lwcport stands in for it (the generated uniform
// buffer list, the View and InstancedView uniform buffers, the view state and its accessors);
// none for what it does not (the material and vertex factory templates, other uniform buffers).
std::optional<std::string> generated_standin(std::string_view name, UnrealEra era);

// Generated headers lwcport does not stand in for, and why, for messages: "" when it does.
std::string generated_not_stood_in(std::string_view name);

}  // namespace lwc
