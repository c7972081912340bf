#!/usr/bin/env bash
# Epic's own UE 4.27 -> 5.x port of its engine shaders as the oracle for lwcport's port (issue 39 §1).
#
#   tests/bench/epic_port.sh [--lwcport BIN] [--out DIR] UE427_SHADERS UE50_SHADERS UE54_SHADERS
#
# The three folders are the engine's shader folder (the one holding Private/ and Public/) at 4.27,
# 5.0 and 5.4. Fetch them yourself from public mirrors; Epic's code is under Epic's EULA and never
# enters this repository, a test, a golden file or a note (file names and counts only). Measured so
# far with Stiiiff/EphemereEngine @ 7dc41e8d (UE 4.27.2, Engine/Shaders), elmachotroso/
# unreal_devtoolbox @ 1c24a3df (UE 5.0.3, Engine/Shaders) and uno1982/Shaders @ 095ea462
# (UE 5.4.3, Shaders), e.g. `git --git-dir=MIRROR archive COMMIT Engine/Shaders | tar -x -C DIR`.
#
# Two targets: the 4.27 files as if they built against 5.4 (oracle: Epic's 5.4.3 files), then
# against 5.0 (oracle: Epic's 5.0.3 files). For each, a scratch COPY of the 4.27 folder is made with
# a `.lwcport.json` of `{"unreal": "5.4"}` (or "5.0") beside it (the fetched tree is never
# written), then `lwcport lint --format json` and `lwcport fix --diff --unsafe-fixes --check-build`
# run on the copy; the fix is also run file by file to learn each file's --check-build outcome.
#
# How a site is counted. Each 4.27 file is paired with the file of the same path in the oracle
# tree (else the one file of that name). The two are compared line by line (Python difflib on the
# lines with // comments removed and blanks collapsed). In each changed block every 4.27 line is
# paired with the block's new line most like it, by the names and numbers they share once the
# port's own changes are taken out of both (types, DF*/LWC*/WS* calls and hack markers dropped,
# `Translated` and `Relative` removed from names, PrimaryView and ResolvedView read as View) and
# words too common to pair by are left out (keywords, View, swizzles, common intrinsics, 0 and 1);
# a pair needs a likeness (Dice coefficient) above 0.4, ties going to the same place in the block. A 4.27 line is a SITE when the new line it
# pairs with brings in a token of one of these spaces (more of them than the old line had):
#   hack        LWCHackToFloat, DFHackToFloat, WSHackToFloat, any *_Hack name
#   df          DoubleFloat or tile/offset: FDF*/FLWC*/FWS* types, DF*(/WS*( calls, LWC* names
#               (LWCAdd(, LWCData, ...), MakeDF*/MakeLWC*, names holding RelativeWorld, PositionHigh, PositionLow, LWCTile
#               or TilePosition (stored relative to a high part or a tile), and PrimaryView alone
#               (its world members are LWC types: FLWC in 5.0-5.3, FDF in 5.4)
#   translated  a name holding `Translated` (TranslatedWorldPosition, LocalToTranslatedWorld,
#               ScreenToTranslatedWorld, ...), or fewer PreViewTranslation terms than before
# checked in that order (DFTransformLocalToTranslatedWorld and DFFastToTranslatedWorld are df, as
# issue 39 counts them). A 4.27 line with no partner is a site too when it names world-space data
# (PreViewTranslation, WorldCameraOrigin, LocalToWorld, WorldPosition, ScreenToWorld, object
# bounds, ...) and its block has at most 20 old lines and brings in one of those spaces (it gets
# the block's space), or when it holds PreViewTranslation and Epic deleted it in a block of at
# most 4 lines (translated). A site's function is the function of the 4.27 file it lies in.
#
# Per site: FLAGGED when a lwcport finding (any rule but lwc-input) spans the 4.27 line;
# REWRITTEN when the fix's diff removes or changes that line; SAME SPACE when lwcport's new text
# for the line (its partner in the diff, paired as above) brings in the space Epic's did. Per
# file, the fixed file's --check-build outcome: "compile" (as the original did), "incomplete"
# (compiles except in code left to port by hand), "held back" (the fix broke the build and was
# withheld), "unchecked" (the original does not compile against lwcport's own Unreal stub, which
# is most engine files: they need the engine's generated headers), or "no fix". Against the stub
# this says little; issue 39 §4 compiles against the engine's own headers.
#
# The 25 files are the ones issue 39 names; the generalisation set is every other 4.27 file with
# at least one site. Prints Markdown for tests/bench/RESULTS.md. With --out DIR, also writes there
# sites.tsv (per site: file, 4.27 line, Epic's space, flagged and by which rules, rewritten, lwcport's
# space) and builds.tsv (per file: the --check-build outcome), which hold no Epic text, and each
# target's lint JSON and fix diff, which do: keep DIR outside the repository. Needs python3.
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
bin=$here/build/lwcport
out=
dirs=()
while (($#)); do
  case "$1" in
    --lwcport) bin=$(realpath "$2"); shift 2 ;;
    --out) out=$(realpath -m "$2"); shift 2 ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) dirs+=("$(realpath "$1")"); shift ;;
  esac
done
((${#dirs[@]} == 3)) || { echo "usage: $0 [--lwcport BIN] [--out DIR] UE427_SHADERS UE50_SHADERS UE54_SHADERS" >&2; exit 2; }
command -v python3 > /dev/null || { echo "$0: needs python3" >&2; exit 2; }
for d in "${dirs[@]}"; do [[ -d $d/Private ]] || { echo "$0: $d has no Private/ folder (give the shader folder itself)" >&2; exit 2; }; done
[[ -x $bin ]] || { echo "$0: no lwcport at $bin (--lwcport BIN)" >&2; exit 2; }
[[ -n $out ]] && mkdir -p "$out"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for target in 5.4 5.0; do
  work=$tmp/$target
  mkdir -p "$work"
  cp -r "${dirs[0]}" "$work/Shaders"
  find "$work/Shaders" -name .lwcport.json -delete  # ours, beside the copy, is the one that applies
  printf '{"unreal": "%s"}\n' "$target" > "$work/.lwcport.json"
  (cd "$work" && "$bin" lint Shaders --format json --fail-on none > lint.json)
  (cd "$work" && "$bin" fix Shaders --diff --unsafe-fixes --check-build --fail-on none > fix.diff 2> fix.txt)
done

python3 - "$bin" "$tmp" "${out:-}" "${dirs[@]}" <<'PY'
import collections, difflib, json, os, re, subprocess, sys

bin_, tmp, out, ue427, ue50, ue54 = sys.argv[1:7]
ISSUE_FILES = ("MaterialTemplate LocalVertexFactory MeshParticleVertexFactory ParticleSpriteVertexFactory "
               "ParticleGPUSpriteVertexFactory VertexFactoryCommon GpuSkinVertexFactory LandscapeVertexFactory "
               "SceneData BasePassVertexShader VelocityShader VolumetricFog VolumetricFogVoxelization VolumetricCloud "
               "SkyAtmosphere HeightFogCommon DeferredLightPixelShaders DeferredLightingCommon ForwardLightingCommon "
               "DeferredDecal DistanceFieldShadowing TranslucentLightInjectionShaders ReflectionEnvironmentShared "
               "LightGridInjection ParticleSimulationShader").split()
SPACES = ("translated", "df", "hack")
SPACE_NAME = {"translated": "translated", "df": "DF/LWC", "hack": "hack"}

# ---- the site classifier (see the header) ----
IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
CALL = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)\s*\(")
WORLDISH = re.compile(r"PreViewTranslation|WorldCameraOrigin|WorldViewOrigin|LocalToWorld|WorldToLocal|ScreenToWorld|"
                      r"SvPositionToWorld|WorldPosition|WorldPos\b|ObjectWorldPosition|ActorWorldPosition|WorldToClip|"
                      r"ClipToWorld|ViewToWorld|WorldToView|PrevWorld|WorldBounds|ObjectBounds")
TYPES = re.compile(r"(?:(?:float|half|int|uint|bool|min16float|FDF|FLWC|FWS)[A-Za-z0-9]*|const|static|in|out|inout)$")
THRESHOLD, UNPAIRED_BLOCK, DELETED_BLOCK = 0.4, 20, 4


def code_of(line):
    i = line.find("//")
    return " ".join((line[:i] if i >= 0 else line).split())


def counts(code):
    c = collections.Counter()
    calls = {m.start(1) for m in CALL.finditer(code)}
    for m in IDENT.finditer(code):
        t = m.group(0)
        if "HackToFloat" in t or t.endswith("_Hack") or t.startswith("LWCHack"):
            c["hack"] += 1
        elif t.startswith(("FDF", "FLWC", "FWS")) or re.match(r"Make(DF|LWC)|LWC[A-Z]", t) or (
                m.start() in calls and re.match(r"(DF|LWC|WS)[A-Z]", t)):
            c["df"] += 1
        elif re.search(r"RelativeWorld|PositionHigh|PositionLow|LWCTile|TilePosition", t):
            c["df"] += 1
        elif "Translated" in t:
            c["translated"] += 1
        elif t == "PrimaryView":
            c["primary"] += 1
        if "PreViewTranslation" in t:
            c["pvt"] += 1
    return c


def space(old, new):
    """The space a replacement brings in, or None."""
    a, b = counts(old), counts(new)
    if b["hack"] > a["hack"]:
        return "hack"
    if b["df"] > a["df"]:
        return "df"
    if b["translated"] > a["translated"] or b["pvt"] < a["pvt"]:
        return "translated"
    if b["primary"] > a["primary"]:
        return "df"
    return None


def pairing_name(t):
    if TYPES.match(t) or "Hack" in t or re.match(r"(DF|LWC|WS|MakeDF|MakeLWC)[A-Z]", t):
        return None
    if t in ("PrimaryView", "ResolvedView"):
        return "View"
    return t.replace("Translated", "").replace("Relative", "") or None


# words too common to pair two lines by
STOP = set("define if else return for View x y z w xy xyz xyzw rgb rgba r g b a mul dot length normalize saturate "
           "max min abs sqrt rsqrt clamp lerp".split())


def tokens(code):
    names = [pairing_name(t) for t in IDENT.findall(code)]
    numbers = [n for n in re.findall(r"\b\d+(?:\.\d*)?\b", code) if n not in ("0", "1", "1.0", "0.0", "1.0f", "0.5")]
    return collections.Counter([t for t in names if t and t not in STOP] + numbers)


def pair(old, new):
    """For each old line, the index of the most alike new line (ties: the same place in the block), or None."""
    tn = [tokens(n) for n in new]
    sn = [sum(t.values()) for t in tn]
    res = []
    for k, o in enumerate(old):
        to = tokens(o)
        so = sum(to.values())
        best, score = None, THRESHOLD
        here = k / max(len(old), 1)
        for j, t in enumerate(tn):
            n = so + sn[j]
            s = (2.0 * sum((to & t).values()) / n if n else 0.0) - 0.01 * abs(j / max(len(new), 1) - here)
            if s > score:
                best, score = j, s
        res.append(best)
    return res


def sites(old_lines, new_lines):
    """{4.27 line (1-based): space Epic moved it to}"""
    a = [code_of(l) for l in old_lines]
    b = [code_of(l) for l in new_lines]
    found = {}
    for tag, i1, i2, j1, j2 in difflib.SequenceMatcher(None, a, b, autojunk=False).get_opcodes():
        if tag == "equal":
            continue
        olds = [i for i in range(i1, i2) if a[i]]
        news = [j for j in range(j1, j2) if b[j]]
        if not olds:
            continue
        block = space(" ".join(a[i] for i in olds), " ".join(b[j] for j in news))
        for i, p in zip(olds, pair([a[i] for i in olds], [b[j] for j in news])):
            s = space(a[i], b[news[p]]) if p is not None else None
            if s:
                found[i + 1] = s
            elif p is None and WORLDISH.search(a[i]) and (
                    (block and len(olds) <= UNPAIRED_BLOCK) or
                    (not news and len(olds) <= DELETED_BLOCK and "PreViewTranslation" in a[i])):
                found[i + 1] = block or "translated"
    return found


def functions(lines):
    """{line: the line its function's body opens on} for the lines of functions, signature and body
    (by brace depth; preprocessor lines skipped; a body is a function's when a call-like name came
    first, so a struct's is not)."""
    res, depth, body, head, seen_call, in_comment, cont = {}, 0, None, 0, False, False, False
    for n, line in enumerate(lines, 1):
        if cont or (not in_comment and line.lstrip().startswith("#")):
            cont = line.rstrip().endswith("\\")
            continue
        text, i = "", 0
        while i < len(line):
            if in_comment:
                j = line.find("*/", i)
                if j < 0:
                    break
                in_comment, i = False, j + 2
            elif line.startswith("/*", i):
                in_comment, i = True, i + 2
            elif line.startswith("//", i):
                break
            else:
                text += line[i]
                i += 1
        for m in re.finditer(r"[A-Za-z_][A-Za-z0-9_]*\s*\(|[{};]", text):
            tok = m.group(0)
            if depth == 0 and tok.endswith("("):
                if not seen_call:
                    head = n
                seen_call = True
            elif tok == "{":
                if depth == 0:
                    body = n if seen_call else None
                    for k in range(head, n) if body else ():
                        res[k] = body  # the signature's lines
                depth += 1
            elif tok == "}":
                depth = max(depth - 1, 0)
                if depth == 0:
                    res[n] = body
                    body, seen_call = None, False
            elif tok == ";" and depth == 0:
                seen_call = False
        if body and n not in res:
            res[n] = body
    return res


# ---- the trees ----
def shader_files(root):
    res = {}
    for d, _, fs in os.walk(root):
        for f in fs:
            if f.endswith((".usf", ".ush")):
                res[os.path.relpath(os.path.join(d, f), root)] = os.path.join(d, f)
    return res


def read(path):
    return open(path, encoding="utf-8", errors="replace").read().splitlines()


old_files = shader_files(ue427)


def counterparts(tree):
    files = shader_files(tree)
    by_name = collections.defaultdict(list)
    for rel in files:
        by_name[os.path.basename(rel)].append(rel)
    res = {}
    for rel in old_files:
        if rel in files:
            res[rel] = files[rel]
        elif len(by_name[os.path.basename(rel)]) == 1:
            res[rel] = files[by_name[os.path.basename(rel)][0]]
    return res


def oracle(tree):
    pairs = counterparts(tree)
    return {rel: sites(read(old_files[rel]), read(new)) for rel, new in sorted(pairs.items())}, len(pairs)


issue = {}
for name in ISSUE_FILES:
    hits = sorted(rel for rel in old_files if os.path.basename(rel).rsplit(".", 1)[0] == name)
    if hits:
        issue[name] = sorted(hits, key=lambda r: (not r.startswith("Private"), r))[0]


# ---- lwcport's side ----
def lwcport(target):
    work = f"{tmp}/{target}"
    lint = json.load(open(f"{work}/lint.json"))
    flagged = collections.defaultdict(lambda: collections.defaultdict(set))  # rel -> line -> rules
    syntax = set()
    for f in lint["findings"]:
        rel = os.path.relpath(f["path"], "Shaders")
        if f["rule"] == "lwc-input":
            if "syntax error" in f["message"]:
                syntax.add(rel)
            continue
        s, e = f["start"]["line"], f["end"]["line"]
        if e > s and f["end"]["column"] == 1:
            e -= 1
        for line in range(s, e + 1):
            flagged[rel][line].add(f["rule"])
    rewritten = collections.defaultdict(dict)  # rel -> old line -> lwcport's space or None
    rel, old_no, group = None, 0, ([], [])

    def flush():
        olds, news = group
        if rel and olds:
            partners = pair([t for _, t in olds], news) if news else [None] * len(olds)
            for (n, t), p in zip(olds, partners):
                rewritten[rel][n] = space(t, news[p] if p is not None else " ".join(news))
        group[0].clear(), group[1].clear()

    for line in open(f"{work}/fix.diff", encoding="utf-8", errors="replace").read().splitlines():
        if line.startswith("--- "):
            flush()
            continue
        if line.startswith("+++ "):
            p = line[4:].split("\t")[0]
            rel = os.path.relpath(p[2:] if p.startswith("b/") else p, "Shaders")
            continue
        m = re.match(r"@@ -(\d+)(?:,\d+)? \+\d+(?:,\d+)? @@", line)
        if m:
            flush()
            old_no = int(m.group(1))
            continue
        if line.startswith("-"):
            if group[1]:
                flush()
            group[0].append((old_no, code_of(line[1:])))
            old_no += 1
        elif line.startswith("+"):
            group[1].append(code_of(line[1:]))
        else:
            flush()
            old_no += 1
    flush()
    summary = open(f"{work}/fix.txt").read()
    return flagged, rewritten, syntax, summary


OUTCOMES = ("compile", "incomplete", "held back", "unchecked")
builds = {}


def build(target, rel):
    key = (target, rel)
    if key not in builds:
        r = subprocess.run([bin_, "fix", os.path.join("Shaders", rel), "--diff", "--unsafe-fixes", "--check-build",
                            "--fail-on", "none"], cwd=f"{tmp}/{target}", capture_output=True, text=True)
        line = [l for l in r.stderr.splitlines() if l.startswith("Build check:")]
        n = [int(x) for x in re.findall(r"(\d+) ", line[0])] if line else [0] * 4
        builds[key] = next((o for o, k in zip(OUTCOMES, n) if k), "no fix")
    return builds[key]


# ---- measuring ----
def measure(target, found, files, rows_out=None):
    flagged, rewritten, syntax, _ = lwcport(target)
    t = collections.Counter()
    missed = collections.Counter()
    rules = collections.Counter()
    per_file = []
    funcs = collections.defaultdict(lambda: [0, 0, 0])  # (file, function) -> sites, flagged, rewritten
    for rel in files:
        s = found.get(rel, {})
        fn = functions(read(old_files[rel]))
        c = collections.Counter()
        old = read(old_files[rel])
        for line, sp in sorted(s.items()):
            c["sites"] += 1
            c[sp] += 1
            fl = line in flagged[rel]
            rw = line in rewritten[rel]
            same = rw and rewritten[rel][line] == sp
            c["flagged"] += fl
            c["rewritten"] += rw
            c["same"] += same
            for r in flagged[rel].get(line, ()):
                rules[r] += 1
            if not fl:
                missed[pattern(code_of(old[line - 1]))] += 1
            f = funcs[(rel, fn.get(line))]
            f[0] += 1
            f[1] += fl
            f[2] += rw
            if rows_out is not None:
                rows_out.append((target, rel, line, sp, int(fl), ",".join(sorted(flagged[rel].get(line, ()))), int(rw),
                                 rewritten[rel].get(line) or "-", int(same), fn.get(line) is not None))
        outcome = build(target, rel) if c["sites"] or rel in issue.values() else "-"
        per_file.append((rel, c, outcome, rel in syntax))
        t.update(c)
        t["files"] += 1
        t["b:" + outcome] += 1
        t["syntax"] += rel in syntax
    inside = {k: v for k, v in funcs.items() if k[1]}
    t["functions"] = len(inside)
    t["f_flagged"] = sum(1 for v in inside.values() if v[1])
    t["f_all_flagged"] = sum(1 for v in inside.values() if v[1] == v[0])
    t["f_rewritten"] = sum(1 for v in inside.values() if v[2])
    t["outside"] = sum(v[0] for k, v in funcs.items() if not k[1])
    return per_file, t, missed, rules


def pattern(code):
    """What kind of world-space code a missed 4.27 line is (own heuristics, for the report)."""
    if re.search(r"\bResolvedView\s*\.\s*\w*(PreViewTranslation|WorldCameraOrigin|WorldViewOrigin)", code):
        return "ResolvedView's world members (pre-view translation, camera origin) in float arithmetic"
    if re.search(r"\bView\s*\.\s*Sky\w*(Origin|PlanetCenter\w*)", code):
        return "sky members (camera origin, planet centre) that UE5 replaced by translated twins"
    if re.search(r"\b\w*View\s*\.\s*\w*(PreViewTranslation|WorldCameraOrigin|WorldViewOrigin)", code):
        return "other view world members in float arithmetic"
    if re.search(r"ScreenToWorld|SvPositionTo\w*World|ClipToWorld|WorldToClip|ViewToWorld|WorldToView|"
                 r"WorldToShadow|WorldToLight\w*|\w*WorldTo\w*Clip|\w*ToWorld\b", code) and not re.search(
                 r"LocalToWorld|ParticleToWorld|OBBToWorld|InstanceToWorld", code):
        return "screen/clip/view/shadow-to-world reconstruction or world-to-clip projection"
    if re.search(r"LocalToWorld|WorldToLocal|ParticleToWorld|WorldToParticle|OBBToWorld|InstanceToWorld|"
                 r"ObjectWorldPosition|ActorWorldPosition|ObjectBounds|BoundingSphere|BoxOrigin|Bounds", code):
        return "object transform, object position or bounds"
    if re.search(r"Light\w*Position|LightPosition|Light\w*Origin", code):
        return "light position or light-relative vector"
    if re.match(r"^(?:[\w<>]+\s+)+\w+(\s*\[[^]]*\])?\s*;$", code):
        return "declaration of a world-space field, local or uniform"
    if re.match(r"^(?:[\w<>]+\s+)+\w+\s*\(.*\)?\s*$", code) and not code.endswith(";"):
        return "function signature taking or returning a world-space value"
    return "a world-space value carried through arithmetic, calls or stores"


def pct(a, b):
    return f"{100.0 * a / b:.0f}%" if b else "-"


def row(name, c, outcome=None, syntax=False):
    sp = " / ".join(str(c[s]) for s in SPACES)
    cells = [name, str(c["sites"]), sp, f"{c['flagged']} ({pct(c['flagged'], c['sites'])})",
             f"{c['rewritten']} ({pct(c['rewritten'], c['sites'])})", f"{c['same']}"]
    if outcome is not None:
        cells.append(outcome + (" (syntax errors)" if syntax else ""))
    return "| " + " | ".join(cells) + " |"


def outcomes(t):
    return ", ".join(f"{t['b:' + o]} {o}" for o in OUTCOMES + ("no fix",) if t["b:" + o])


def report(target, oracle_name, found, npairs, rows):
    issue_rel = [issue[n] for n in ISSUE_FILES if n in issue]
    general = [rel for rel in sorted(found) if found[rel] and rel not in issue_rel]
    per_file, t25, missed25, rules25 = measure(target, found, issue_rel, rows)
    per_gen, tg, missedg, rulesg = measure(target, found, general, rows)
    flagged, rewritten, syntax, summary = lwcport(target)
    print(f"### Target UE {target} (`{{\"unreal\": \"{target}\"}}`), oracle: Epic's {oracle_name} files\n")
    print(f"{len(old_files)} 4.27 shader files, {npairs} with a counterpart in {oracle_name}; "
          f"{sum(1 for v in found.values() if v)} of them hold sites, {sum(len(v) for v in found.values())} sites in all.\n")
    print("| file | sites | translated / DF-LWC / hack | flagged | rewritten | same space as Epic | fixed file, --check-build |")
    print("|---|---|---|---|---|---|---|")
    for rel, c, outcome, syn in per_file:
        print(row(os.path.basename(rel), c, outcome, syn))
    print(row(f"**the {len(issue_rel)} files**", t25, outcomes(t25)))
    print(row(f"**generalisation set ({tg['files']} files)**", tg, outcomes(tg)))
    print()
    for name, t in ((f"the {len(issue_rel)} files", t25), ("the generalisation set", tg)):
        print(f"- {name}: {t['sites']} sites, {t['flagged']} flagged ({pct(t['flagged'], t['sites'])}), "
              f"{t['rewritten']} rewritten ({pct(t['rewritten'], t['sites'])}), {t['same']} rewritten into Epic's space "
              f"({pct(t['same'], t['rewritten'])} of those rewritten); {t['functions']} functions hold sites "
              f"({t['outside']} sites outside functions): {t['f_flagged']} with a site flagged, {t['f_all_flagged']} "
              f"with every site flagged, {t['f_rewritten']} with a site rewritten; {t['syntax']} files with syntax "
              f"errors lwcport could not place")
    print(f"- rules that flag sites (a site may have several): the {len(issue_rel)} files "
          + ", ".join(f"{r} {n}" for r, n in rules25.most_common()) + "; generalisation set "
          + ", ".join(f"{r} {n}" for r, n in rulesg.most_common()))
    print(f"- whole tree, `fix --check-build`: {summary.strip().splitlines()[0]}\n")
    print(f"Sites not flagged, by kind (the {len(issue_rel)} files / generalisation set):\n")
    print("| kind of 4.27 code | the 25 | generalisation |\n|---|---|---|")
    for k in sorted(set(missed25) | set(missedg), key=lambda k: (-(missed25[k] + missedg[k]), k)):
        print(f"| {k} | {missed25[k]} | {missedg[k]} |")
    print()
    return t25, tg


rows = []
o54, n54 = oracle(ue54)
o50, n50 = oracle(ue50)
missing = [n for n in ISSUE_FILES if n not in issue]
if missing:
    print(f"Not found in the 4.27 tree: {', '.join(missing)}\n")
report("5.4", "5.4.3", o54, n54, rows)
report("5.0", "5.0.3", o50, n50, rows)
# the 5.0 target on the 5.4.3 sites, so the two targets compare on one set of lines
issue_rel = [issue[n] for n in ISSUE_FILES if n in issue]
_, t, _, _ = measure("5.0", o54, issue_rel)
_, g, _, _ = measure("5.0", o54, [r for r in sorted(o54) if o54[r] and r not in issue_rel])
print(f"Target 5.0 on the 5.4.3 sites: the {len(issue_rel)} files {t['sites']} sites, {t['flagged']} flagged "
      f"({pct(t['flagged'], t['sites'])}), {t['rewritten']} rewritten, {t['same']} same space; generalisation set "
      f"{g['sites']} sites, {g['flagged']} flagged ({pct(g['flagged'], g['sites'])}), {g['rewritten']} rewritten, "
      f"{g['same']} same space.")
if out:
    with open(os.path.join(out, "sites.tsv"), "w") as f:
        f.write("target\tfile\tline_427\tepic_space\tflagged\trules\trewritten\tlwcport_space\tsame_space\tin_function\n")
        for r in rows:
            f.write("\t".join(str(x) for x in r) + "\n")
    with open(os.path.join(out, "builds.tsv"), "w") as f:
        f.write("target\tfile\tcheck_build\n")
        for (target, rel), o in sorted(builds.items()):
            f.write(f"{target}\t{rel}\t{o}\n")
PY
if [[ -n $out ]]; then
  for target in 5.4 5.0; do
    cp "$tmp/$target/lint.json" "$out/lint-$target.json"
    cp "$tmp/$target/fix.diff" "$out/fix-$target.diff"
    cp "$tmp/$target/fix.txt" "$out/fix-$target.txt"
  done
fi
