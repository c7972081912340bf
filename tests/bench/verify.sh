#!/usr/bin/env bash
# Verification benchmark: `lwcport verify` over the bundled corpus on lavapipe, in one run.
# Prints functions verified per second, where the time goes (glslang; Vulkan pipelines and
# lavapipe's JIT; the timed rounds), the host's share of the CPU time against the driver
# processes', the peak memory (all processes together, and the largest), and the run-time ratio
# of each rewrite to the original measured in the same run (the baseline); append the table to
# RESULTS.md with the machine and date.
#   usage: tests/bench/verify.sh [PATHS...]   (default: corpus)
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=build/lwcport
[ -x "$bin" ] || { echo "build first: bash .ci/setup" >&2; exit 2; }
command -v python3 > /dev/null || { echo "python3 is missing: apt-get install python3" >&2; exit 2; }
out=tests/bench/work/verify.json
mkdir -p "$(dirname "$out")"
[ $# -gt 0 ] || set -- corpus
python3 - "$bin" "$out" "$@" <<'PY'
import json, math, os, subprocess, sys, time
binary, out, paths = sys.argv[1], sys.argv[2], sys.argv[3:]
started = time.monotonic()
proc = subprocess.Popen([binary, "verify", *paths, "--format", "json", "--fail-on", "none", "--output", out])
tick = os.sysconf("SC_CLK_TCK")
cpu = {}            # pid -> (user + system seconds, is the host)
peak_total = peak_one = 0
def children(pid):
    try:
        with open(f"/proc/{pid}/task/{pid}/children") as f:
            return [int(x) for x in f.read().split()]
    except OSError:
        return []
while proc.poll() is None:
    total = 0
    for pid in [proc.pid] + children(proc.pid):
        try:
            with open(f"/proc/{pid}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
            # PSS: pages the driver processes share with the host (forked from it) and with each
            # other (the driver's libraries) are counted once, split between them; RSS would
            # count them in every process.
            with open(f"/proc/{pid}/smaps_rollup") as f:
                rss = next(int(l.split()[1]) for l in f if l.startswith("Pss:")) // 1024
        except (OSError, StopIteration):
            continue
        cpu[pid] = ((int(fields[11]) + int(fields[12])) / tick, pid == proc.pid)
        total += rss
        peak_one = max(peak_one, rss)
    peak_total = max(peak_total, total)
    time.sleep(0.05)
whole = time.monotonic() - started  # with the driver's start, its probes and the library check
r = json.load(open(out))
t = r["time"]
fns = r["functions"]
variants = sum(len(f["variants"]) for f in fns)
ratios = []
for f in fns:
    base = f["variants"][0]
    if not base["measured"] or not base["nsPerInvocation"]:
        continue
    for v in f["variants"][1:]:
        if v["measured"] and v["nsPerInvocation"]:
            ratios.append(v["nsPerInvocation"] / base["nsPerInvocation"])
host = sum(s for s, is_host in cpu.values() if is_host)
driver = sum(s for s, is_host in cpu.values() if not is_host)
print(f"| device | {r['device']} |")
print("|---|---|")
print(f"| functions / variants | {len(fns)} / {variants} |")
print(f"| wall time, the whole process | {whole:.1f} s ({len(fns) / whole:.2f} functions/s) |")
print(f"| wall time, the functions | {t['wallSeconds']:.1f} s ({t['functionsPerSecond']:.2f} functions/s) |")
print(f"| CPU time | {host + driver:.1f} s: host {host:.1f} s ({100 * host / max(host + driver, 1e-9):.0f}%), "
      f"driver processes {driver:.1f} s |")
for key, label in (("compileSeconds", "glslang (preprocess, compile check, kernel)"),
                   ("pipelineSeconds", "pipelines, JIT and the correctness dispatches"),
                   ("dispatchSeconds", "timed rounds (driver CPU time)")):
    print(f"| {label} | {t[key]:.1f} s |")
print(f"| peak memory (PSS) | {peak_total} MB all processes, {peak_one} MB the largest |")
if ratios:
    geo = math.exp(sum(math.log(x) for x in ratios) / len(ratios))
    print(f"| rewrite / original run time, {len(ratios)} measured rewrites | geometric mean {geo:.2f}, "
          f"range {min(ratios):.2f}-{max(ratios):.2f} |")
PY
