#!/usr/bin/env python3
"""The workspace's structure checks, run by `.ci/run`.

1. Every crate opts into the workspace lints (`[lints] workspace = true`).
2. No import circle between the files of any crate, nor between the
   folders (top-level modules) of any crate.
3. Every top-level module of the core states which others it may use, in
   its doc (`//! May use: load, prepare.` or `//! May use: nothing.`), and
   uses no other. The same holds in the other crates wherever a
   top-level module has such a line.

An import is any path a file names (`use` trees, `crate::`/`super::`/
`self::` paths in code, names brought in by `use` and then used as
`name::item`), resolved to the file that defines the item, through
re-exports (`pub use`) and imports. `mod x;` declarations and the files'
`#[cfg(test)] mod tests` blocks are not imports; comments are ignored.

`python3 scripts/deps.py` prints what is wrong and exits 1, or prints a
line per crate and exits 0; `--graph CRATE` prints the folder graph.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

ITEM = re.compile(
    r"^\s*(?:pub(?:\([^)]*\))?\s+)?(?:unsafe\s+|async\s+|const\s+)*"
    r"(?:fn|struct|enum|trait|const|static|type|union|mod)\s+([A-Za-z_]\w*)",
    re.M,
)
MACRO = re.compile(r"^\s*macro_rules!\s*([A-Za-z_]\w*)", re.M)
USE = re.compile(r"^\s*(pub(?:\([^)]*\))?\s+)?use\s+([^;]+);", re.M)
PATH = re.compile(r"\b((?:crate|super|self)(?:::[A-Za-z_]\w*)+)")
MAY_USE = re.compile(r"^//! May use: (.*?)\.?\s*$", re.M)


def strip(text: str) -> str:
    """Code without comments, string literals and the trailing test module."""
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r'r#+".*?"#+', '""', text, flags=re.S)
    text = re.sub(r'"(?:\\.|[^"\\])*"', '""', text, flags=re.S)
    m = re.search(r"#\[cfg\(test\)\]\s*mod\s+\w+\s*\{", text)
    if m:
        text = text[: m.start()]
    return text


def expand(tree: str) -> list[tuple[list[str], str]]:
    """`a::{b, c::{d as e}}` -> [(['a','b'], 'b'), (['a','c','d'], 'e')]."""
    tree = re.sub(r"\s+as\s+", "@", tree)
    tree = re.sub(r"\s+", "", tree)
    out: list[tuple[list[str], str]] = []

    def walk(prefix: list[str], s: str) -> None:
        depth = 0
        start = 0
        parts = []
        for i, ch in enumerate(s):
            if ch == "{":
                depth += 1
            elif ch == "}":
                depth -= 1
            elif ch == "," and depth == 0:
                parts.append(s[start:i])
                start = i + 1
        parts.append(s[start:])
        for part in parts:
            if not part:
                continue
            if "{" in part:
                head, rest = part.split("{", 1)
                head_segs = [x for x in head.split("::") if x]
                walk(prefix + head_segs, rest[: rest.rfind("}")])
                continue
            alias = None
            if "@" in part:
                part, alias = part.split("@", 1)
            segs = prefix + [x for x in part.split("::") if x]
            if segs and segs[-1] == "self":
                segs = segs[:-1]
            if not segs:
                continue
            out.append((segs, alias or segs[-1]))

    walk([], tree)
    return out


class Crate:
    def __init__(self, name: str, src: Path):
        self.name = name
        self.src = src
        self.modules: dict[tuple[str, ...], Path] = {}
        for f in sorted(src.rglob("*.rs")):
            rel = f.relative_to(src)
            parts = list(rel.with_suffix("").parts)
            if parts[-1] in ("mod", "lib", "main"):
                parts = parts[:-1]
            if rel.parts[0] == "bin":
                continue
            self.modules[tuple(parts)] = f
        self.code = {m: strip(p.read_text()) for m, p in self.modules.items()}
        self.raw = {m: p.read_text() for m, p in self.modules.items()}
        self.items = {
            m: set(ITEM.findall(c)) | set(MACRO.findall(c)) for m, c in self.code.items()
        }
        self.imports: dict[tuple[str, ...], dict[str, list[str]]] = {}
        for m, c in self.code.items():
            imp: dict[str, list[str]] = {}
            for _vis, tree in USE.findall(c):
                for segs, alias in expand(tree):
                    if alias != "_" and segs[-1] != "*":
                        imp[alias] = segs
            self.imports[m] = imp

    def start(self, segs: list[str], here: tuple[str, ...]):
        mod = here
        i = 0
        while i < len(segs) and segs[i] in ("crate", "super", "self"):
            if segs[i] == "crate":
                mod = ()
            elif segs[i] == "super":
                mod = mod[:-1]
            i += 1
        if i == 0:
            first = segs[0]
            if here + (first,) in self.modules:
                mod = here
            elif first in self.imports.get(here, {}):
                return None
            else:
                return None
        return mod, segs[i:]

    def resolve(self, segs: list[str], here: tuple[str, ...], depth: int = 0):
        """The module that defines the item `segs` names from `here`."""
        if depth > 20:
            return None
        started = self.start(segs, here)
        if started is None:
            first = segs[0]
            target = self.imports.get(here, {}).get(first)
            if target is None or target[0] not in ("crate", "super", "self"):
                if here + (first,) in self.modules:
                    return self.walk(here, segs, depth)
                return None
            return self.resolve(target + segs[1:], here, depth + 1)
        mod, rest = started
        return self.walk(mod, rest, depth)

    def walk(self, mod, rest, depth):
        for k, s in enumerate(rest):
            if mod + (s,) in self.modules:
                mod = mod + (s,)
                continue
            if s in self.items.get(mod, set()):
                return mod
            target = self.imports.get(mod, {}).get(s)
            if target is not None and target[0] in ("crate", "super", "self"):
                return self.resolve(target + rest[k + 1 :], mod, depth + 1)
            if target is not None and mod + (target[0],) in self.modules:
                return self.resolve(["self"] + target + rest[k + 1 :], mod, depth + 1)
            return mod
        return mod

    def edges(self) -> dict[tuple[str, ...], set[tuple[str, ...]]]:
        graph: dict[tuple[str, ...], set[tuple[str, ...]]] = {m: set() for m in self.modules}
        for m, c in self.code.items():
            refs: list[list[str]] = []
            for _vis, tree in USE.findall(c):
                refs += [segs for segs, _ in expand(tree) if segs[-1] != "*"]
                for segs, _ in expand(tree):
                    if segs[-1] == "*":
                        refs.append(segs[:-1])
            body = USE.sub("", c)
            refs += [p.split("::") for p in PATH.findall(body)]
            for alias, segs in self.imports[m].items():
                if segs[0] not in ("crate", "super", "self"):
                    continue
                for tail in re.findall(r"\b" + re.escape(alias) + r"((?:::[A-Za-z_]\w*)+)", body):
                    refs.append(segs + tail.split("::")[1:])
            for segs in refs:
                target = self.resolve(segs, m)
                if target is not None and target != m and target in self.modules:
                    if target == m[: len(target)] and not self.items.get(target):
                        continue
                    graph[m].add(target)
        return graph


def sccs(graph):
    index = {}
    low = {}
    stack: list = []
    on = set()
    out = []
    counter = [0]

    def strong(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(graph):
        if v not in index:
            strong(v)
    return out


def cycle_path(graph, comp):
    """One circle through a strongly connected component, for the message."""
    members = set(comp)
    startv = comp[0]
    path = [startv]
    seen = {startv}
    v = startv
    while True:
        nxt = sorted(w for w in graph[v] if w in members)
        back = [w for w in nxt if w == startv]
        if back and len(path) > 1:
            return path + [startv]
        fresh = [w for w in nxt if w not in seen]
        if not fresh:
            return path + [nxt[0] if nxt else startv]
        v = fresh[0]
        seen.add(v)
        path.append(v)


def name(mod):
    return "::".join(mod) or "(root)"


def folder(mod):
    return mod[0] if mod else None


def check_crate(label: str, src: Path) -> list[str]:
    crate = Crate(label, src)
    graph = crate.edges()
    errors = []
    for comp in sccs(graph):
        errors.append(
            f"{label}: import circle between files: "
            + " -> ".join(name(m) for m in cycle_path(graph, comp))
            + (f" (and {len(comp)} files in all: {', '.join(name(m) for m in comp)})"
               if len(comp) > 3 else "")
        )
    fgraph: dict[str, set[str]] = {}
    for m, targets in graph.items():
        a = folder(m)
        if a is None:
            continue
        fgraph.setdefault(a, set())
        for t in targets:
            b = folder(t)
            if b is not None and b != a:
                fgraph[a].add(b)
    for comp in sccs(fgraph):
        errors.append(
            f"{label}: import circle between folders: "
            + " -> ".join(cycle_path(fgraph, comp))
        )
    declared = {}
    for m, path in crate.modules.items():
        if len(m) != 1:
            continue
        found = MAY_USE.search(crate.raw[m])
        if found:
            text = found.group(1).strip()
            allowed = set() if text == "nothing" else {
                x.strip().strip("`") for x in text.split(",") if x.strip()
            }
            declared[m[0]] = allowed
    required = label == "core"
    base = BASE.get(label, set())
    for top, targets in sorted(fgraph.items()):
        if top not in base:
            targets = targets - base
        if top not in declared:
            if required:
                errors.append(
                    f"{label}: {top} does not say what it may use "
                    f"(a `//! May use: ...` line in its doc)"
                )
            continue
        for t in sorted(targets - declared[top]):
            why = sorted(
                name(m) + " -> " + name(x)
                for m, xs in graph.items()
                if folder(m) == top
                for x in xs
                if folder(x) == t
            )
            errors.append(f"{label}: {top} uses {t}, which its doc does not allow ({why[0]})")
        for t in sorted(declared[top] - targets):
            if t not in fgraph:
                errors.append(f"{label}: {top} may use {t}, which is not a module")
            else:
                errors.append(f"{label}: {top} says it may use {t}, but does not")
    return errors, fgraph


def check_lints() -> list[str]:
    errors = []
    members = re.search(r"members\s*=\s*\[([^\]]*)\]", (ROOT / "Cargo.toml").read_text())
    dirs = re.findall(r'"([^"]+)"', members.group(1)) if members else []
    for d in dirs + ["fuzz"]:
        toml = ROOT / d / "Cargo.toml"
        if not toml.exists():
            continue
        text = toml.read_text()
        if not re.search(r"^\[lints\]\s*\nworkspace\s*=\s*true", text, re.M):
            if d == "fuzz":
                continue
            errors.append(f"{d}/Cargo.toml: no `[lints] workspace = true`")
    return errors, dirs


# The base files of a crate: root files every module may use without
# saying so (errors, notices, the portable functions, the geometric types,
# quaternion arithmetic, the random generator). They themselves may use
# only each other.
BASE = {"core": {"error", "notice", "portable", "geom", "rotation", "rng"}}

CRATES = {
    "core": "core/src",
    "session": "session/src",
    "app": "app/src",
    "web": "web/entry/src",
    "python": "python/src",
}


def main() -> int:
    errors, _ = check_lints()
    if len(sys.argv) == 3 and sys.argv[1] == "--graph":
        _, fgraph = check_crate(sys.argv[2], ROOT / CRATES[sys.argv[2]])
        for k in sorted(fgraph):
            print(f"{k}: {', '.join(sorted(fgraph[k])) or '-'}")
        return 0
    for label, src in CRATES.items():
        if not (ROOT / src).exists():
            continue
        errs, fgraph = check_crate(label, ROOT / src)
        errors += errs
        if not errs:
            print(f"{label}: {sum(1 for _ in (ROOT / src).rglob('*.rs'))} files, "
                  f"{len(fgraph)} folders and top-level files, no circle")
    for e in errors:
        print(e)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
