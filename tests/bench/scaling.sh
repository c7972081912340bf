#!/usr/bin/env bash
# How lint's time and memory grow with its input, per shape of input: realistic code in one file
# of 1 to 8 MB (corpus files joined, functions renamed), 1,000 to 16,000 findings on one line,
# and nesting 12,500 to 100,000 deep (parentheses, calls, braces, #if groups). For each step the
# exponent log2(t2/t1) is printed: 1 is linear, 2 quadratic. CPU time (user + system), peak RSS.
#   usage: tests/bench/scaling.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=build/lwcport
work=tests/bench/work/scaling
rm -rf "$work" && mkdir -p "$work"
python3 - "$work" <<'PY'
import glob, re, sys
work = sys.argv[1]
files = sorted(f for f in glob.glob('corpus/**/*.usf', recursive=True) + glob.glob('corpus/**/*.hlsl', recursive=True)
               if '/engine/' not in f and '.fixed.' not in f)
texts = [open(f, encoding='utf-8', errors='replace').read() for f in files]
for mb in (1, 2, 4, 8):
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
echo "| input | size | CPU s | peak MB | exponent (time) |"
echo "|---|---|---|---|---|"
for shape in code line parens calls braces ifs; do
  prev=""
  for f in $(ls "$work"/$shape-*.usf | sort -t- -k2 -n); do
    size=${f##*-}; size=${size%.usf}
    /usr/bin/time -o "$work/time" -f "%U %S %M" "$bin" lint "$f" --format json --fail-on none > /dev/null 2>&1 || true
    read -r user sys rss < "$work/time"
    cpu=$(awk -v u="$user" -v s="$sys" 'BEGIN { printf "%.2f", u + s }')
    exp=$([ -n "$prev" ] && awk -v a="$prev" -v b="$cpu" 'BEGIN { if (a > 0.02) printf "%.2f", log(b / a) / log(2); else print "-" }' || echo "")
    echo "| $shape | $size | $cpu | $((rss / 1024)) | $exp |"
    prev=$cpu
  done
done
