#!/usr/bin/env bash
# Issue 39 §4: compiled against the real engine. Which of Epic's own 5.x shader files compile in
# lwcport's build against the engine's own headers ("engine-shaders": glslang, lwcport standing in
# only for what the shader compiler generates), and, of those, which of lwcport's fixed 4.27
# counterparts compile in their place.
#
#   tests/bench/engine_build.sh [--build DIR] [--out DIR] [--all] UE427_SHADERS UE5_SHADERS 5.4|5.0
#
# The folders are the engine's shader folder (Private/, Public/) at 4.27 and at the 5.x target
# (see epic_port.sh for the public mirrors; Epic's code never enters this repository). The 4.27
# folder is copied and fixed as epic_port.sh fixes it (`{"unreal": TARGET}`, `fix --unsafe-fixes`);
# the 5.x folder is linked into a scratch folder with `{"engine-shaders": "."}`. Each file is
# compiled as it is (build/tests/lwcport_engine_compile: the environment `fix --check-build`
# gives it); where Epic's file compiles, lwcport's fixed 4.27 file takes its place, alone (every
# other file stays Epic's), and is compiled the same way. Files: the 25 issue 39 names, or with
# --all every 4.27 file with a counterpart of the same path. Prints Markdown for RESULTS.md (file
# names and outcomes only); with --out DIR, builds.tsv there holds each first error, which quotes
# Epic's names: keep DIR outside the repository.
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=$here/build
out=
all=0
args=()
while (($#)); do
  case $1 in
    --build) build=$(cd "$2" && pwd); shift 2 ;;
    --out) out=$2; shift 2 ;;
    --all) all=1; shift ;;
    *) args+=("$1"); shift ;;
  esac
done
((${#args[@]} == 3)) || { sed -n 2,20p "$0" >&2; exit 2; }
old_src=$(cd "${args[0]}" && pwd); new_src=$(cd "${args[1]}" && pwd); target=${args[2]}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cp -r "$old_src" "$work/old"
printf '{"unreal": "%s", "virtual-roots": {"/Engine/": "."}}\n' "$target" > "$work/old/.lwcport.json"
(cd "$work/old" && "$build/lwcport" fix . --unsafe-fixes --fail-on none > "$work/fix.txt" 2>&1) || true
mkdir "$work/new"
cp -rs "$new_src/." "$work/new/"
echo '{"engine-shaders": "."}' > "$work/new/.lwcport.json"

issue="MaterialTemplate.ush LocalVertexFactory.ush MeshParticleVertexFactory.ush ParticleSpriteVertexFactory.ush
ParticleGPUSpriteVertexFactory.ush VertexFactoryCommon.ush GpuSkinVertexFactory.ush LandscapeVertexFactory.ush SceneData.ush
BasePassVertexShader.usf VelocityShader.usf VolumetricFog.usf VolumetricFogVoxelization.usf VolumetricCloud.usf SkyAtmosphere.usf
HeightFogCommon.ush DeferredLightPixelShaders.usf DeferredLightingCommon.ush ForwardLightingCommon.ush DeferredDecal.usf
DistanceFieldShadowing.usf TranslucentLightInjectionShaders.usf ReflectionEnvironmentShared.ush LightGridInjection.usf
ParticleSimulationShader.usf"
cd "$work/new"
files=()
if ((all)); then
  while IFS= read -r rel; do [[ -e "$rel" ]] && files+=("$rel"); done < <(cd "$work/old" && find Private Public -name '*.us[hf]' | sort)
else
  for name in $issue; do
    rel=$(cd "$work/old" && find Private -name "$name" | sort | head -1)
    [[ -n $rel && -e $rel ]] && files+=("$rel")
  done
fi
compile() { "$build/tests/lwcport_engine_compile" "$1" | cut -f2-; }
: > "$work/builds.tsv"
epic_ok=0; ours_ok=0; changed=0; changed_ok=0
rows=()
for rel in "${files[@]}"; do
  epic=$(compile "$rel")
  ours=-
  if [[ $epic == compiles ]]; then
    epic_ok=$((epic_ok + 1))
    cp --remove-destination "$work/old/$rel" "$rel"
    ours=$(compile "$rel")
    ln -sf "$new_src/$rel" "$rel"
    [[ $ours == compiles ]] && ours_ok=$((ours_ok + 1))
    if ! cmp -s "$work/old/$rel" "$old_src/$rel"; then
      changed=$((changed + 1))
      [[ $ours == compiles ]] && changed_ok=$((changed_ok + 1))
    fi
  fi
  printf '%s\t%s\t%s\n' "$rel" "$epic" "$ours" >> "$work/builds.tsv"
  rows+=("| $(basename "$rel") | ${epic%%$'\t'*} | ${ours%%$'\t'*} |")
done
[[ -n $out ]] && mkdir -p "$out" && cp "$work/builds.tsv" "$out/builds.tsv"
echo "### Compiled against the engine's own headers: UE $target"
echo
echo "${#files[@]} files; Epic's $target file compiles in lwcport's build for $epic_ok; of those, lwcport's fixed 4.27"
echo "file compiles in its place for $ours_ok; of the $changed of those the fix changed, $changed_ok compile."
echo
if ((!all)); then
  echo "| file | Epic's file | lwcport's fixed 4.27 file |"
  echo "|---|---|---|"
  printf '%s\n' "${rows[@]}"
fi
