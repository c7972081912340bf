#!/usr/bin/env bash
# Replays every input that once crashed or hung a target, minimised (tests/fuzz/regressions,
# lsp-regressions, host-regressions), then fuzzes for SECONDS in all (default 120): half for the
# shader target (from the corpus, with the shader dictionary), a quarter for the language server's
# stream (lwcport_lsp_fuzz, from tests/fuzz/lsp-seeds with tests/fuzz/lsp.dict), a quarter for
# `lwcport host` (lwcport_host_fuzz: C++ text from the host corpus, with tests/fuzz/cpp.dict). A
# crash, an ASan/UBSan report, an uncaught exception or an input slower than 10 s (30 s for C++)
# fails the run; the input is kept in build-fuzz/artifacts/.
#   usage: tests/fuzz/run.sh [SECONDS] [extra libFuzzer flags...]
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-120}
shift || true
lsp_seconds=$((seconds / 4))
host_seconds=$((seconds / 4))
fuzz=build-fuzz/lwcport_fuzz
lsp_fuzz=build-fuzz/lwcport_lsp_fuzz
host_fuzz=build-fuzz/lwcport_host_fuzz
for target in "$fuzz" "$lsp_fuzz" "$host_fuzz"; do
  [ -x "$target" ] || { echo "$target is missing: run tests/fuzz/build.sh (.ci/setup does)" >&2; exit 2; }
done
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

replay() {  # target folder [timeout]
  local inputs=("$2"/*)
  if [ -e "${inputs[0]}" ]; then
    "$1" -timeout="${3:-10}" -rss_limit_mb=4096 "${inputs[@]}" > build-fuzz/replay.log 2>&1 || { cat build-fuzz/replay.log; exit 1; }
    echo "replayed ${#inputs[@]} regression input(s) of $(basename "$1")"
  fi
}
replay "$fuzz" tests/fuzz/regressions
replay "$lsp_fuzz" tests/fuzz/lsp-regressions
replay "$host_fuzz" tests/fuzz/host-regressions 30

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
"$fuzz" "$work" "$seeds" -dict=tests/fuzz/shader.dict -max_total_time="$((seconds - lsp_seconds - host_seconds))" -timeout=10 -rss_limit_mb=2048 \
  -max_len=16384 -print_final_stats=1 -artifact_prefix=build-fuzz/artifacts/ "$@" 2>&1 | tail -25

mkdir -p build-fuzz/lsp-work
"$lsp_fuzz" build-fuzz/lsp-work tests/fuzz/lsp-seeds -dict=tests/fuzz/lsp.dict -max_total_time="$lsp_seconds" -timeout=10 -rss_limit_mb=2048 \
  -max_len=16384 -print_final_stats=1 -artifact_prefix=build-fuzz/artifacts/lsp- "$@" 2>&1 | tail -25

# lwcport host: C++ text through Clang and the host checks. Seeds: the regressions, and the host
# corpus's units that include only its stand-in headers (a unit that includes glm or the standard
# library parses ten times slower, and so is fuzzed less).
mkdir -p build-fuzz/host-seeds build-fuzz/host-work
cp tests/fuzz/host-regressions/* build-fuzz/host-seeds/
grep -L -E '#include <' $(find corpus/host -name '*.cpp') | xargs -I{} cp {} build-fuzz/host-seeds/
"$host_fuzz" build-fuzz/host-work build-fuzz/host-seeds -dict=tests/fuzz/cpp.dict -max_total_time="$host_seconds" -timeout=30 \
  -rss_limit_mb=4096 -max_len=8192 -print_final_stats=1 -artifact_prefix=build-fuzz/artifacts/host- "$@" 2>&1 | tail -25
