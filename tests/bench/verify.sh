#!/usr/bin/env bash
# Verification benchmark: `lwcport verify` over the bundled corpus on lavapipe, in one run.
# Prints functions verified per second, where the time goes (glslang; Vulkan pipelines and
# lavapipe's JIT; the timed dispatches), and the run-time ratio of each rewrite to the original
# measured in the same run (the baseline); append the table to RESULTS.md with the machine and date.
#   usage: tests/bench/verify.sh [PATHS...]   (default: corpus)
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=build/lwcport
[ -x "$bin" ] || { echo "build first: bash .ci/setup" >&2; exit 2; }
command -v python3 > /dev/null || { echo "python3 is missing: apt-get install python3" >&2; exit 2; }
out=tests/bench/work/verify.json
mkdir -p "$(dirname "$out")"
[ $# -gt 0 ] || set -- corpus
"$bin" verify "$@" --format json --fail-on none --output "$out"
python3 - "$out" <<'PY'
import json, math, sys
r = json.load(open(sys.argv[1]))
t = r["time"]
fns = r["functions"]
variants = sum(len(f["variants"]) for f in fns)
ratios = []
for f in fns:
    base = f["variants"][0]
    if not base["measured"] or base["nsPerInvocation"] <= 0:
        continue
    for v in f["variants"][1:]:
        if v["measured"]:
            ratios.append(v["nsPerInvocation"] / base["nsPerInvocation"])
busy = t["compileSeconds"] + t["pipelineSeconds"] + t["dispatchSeconds"]
print(f"| device | {r['device']} |")
print(f"| functions / variants | {len(fns)} / {variants} |")
print(f"| wall time | {t['wallSeconds']:.1f} s ({t['functionsPerSecond']:.2f} functions/s) |")
for key, label in (("compileSeconds", "glslang (preprocess, compile check, kernel)"),
                   ("pipelineSeconds", "Vulkan pipelines + lavapipe JIT"),
                   ("dispatchSeconds", "timed dispatches")):
    print(f"| {label} | {t[key]:.1f} s ({100 * t[key] / t['wallSeconds']:.0f}% of wall) |")
print(f"| other (inputs, encoding, comparison, process traffic) | {t['wallSeconds'] - busy:.1f} s |")
if ratios:
    geo = math.exp(sum(math.log(x) for x in ratios) / len(ratios))
    print(f"| rewrite / original run time, {len(ratios)} measured rewrites | geometric mean {geo:.2f}, "
          f"range {min(ratios):.2f}-{max(ratios):.2f} |")
PY
