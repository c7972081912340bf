#!/usr/bin/env bash
# Replays every input in tests/fuzz/regressions (each a crash or hang once found, minimised),
# then fuzzes for SECONDS (default 120) from the corpus with the shader dictionary. A crash, an
# ASan/UBSan report, an uncaught exception or an input slower than 10 s fails the run; the input
# is kept in build-fuzz/artifacts/.
#   usage: tests/fuzz/run.sh [SECONDS] [extra libFuzzer flags...]
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-120}
shift || true
fuzz=build-fuzz/lwcport_fuzz
[ -x "$fuzz" ] || { echo "$fuzz is missing: run tests/fuzz/build.sh (.ci/setup does)" >&2; exit 2; }
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

regressions=(tests/fuzz/regressions/*)
if [ -e "${regressions[0]}" ]; then
  "$fuzz" -timeout=10 -rss_limit_mb=2048 "${regressions[@]}" > build-fuzz/replay.log 2>&1 || { cat build-fuzz/replay.log; exit 1; }
  echo "replayed ${#regressions[@]} regression input(s)"
fi

# Seeds: each corpus file behind the byte that makes the target read it with its own extension
# (the order of kPaths in fuzz_target.cpp).
seeds=build-fuzz/seeds
work=build-fuzz/work
mkdir -p "$seeds" "$work" build-fuzz/artifacts
exts=(usf ush hlsl vert frag comp glsl.js sc)
i=0
while IFS= read -r f; do
  for k in "${!exts[@]}"; do
    if [[ "$f" == *."${exts[$k]}" ]]; then
      { printf "\\$(printf '%03o' "$k")"; cat "$f"; } > "$seeds/seed$i"
      i=$((i + 1))
      break
    fi
  done
done < <(find corpus -type f | sort)
# ... and a few behind 0xF0, which opens them in the language server.
for f in corpus/glsl/forward.vert corpus/ue4/HeightFogCommon.ush corpus/ue5.4/DoubleFloatHelpers.ush; do
  { printf '\360'; cat "$f"; } > "$seeds/lsp-$(basename "$f")"
done
"$fuzz" "$work" "$seeds" -dict=tests/fuzz/shader.dict -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -max_len=16384 -print_final_stats=1 -artifact_prefix=build-fuzz/artifacts/ "$@" 2>&1 | tail -25
