#!/usr/bin/env python3
"""Language server benchmark (issue 16 section 4): how long `lwcport lsp` takes to re-diagnose a
5,000-line HLSL file with findings after a one-character edit, against baselines measured in the
same run on the same text (a fresh analysis inside the server, `lwcport lint` and `lwcport parse`
as processes), and its memory with 200 open documents.

Latency is end to end (didChange sent to publishDiagnostics read) and the server's own CPU time
per analysis (from its --log); the baselines are CPU time (user + system), interleaved with the
edits so that load on the shared machine falls on both. Prints Markdown for RESULTS.md.

  usage: tests/bench/lsp.py [--edits N] [--file PATH] [--tree DIR]
         --file: edit this file instead of the generated one; --tree: open 200 files of DIR too
"""
import argparse
import glob
import json
import os
import random
import re
import resource
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = os.path.join(ROOT, "build", "lwcport")
WORK = os.path.join(ROOT, "tests", "bench", "work", "lsp")
SHADERS = (".usf", ".ush", ".hlsl", ".hlsli", ".glsl", ".vert", ".frag", ".comp")


def corpus_files():
    files = []
    for ext in SHADERS:
        files += glob.glob(os.path.join(ROOT, "corpus", "**", "*" + ext), recursive=True)
    return sorted(f for f in files if "/engine/" not in f)


def big_file(path, lines=5000):
    """Corpus HLSL joined until 5,000 lines, each copy's functions renamed, includes removed."""
    texts = [open(f, encoding="utf-8", errors="replace").read() for f in corpus_files() if f.endswith((".usf", ".hlsl"))]
    out, count, k = [], 0, 0
    while count < lines:
        t = re.sub(r"^([A-Za-z_][A-Za-z0-9_<>]* )([A-Za-z_][A-Za-z0-9_]*)\(", lambda m: f"{m.group(1)}{m.group(2)}_{k}(",
                   texts[k % len(texts)], flags=re.M)
        t = re.sub(r"^#include.*$", "", t, flags=re.M)
        out.append(t)
        count += t.count("\n")
        k += 1
    with open(path, "w") as f:
        f.write("".join(out))


class Server:
    def __init__(self, log):
        self.proc = subprocess.Popen([BIN, "lsp", "--log", log], stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        self.next_id = 1

    def send(self, message):
        body = json.dumps(message).encode()
        self.proc.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        self.proc.stdin.flush()

    def read(self):
        length = None
        while True:
            line = self.proc.stdout.readline()
            if not line:
                raise RuntimeError("the server closed its output")
            line = line.strip()
            if not line:
                break
            if line.lower().startswith(b"content-length:"):
                length = int(line.split(b":")[1])
        return json.loads(self.proc.stdout.read(length))

    def request(self, method, params):
        self.next_id += 1
        self.send({"jsonrpc": "2.0", "id": self.next_id, "method": method, "params": params})
        while True:
            m = self.read()
            if m.get("id") == self.next_id:
                return m

    def notify(self, method, params):
        self.send({"jsonrpc": "2.0", "method": method, "params": params})

    def published(self, uri, version):
        while True:
            m = self.read()
            p = m.get("params", {})
            if m.get("method") == "textDocument/publishDiagnostics" and p.get("uri") == uri and p.get("version") == version:
                return p

    def memory_kb(self):
        status = open(f"/proc/{self.proc.pid}/status").read()
        return {k: int(re.search(rf"{k}:\s+(\d+)", status).group(1)) for k in ("VmRSS", "VmHWM")}

    def close(self):
        self.request("shutdown", None)
        self.notify("exit", None)
        self.proc.wait()


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def process_cpu_ms(args):
    before = children_cpu()
    subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return (children_cpu() - before) * 1e3


def percentile(values, p):
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(round(p / 100 * (len(ordered) - 1))))]


def analysis_cpu(log, path):
    """Per version, the server's CPU ms for analysing `path` (the last analysis of each version)."""
    out = {}
    for line in open(log):
        m = re.search(r"analysed (.*) \(version (\d+)\): .* \(CPU ([\d.]+) ms\)", line)
        if m and m.group(1) == path:
            out[int(m.group(2))] = float(m.group(3))
    return out


def rediagnose(edits, given=None, seed=20261123):
    os.makedirs(WORK, exist_ok=True)
    path = os.path.abspath(given) if given else os.path.join(WORK, "Big.usf")
    if not given:
        big_file(path)
    text = open(path, encoding="utf-8", errors="replace").read()
    lines = text.split("\n")
    uri = "file://" + path
    log = os.path.join(WORK, "server.log")
    if os.path.exists(log):
        os.remove(log)
    server = Server(log)
    server.request("initialize", {"capabilities": {}})
    server.notify("initialized", {})
    server.notify("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": "hlsl", "version": 1, "text": text}})
    first = server.published(uri, 1)
    # Lines inside function bodies (indented), where a user types most.
    inside = [i for i, l in enumerate(lines) if l.startswith(("\t", "  ")) and l.strip()]
    random.seed(seed)
    latency, fresh, lint_cpu, parse_cpu = [], [], [], []
    version = 1
    for i in range(edits):
        line = random.choice(inside)
        # One character typed, then taken back: the text stays the file's.
        for change in ({"range": {"start": {"line": line, "character": 1}, "end": {"line": line, "character": 1}}, "text": " "},
                       {"range": {"start": {"line": line, "character": 1}, "end": {"line": line, "character": 2}}, "text": ""}):
            version += 1
            start = time.perf_counter()
            server.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": version}, "contentChanges": [change]})
            server.published(uri, version)
            latency.append((time.perf_counter() - start) * 1e3)
        if i % 20 == 0:  # the baselines, interleaved
            lint_cpu.append(process_cpu_ms([BIN, "lint", path, "--format", "json", "--fail-on", "none"]))
            parse_cpu.append(process_cpu_ms([BIN, "parse", path]))
            # A fresh analysis in the server: the document closed and opened again (no tree to edit).
            server.notify("textDocument/didClose", {"textDocument": {"uri": uri}})
            version += 1
            server.notify("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": "hlsl", "version": version, "text": text}})
            server.published(uri, version)
            fresh.append(version)
    server.close()
    cpu = analysis_cpu(log, path)
    fresh_cpu = [cpu[v] for v in fresh if v in cpu]
    edit_cpu = [c for v, c in cpu.items() if v not in fresh and v != 1]
    return {"lines": len(lines), "findings": len(first["diagnostics"]), "latency": latency, "edit_cpu": edit_cpu,
            "fresh_cpu": fresh_cpu, "lint_cpu": lint_cpu, "parse_cpu": parse_cpu}


def open_many(files, count=200):
    log = os.path.join(WORK, "memory.log")
    server = Server(log)
    server.request("initialize", {"capabilities": {}})
    before = server.memory_kb()
    for i in range(count):
        f = files[i % len(files)]
        # Each document its own URI (a copy beside the original keeps its includes and config).
        uri = "file://" + (f if i < len(files) else f"{f}.copy{i // len(files)}{os.path.splitext(f)[1]}")
        lang = "glsl" if f.endswith((".glsl", ".vert", ".frag", ".comp")) else "hlsl"
        text = open(f, encoding="utf-8", errors="replace").read()
        server.notify("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": lang, "version": 1, "text": text}})
        server.published(uri, 1)
    after = server.memory_kb()
    server.close()
    return before, after


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--edits", type=int, default=150)
    parser.add_argument("--file", help="a file to edit instead of the generated one (not changed on disk)")
    parser.add_argument("--tree", help="a shader tree to open 200 documents of")
    args = parser.parse_args()
    r = rediagnose(args.edits, args.file)
    ms = lambda v: f"{v:.1f}"
    print(f"Re-diagnose after a one-character edit inside a function, {r['lines']}-line HLSL file"
          f"{' (' + os.path.basename(args.file) + ')' if args.file else ''}, {r['findings']} findings, "
          f"{len(r['latency'])} edits:\n")
    print("| measure | p50 ms | p90 ms | p99 ms | max ms |")
    print("|---|---|---|---|---|")
    for name, v in (("end to end (wall, didChange to publishDiagnostics)", r["latency"]), ("server CPU per re-analysis", r["edit_cpu"])):
        print(f"| {name} | {ms(percentile(v, 50))} | {ms(percentile(v, 90))} | {ms(percentile(v, 99))} | {ms(max(v))} |")
    print("\nBaselines on the same text, interleaved (CPU ms, median):\n")
    print("| baseline | CPU ms | re-analysis p50 / baseline |")
    print("|---|---|---|")
    p50 = percentile(r["edit_cpu"], 50)
    for name, v in (("fresh analysis in the server (no tree to edit)", r["fresh_cpu"]), ("`lwcport lint` (process)", r["lint_cpu"]),
                    ("`lwcport parse` (process, parse only)", r["parse_cpu"])):
        m = statistics.median(v)
        print(f"| {name} | {ms(m)} | {p50 / m:.2f} |")
    sets = [("corpus", corpus_files())]
    if args.tree:
        tree = sorted(f for ext in SHADERS for f in glob.glob(os.path.join(args.tree, "**", "*" + ext), recursive=True))
        sets.append((args.tree, tree))
    print("\nMemory with 200 open documents (the server's resident set):\n")
    print("| documents from | distinct files | RSS before MB | RSS after MB | peak MB |")
    print("|---|---|---|---|---|")
    for name, files in sets:
        before, after = open_many(files)
        print(f"| {name} | {min(200, len(files))} | {before['VmRSS'] / 1024:.0f} | {after['VmRSS'] / 1024:.0f} | {after['VmHWM'] / 1024:.0f} |")


if __name__ == "__main__":
    sys.exit(main())
