#!/usr/bin/env bash
# lwcport on real shader trees (public repositories you fetched yourself; never commit them): per
# tree, files, bytes, files with syntax errors, findings and fixes per rule, and what
# `fix --check-build` says of the fixes (safe ones alone, then safe and unsafe together).
#
#   tests/bench/realworld.sh [--lwcport BIN] [--lang hlsl|glsl] DIR...
#
# A tree's own .lwcport.json applies as it would for its users (put one beside it to say which
# engine it builds against, or which extensions are shaders). Needs python3 to total the JSON.
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=build/lwcport
extra=()
dirs=()
while (($#)); do
  case "$1" in
    --lwcport) bin=$2; shift 2 ;;
    --lang) extra+=(--lang "$2"); shift 2 ;;
    *) dirs+=("$1"); shift ;;
  esac
done
((${#dirs[@]})) || { echo "usage: $0 [--lwcport BIN] [--lang hlsl|glsl] DIR..." >&2; exit 2; }
command -v python3 > /dev/null || { echo "$0: needs python3 to total the JSON reports" >&2; exit 2; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for dir in "${dirs[@]}"; do
  "$bin" parse "${extra[@]}" "$dir" > "$tmp/parse.txt" || true
  "$bin" lint "${extra[@]}" "$dir" --format json --fail-on none > "$tmp/lint.json"
  "$bin" fix "${extra[@]}" "$dir" --diff --check-build --fail-on none > /dev/null 2> "$tmp/safe.txt"
  "$bin" fix "${extra[@]}" "$dir" --diff --check-build --unsafe-fixes --fail-on none > /dev/null 2> "$tmp/unsafe.txt"
  python3 - "$dir" "$tmp" <<'EOF'
import collections, json, re, sys
tree, tmp = sys.argv[1], sys.argv[2]
parse = open(f"{tmp}/parse.txt").read().strip().splitlines()[-1]
lint = json.load(open(f"{tmp}/lint.json"))
files = lint["files"]
nbytes = re.search(r"(\d+) bytes", parse).group(1)
syntax = {f["path"] for f in lint["findings"] if f["rule"] == "lwc-input" and "syntax error" in f["message"]}
findings, safe, unsafe = collections.Counter(), collections.Counter(), collections.Counter()
for f in lint["findings"]:
    if f["rule"] == "lwc-input":
        continue
    findings[f["rule"]] += 1
    if "fix" in f:
        (safe if f["fix"]["applicability"] == "safe" else unsafe)[f["rule"]] += 1
def build(name):
    line = [l for l in open(f"{tmp}/{name}.txt") if l.startswith("Build check:")]
    if not line:
        return "no fix"
    n = [int(x) for x in re.findall(r"(\d+) ", line[0])]
    return f"{n[0]} compile, {n[1]} incomplete, {n[2]} break, {n[3]} unchecked"
print(f"## {tree}\n")
print(f"{files} files, {nbytes} bytes, {len(syntax)} with syntax errors ({100.0 * len(syntax) / max(files, 1):.1f}%)\n")
print("| rule | findings | safe fixes | unsafe fixes |\n|---|---|---|---|")
for rule in sorted(findings):
    print(f"| {rule} | {findings[rule]} | {safe[rule]} | {unsafe[rule]} |")
print(f"\nfix --check-build, safe fixes: {build('safe')}; safe and unsafe: {build('unsafe')}\n")
EOF
done
