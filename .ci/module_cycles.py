#!/usr/bin/env python3
"""Fail when a crate's modules import each other in a circle.

Usage: module_cycles.py CRATE_DIR...

Each file under CRATE_DIR/src is a module (`a/b.rs` and `a/b/mod.rs` are
`a::b`; `lib.rs`/`main.rs` are the crate root). A module depends on another
when it names it through a `crate::` or `super::` path (in a `use` or in
code), or when it declares it with `mod`. A child naming its parent's (or
an ancestor's) items is not counted: the parent declares the child, so
every child would close a circle with it, and items a parent shares with
its children are the parent's to hold. Circles between siblings (or
cousins) are what this looks for. A path goes to the deepest
module it names (`crate::a::b::item` -> `a::b` when `a/b.rs` exists). The
crate root is left out: it only declares the modules. Exits 1 and prints
every circle found.
"""

import re
import sys
from pathlib import Path

PATH = re.compile(r"\b(crate|super)((?:::[A-Za-z_][A-Za-z0-9_]*)+|::\{)")
USE_GROUP = re.compile(r"\buse\s+(crate|super)::([A-Za-z0-9_:]*)\{([^;]*)\};", re.S)
MOD_DECL = re.compile(r"^\s*(?:pub(?:\([^)]*\))?\s+)?mod\s+([A-Za-z_][A-Za-z0-9_]*)\s*;", re.M)
COMMENT = re.compile(r"//[^\n]*")


def modules(src: Path) -> dict:
    out = {}
    for f in src.rglob("*.rs"):
        parts = list(f.relative_to(src).with_suffix("").parts)
        if parts[-1] == "mod":
            parts = parts[:-1]
        if parts in (["lib"], ["main"]):
            parts = []
        out[tuple(parts)] = f
    return out


def deepest(mods: dict, path: tuple) -> tuple:
    for n in range(len(path), 0, -1):
        if path[:n] in mods:
            return path[:n]
    return ()


INLINE_MOD = re.compile(r"^\s*(?:pub(?:\([^)]*\))?\s+)?mod\s+[A-Za-z_][A-Za-z0-9_]*\s*\{", re.M)


def targets(mods: dict, me: tuple, text: str) -> set:
    text = COMMENT.sub("", text)
    # `super::` inside an inline module (`mod tests { use super::*; }`) is
    # the file's own module, not its parent.
    inline = INLINE_MOD.search(text)
    cut = inline.start() if inline else len(text)
    out = set()
    for part, own in ((text[:cut], False), (text[cut:], True)):
        out |= targets_in(mods, me, part, own)
    for name in MOD_DECL.findall(text):
        child = me + (name,)
        if child in mods:
            out.add(child)
    return out


def targets_in(mods: dict, me: tuple, text: str, inline: bool) -> set:
    paths = []
    for m in USE_GROUP.finditer(text):
        head = m.group(2).strip(":").split("::") if m.group(2).strip(":") else []
        for item in re.split(r"[,\s]+", m.group(3)):
            item = item.strip("{} ")
            if item and item != "self":
                paths.append((m.group(1), head + item.split("::")))
            elif item == "self":
                paths.append((m.group(1), head))
    for m in PATH.finditer(text):
        rest = [p for p in m.group(2).split("::") if p and p != "{"]
        paths.append((m.group(1), rest))
    out = set()
    for root, rest in paths:
        if root == "crate":
            base = []
        else:
            base = list(me) if inline else list(me[:-1])
            while rest and rest[0] == "super":
                base, rest = base[:-1], rest[1:]
        t = deepest(mods, tuple(base + rest))
        if t and me[: len(t)] != t:
            out.add(t)
    return out


def cycles(graph: dict) -> list:
    found, state, stack = [], {}, []

    def visit(n):
        state[n] = 1
        stack.append(n)
        for t in sorted(graph.get(n, ())):
            if state.get(t) == 1:
                found.append(stack[stack.index(t):] + [t])
            elif t not in state:
                visit(t)
        stack.pop()
        state[n] = 2

    for n in sorted(graph):
        if n not in state:
            visit(n)
    return found


def main() -> int:
    bad = 0
    for crate in sys.argv[1:]:
        mods = modules(Path(crate) / "src")
        graph = {m: targets(mods, m, f.read_text()) for m, f in mods.items() if m}
        found = cycles(graph)
        for c in found:
            print(f"{crate}: circle: " + " -> ".join("::".join(m) for m in c))
        if not found:
            print(f"{crate}: {len(graph)} modules, no circle")
        bad += len(found)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
