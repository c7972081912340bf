#!/usr/bin/env bash
# Lint throughput benchmark. Generates >= 5,000 files / 50 MB from the corpus (or takes a real
# tree with --tree DIR), then times, in one run on the same files and interleaved (each command
# once per round, 5 rounds, medians): lint --jobs 1, lint --jobs 2, parse-only --jobs 1 (the
# baseline), and ripgrep over the rules' trigger identifiers. Ratios are of CPU time (user +
# system), the 2-job speed-up of wall time. Prints the figures as a Markdown table; append them
# to RESULTS.md with the machine and date.
#   usage: tests/bench/run.sh [FILES] [TARGET_MB]
#          tests/bench/run.sh --tree DIR
set -euo pipefail
tree=""
if [ "${1:-}" = "--tree" ]; then
  tree=$(cd "$2" && pwd)
  shift 2
fi
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
if [ -z "$tree" ]; then
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
fi
[ -n "$tree" ] && work=$tree
read -r count bytes < <("$bin" parse "$work" | tail -1 | sed -E 's/^Parsed ([0-9]+) file\(s\), ([0-9]+) bytes.*/\1 \2/')

# Each command once per round, in turn, so drift on a shared machine hits all alike; per command
# the median CPU (user + system) and wall time, and the largest peak memory.
pattern='View\.|PrimaryView|LWCHackToFloat|DFHackToFloat|_Hack\b|FLWC|\bLWC[A-Z]|DFFastTwoSum|DFDemote|LocalToWorld|WorldCameraOrigin|PreViewTranslation|modelMatrix|cameraPosition|precise|4097'
commands=(
  "parse1|$bin parse $work --jobs 1"
  "lint1|$bin lint $work --jobs 1 --format json --fail-on none"
  "lint2|$bin lint $work --jobs 2 --format json --fail-on none"
  "rg1|rg -j1 -c -e $pattern $work"
)
samples=$(mktemp)
trap 'rm -f "$samples" "$samples.one"' EXIT
for round in 0 1 2 3 4 5; do
  for entry in "${commands[@]}"; do
    label=${entry%%|*}
    read -ra cmd <<< "${entry#*|}"
    /usr/bin/time -o "$samples.one" -f "%e %U %S %M" "${cmd[@]}" > /dev/null 2>&1 || true
    [ "$round" -gt 0 ] && echo "$label $(tail -1 "$samples.one")" >> "$samples"  # round 0 warms the page cache
  done
done
awk -v bytes="$bytes" -v count="$count" '
  function median(label, what,   n, i, j, v, tmp) {
    n = 0
    for (i = 1; i <= rows; i++) if (lab[i] == label) v[++n] = val[i, what]
    for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (v[j] < v[i]) { tmp = v[i]; v[i] = v[j]; v[j] = tmp }
    return n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2
  }
  { rows++; lab[rows] = $1; val[rows, "wall"] = $2; val[rows, "cpu"] = $3 + $4; if ($5 > m[$1]) m[$1] = $5 }
  END {
    mb = bytes / 1048576
    p = median("parse1", "cpu"); l1 = median("lint1", "cpu"); r = median("rg1", "cpu")
    printf "| files | %d |\n| bytes | %d (%.1f MB) |\n", count, bytes, mb
    printf "| parse-only, 1 job, CPU | %.2f s (%.1f MB/s) |\n", p, mb / p
    printf "| lint, 1 job, CPU | %.2f s (%.1f MB/s per core) |\n", l1, mb / l1
    printf "| lint, 2 jobs, wall | %.2f s |\n", median("lint2", "wall")
    printf "| ripgrep, 1 thread, trigger identifiers, CPU | %.2f s |\n", r
    printf "| lint / parse-only, CPU (target <= 1.5) | %.2f |\n", l1 / p
    printf "| speed-up on 2 jobs, wall (target >= 1.7) | %.2f |\n", median("lint1", "wall") / median("lint2", "wall")
    printf "| lint / ripgrep, CPU | %.1f |\n", l1 / (r > 0 ? r : 0.01)
    printf "| peak memory, lint 2 jobs (target < 200 MB) | %.1f MB |\n", m["lint2"] / 1024
  }' "$samples"
