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
// buffer list, the uniform buffers of its tables, the view state and its accessors, the vertex
// factory as the local one); none for what it does not (a pass's own uniform buffers).
std::optional<std::string> generated_standin(std::string_view name, UnrealEra era);

// `/Engine/Generated/Material.ush` for a material with no expressions: the engine's own material
// template (`template`, its Private/MaterialTemplate.ush) with each of the blanks the shader
// compiler fills per material filled as a default material would: counts of texture coordinates,
// the pixel inputs' members (lwcport's table), `return 0` for a value, nothing for code.
std::string material_standin(std::string_view material_template, UnrealEra era);

}  // namespace lwc
