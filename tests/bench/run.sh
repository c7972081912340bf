#!/usr/bin/env bash
# Lint throughput benchmark. Generates >= 5,000 files / 50 MB from the corpus, then times, in one
# run on the same files: lint --jobs 1, lint --jobs 2, parse-only --jobs 1 (the baseline), and
# ripgrep over the rules' trigger identifiers. Prints the figures as a Markdown table row set;
# append them to RESULTS.md with the machine and date.
#   usage: tests/bench/run.sh [FILES] [TARGET_MB]
set -euo pipefail
cd "$(dirname "$0")/../.."
files=${1:-5000}
target_mb=${2:-50}
work=tests/bench/work
bin=build/lwcport
[ -x "$bin" ] || { echo "build first: bash .ci/setup" >&2; exit 2; }
command -v rg > /dev/null || { echo "ripgrep is missing: apt-get install ripgrep" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "GNU time is missing: apt-get install time" >&2; exit 2; }

# Each generated file joins corpus files of one language, with its functions renamed so no two
# files are alike, until it reaches its share of the target size.
rm -rf "$work" && mkdir -p "$work/hlsl" "$work/glsl"
mapfile -t hlsl < <(find corpus -name '*.usf' -o -name '*.ush' -o -name '*.hlsl' | grep -v /engine/ | sort)
mapfile -t glsl < <(find corpus -name '*.vert' -o -name '*.frag' -o -name '*.comp' | sort)
per_file=$(( target_mb * 1024 * 1024 / files + 1 ))
awk -v files="$files" -v per="$per_file" -v out="$work" -v nh="${#hlsl[@]}" '
  FNR == 1 { src++; name[src] = FILENAME; lines[src] = 0 }
  { text[src, ++lines[src]] = $0; size[src] += length($0) + 1 }
  END {
    for (f = 0; f < files; f++) {
      glsl = (f % 5 == 4)
      ext = glsl ? ".vert" : ".usf"
      path = out "/" (glsl ? "glsl" : "hlsl") "/gen" f ext
      written = 0; k = f
      while (written < per) {
        s = glsl ? nh + 1 + k % (src - nh) : 1 + k % nh
        if (glsl && written > 0 && name[s] ~ /\.comp$/) { k++; continue }
        for (i = 1; i <= lines[s]; i++) {
          line = text[s, i]
          if (glsl && written > 0 && (line ~ /^#version/ || line ~ /^layout\(local_size/)) continue
          if (line ~ /^[A-Za-z_][A-Za-z0-9_<>]* [A-Za-z_][A-Za-z0-9_]*\(/ && line !~ /main\(/) sub(/\(/, "_" f "_" k "(", line)
          print line > path
          written += length(line) + 1
        }
        k++
      }
      close(path)
    }
  }' "${hlsl[@]}" "${glsl[@]}"
bytes=$(cat "$work"/*/* | wc -c)
count=$(find "$work" -type f | wc -l)

measure() {  # label, command...: prints "label seconds maxrss_kb"
  local label=$1; shift
  "$@" > /dev/null 2>&1 || true  # warm the page cache
  local best=""
  local rss=0
  for run in 1 2 3; do
    local t
    t=$( { /usr/bin/time -f "%e %M" "$@" > /dev/null; } 2>&1 >/dev/null | tail -1)
    local s=${t% *} m=${t#* }
    if [ -z "$best" ] || awk -v a="$s" -v b="$best" 'BEGIN { exit !(a < b) }'; then best=$s; fi
    [ "$m" -gt "$rss" ] && rss=$m
  done
  echo "$label $best $rss"
}

pattern='View\.|PrimaryView|LWCHackToFloat|DFHackToFloat|_Hack\b|FLWC|\bLWC[A-Z]|DFFastTwoSum|DFDemote|LocalToWorld|WorldCameraOrigin|PreViewTranslation|modelMatrix|cameraPosition|precise|4097'
results=$(
  measure parse1 "$bin" parse "$work" --jobs 1
  measure lint1 "$bin" lint "$work" --jobs 1 --format json --fail-on none
  measure lint2 "$bin" lint "$work" --jobs 2 --format json --fail-on none
  measure rg1 rg -j1 -c -e "$pattern" "$work"
)
echo "$results" > "$work/times.txt"
awk -v bytes="$bytes" -v count="$count" '
  { t[$1] = $2; m[$1] = $3 }
  END {
    mb = bytes / 1048576
    printf "| files | %d |\n| bytes | %d (%.1f MB) |\n", count, bytes, mb
    printf "| parse-only, 1 job | %.2f s (%.1f MB/s) |\n", t["parse1"], mb / t["parse1"]
    printf "| lint, 1 job | %.2f s (%.1f MB/s per core) |\n", t["lint1"], mb / t["lint1"]
    printf "| lint, 2 jobs | %.2f s |\n", t["lint2"]
    printf "| ripgrep, 1 thread, trigger identifiers | %.2f s |\n", t["rg1"]
    printf "| lint / parse-only (target <= 1.5) | %.2f |\n", t["lint1"] / t["parse1"]
    printf "| speed-up on 2 jobs (target >= 1.7) | %.2f |\n", t["lint1"] / t["lint2"]
    printf "| lint / ripgrep | %.1f |\n", t["lint1"] / t["rg1"]
    printf "| peak memory, lint 2 jobs (target < 200 MB) | %.1f MB |\n", m["lint2"] / 1024
  }' "$work/times.txt"
