#!/usr/bin/env bash
# How lint's time and memory grow with its input, per shape of input: realistic code in one file
# of 1 to 16 MB (corpus files joined, functions renamed), 1,000 to 16,000 findings on one line,
# and nesting 12,500 to 100,000 deep (parentheses, calls, braces, #if groups). CPU time (user +
# system) and peak RSS of `lint --format json`, each the median of ROUNDS runs; the rounds are
# interleaved (every input once, then again), so a busy spell on the machine touches every size.
# For each step the exponent log2(b/a) is printed for time and memory (1 is linear, 2 quadratic),
# and for each shape the exponent fitted over all its sizes (least squares on log-log; for time,
# over the sizes that take more than 0.02 s, the timer's resolution).
#   usage: [LWCPORT=BIN] tests/bench/scaling.sh [ROUNDS]   (default 3 rounds)
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=${LWCPORT:-build/lwcport}  # LWCPORT=another/build/lwcport measures that one
rounds=${1:-3}
work=tests/bench/work/scaling
rm -rf "$work" && mkdir -p "$work"
echo '{"max-file-bytes": 67108864}' > "$work/.lwcport.json"  # the 16 MB input is past the default limit
python3 - "$work" <<'PY'
import glob, re, sys
work = sys.argv[1]
files = sorted(f for f in glob.glob('corpus/**/*.usf', recursive=True) + glob.glob('corpus/**/*.hlsl', recursive=True)
               if '/engine/' not in f and '.fixed.' not in f)
texts = [open(f, encoding='utf-8', errors='replace').read() for f in files]
for mb in (1, 2, 4, 8, 16):
    out, size, k = [], 0, 0
    while size < mb << 20:
        t = re.sub(r'^([A-Za-z_][A-Za-z0-9_<>]* )([A-Za-z_][A-Za-z0-9_]*)\(', lambda m: f'{m.group(1)}{m.group(2)}_{k}(',
                   texts[k % len(texts)], flags=re.M)
        t = re.sub(r'^#include.*$', '', t, flags=re.M)
        out.append(t); size += len(t); k += 1
    open(f'{work}/code-{mb}.usf', 'w').write(''.join(out))
for n in (1000, 2000, 4000, 8000, 16000):
    open(f'{work}/line-{n}.usf', 'w').write('float3 F() { return ' + ' + '.join(['View.WorldCameraOrigin'] * n) + '; }\n')
for n in (12500, 25000, 50000, 100000):
    open(f'{work}/parens-{n}.usf', 'w').write('float F() { return ' + '(' * n + '1' + ')' * n + '; }\n')
    open(f'{work}/calls-{n}.usf', 'w').write('float F() { return ' + 'f(' * n + '1' + ')' * n + '; }\n')
    open(f'{work}/braces-{n}.usf', 'w').write('void F() ' + '{' * n + '}' * n + '\n')
    open(f'{work}/ifs-{n}.usf', 'w').write('#if A\n' * n + 'float x;\n' + '#endif\n' * n)
PY
shapes="code line parens calls braces ifs"
for ((r = 0; r < rounds; ++r)); do
  for shape in $shapes; do
    for f in "$work"/$shape-*.usf; do
      /usr/bin/time -o "$work/time" -f "%U %S %M" "$bin" lint "$f" --format json --fail-on none > /dev/null 2>&1 || true
      echo "$shape $(basename "$f" .usf | cut -d- -f2) $(cat "$work/time")" >> "$work/runs"
    done
  done
done
python3 - "$work/runs" <<'PY'
import collections, math, statistics, sys
runs = collections.defaultdict(list)
for line in open(sys.argv[1]):
    shape, size, user, sys_, rss = line.split()
    runs[(shape, int(size))].append((float(user) + float(sys_), int(rss) / 1024))
def fit(xs, ys, floor=0):  # the slope of log(y) over log(x), over the points above the floor ("-": too few)
    points = [(math.log(x), math.log(y)) for x, y in zip(xs, ys) if y > floor]
    if len(points) < 2:
        return "-"
    mx, my = statistics.mean(p[0] for p in points), statistics.mean(p[1] for p in points)
    return f"{sum((a - mx) * (b - my) for a, b in points) / sum((a - mx) ** 2 for a, _ in points):.2f}"
print("| input | size | CPU s | peak MB | exponent (time) | exponent (memory) |")
print("|---|---|---|---|---|---|")
for shape in dict.fromkeys(s for s, _ in runs):
    sizes = sorted(n for s, n in runs if s == shape)
    cpu = [statistics.median(t for t, _ in runs[(shape, n)]) for n in sizes]
    mem = [statistics.median(m for _, m in runs[(shape, n)]) for n in sizes]
    for i, n in enumerate(sizes):
        step = lambda v: f"{math.log(v[i] / v[i - 1], sizes[i] / sizes[i - 1]):.2f}" if i and v[i - 1] > 0.02 else ""
        print(f"| {shape} | {n} | {cpu[i]:.2f} | {mem[i]:.0f} | {step(cpu)} | {step(mem)} |")
    print(f"| {shape} | fitted {sizes[0]}-{sizes[-1]} | | | {fit(sizes, cpu, 0.02)} | {fit(sizes, mem)} |")
PY
