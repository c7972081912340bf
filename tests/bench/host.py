#!/usr/bin/env python3
"""lwcport host's speed (issue 18 section 5): CPU time of `lwcport host` on translation units of a
real codebase against `clang++ -fsyntax-only` on the same units with the same compile commands,
measured in the same run. Each unit is parsed by both, one after the other, so load on the shared
machine falls on both; CPU time is user + system of each child process (os.wait4). Prints a
Markdown table for RESULTS.md.

  usage: tests/bench/host.py BUILD_DIR [--units N] [--every K] [--lwcport-host PATH] [--clang PATH]
         BUILD_DIR holds compile_commands.json; every K-th C++ unit (sorted by path) is measured,
         at most N of them.
"""
import argparse
import json
import os
import shlex
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def cpu_of(argv, cwd):
    """CPU seconds (user + system) of a child, and its exit status."""
    with open(os.devnull, "wb") as null:
        proc = subprocess.Popen(argv, cwd=cwd, stdout=null, stderr=null)
        _, status, usage = os.wait4(proc.pid, 0)
    return usage.ru_utime + usage.ru_stime, os.waitstatus_to_exitcode(status)


def syntax_only(entry, clang):
    """The unit's compile command with the output dropped and -fsyntax-only instead of -c."""
    argv = entry["arguments"] if "arguments" in entry else shlex.split(entry["command"])
    out, skip = [clang], False
    for a in argv[1:]:
        if skip:
            skip = False
            continue
        if a in ("-o", "-MF", "-MT", "-MQ"):
            skip = True
            continue
        if a in ("-c", "-MD", "-MMD"):
            continue
        out.append(a)
    return out + ["-fsyntax-only"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build_dir")
    ap.add_argument("--units", type=int, default=20)
    ap.add_argument("--every", type=int, default=1)
    ap.add_argument("--lwcport-host", default=os.path.join(HERE, "../../build/lwcport-host"))
    ap.add_argument("--clang", default="/usr/lib/llvm-19/bin/clang++")
    args = ap.parse_args()
    db = json.load(open(os.path.join(args.build_dir, "compile_commands.json")))
    cpp = sorted((e for e in db if e["file"].endswith((".cpp", ".cc", ".cxx"))), key=lambda e: e["file"])
    units = cpp[:: args.every][: args.units]
    total_clang = total_host = 0.0
    rows = []
    for entry in units:
        path = entry["file"] if os.path.isabs(entry["file"]) else os.path.join(entry["directory"], entry["file"])
        clang_cpu, clang_rc = cpu_of(syntax_only(entry, args.clang), entry["directory"])
        # From the project's root (the build folder's parent), as a user runs it: its headers are reported on too.
        host_cpu, host_rc = cpu_of([args.lwcport_host, "host", "-p", os.path.abspath(args.build_dir), path, "--fail-on", "none", "-j", "1"],
                                   os.path.dirname(os.path.abspath(args.build_dir)))
        if clang_rc != 0 or host_rc != 0:
            print(f"skipped {path}: clang exit {clang_rc}, lwcport host exit {host_rc}", file=sys.stderr)
            continue
        total_clang += clang_cpu
        total_host += host_cpu
        rows.append((os.path.relpath(path, os.path.dirname(os.path.abspath(args.build_dir))), clang_cpu, host_cpu))
    print(f"| units | clang -fsyntax-only CPU s | lwcport host CPU s | ratio |")
    print(f"|---|---|---|---|")
    ratio = total_host / total_clang if total_clang else float("nan")
    print(f"| {len(rows)} of {len(cpp)} | {total_clang:.1f} | {total_host:.1f} | {ratio:.2f} |")
    worst = max(rows, key=lambda r: r[2] / r[1]) if rows else None
    if worst:
        print(f"\nslowest relative unit: {worst[0]} ({worst[2] / worst[1]:.2f}x)")


if __name__ == "__main__":
    main()
