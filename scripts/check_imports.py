#!/usr/bin/env python3
"""Lists the import cycles, of any length, among the files of each crate.

Usage: check_imports.py CRATE_SRC_DIR [CRATE_SRC_DIR ...]

Unit-test modules (`#[cfg(test)] mod …`) are left out. Follows `use crate::…`, `use super::…`,
`use self::…`, `use child::…` (from the file of a module with children), and `crate::…`, `super::…`, `self::…`
and `child::…` paths in code (comments and doc links are ignored), resolving each to
the file that defines the longest matching module path. A cycle is a strongly connected
component of more than one file in that graph (a file that reaches itself through others);
each is printed with one closed path through all of its files. Exits 1 when any crate has
one, so that `.ci/run` can hold every crate to arrows that point one way.
"""

import pathlib
import re
import sys


def main() -> int:
    if len(sys.argv) < 2:
        print("usage: check_imports.py CRATE_SRC_DIR [CRATE_SRC_DIR ...]", file=sys.stderr)
        return 2
    found = 0
    for arg in sys.argv[1:]:
        found += check(pathlib.Path(arg))
    return 1 if found else 0


def cycles(edges):
    """The strongly connected components of more than one file (Tarjan's algorithm, without
    recursion), each sorted, in a stable order."""
    index, low, on, stack, out = {}, {}, set(), [], []
    counter = 0
    for start in sorted(edges):
        if start in index:
            continue
        work = [(start, iter(sorted(edges.get(start, ()))))]
        index[start] = low[start] = counter
        counter += 1
        stack.append(start)
        on.add(start)
        while work:
            v, it = work[-1]
            advanced = False
            for w in it:
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(edges.get(w, ())))))
                    advanced = True
                    break
                if w in on:
                    low[v] = min(low[v], index[w])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
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
    return sorted(out)


def closed_path(comp, edges):
    """One path from the component's first file back to it, through the component (a
    breadth-first search, so the shortest such path), for the message."""
    inside = set(comp)
    first = comp[0]
    prev = {}
    queue = [first]
    while queue:
        v = queue.pop(0)
        for w in sorted(edges.get(v, ())):
            if w not in inside:
                continue
            if w == first:
                path = [v]
                while path[-1] != first:
                    path.append(prev[path[-1]])
                return [first] + path[::-1][1:] + [first] if len(path) > 1 else [first, v, first]
            if w not in prev:
                prev[w] = v
                queue.append(w)
    return comp


def check(root) -> int:
    files = {}
    for p in root.rglob("*.rs"):
        text = p.read_text()
        # Unit-test modules at the end of a file import their parent by `super::*`.
        text = re.split(r"#\[cfg\(test\)\]\s*mod \w+ \{", text)[0]
        code = "\n".join(l.split("//")[0] for l in text.splitlines())
        files[str(p.relative_to(root))] = code

    def modpath(f):
        parts = f[:-3].split("/")
        if parts[-1] in ("mod", "lib"):
            parts = parts[:-1]
        return parts

    def resolve(mp):
        if not mp:
            return "lib.rs"
        for cand in ("/".join(mp) + ".rs", "/".join(mp) + "/mod.rs"):
            if cand in files:
                return cand
        return None

    def longest(base, segs):
        for i in range(len(segs), -1, -1):
            r = resolve(base + segs[:i])
            if r:
                return r
        return None

    def expand(s, out):
        s = s.strip()
        m = re.match(r"^([\w:]*)\{(.*)\}$", s, re.S)
        if not m:
            out.append(s)
            return
        pre, inner, depth, cur = m.group(1), m.group(2), 0, ""
        items = []
        for ch in inner:
            depth += ch == "{"
            depth -= ch == "}"
            if ch == "," and depth == 0:
                items.append(cur)
                cur = ""
            else:
                cur += ch
        items.append(cur)
        for it in items:
            if it.strip():
                expand(pre + it.strip(), out)

    edges = {}
    for f, src in files.items():
        me = modpath(f)
        deps = set()
        for m in re.finditer(r"\buse\s+([^;]+);", src):
            paths = []
            expand(m.group(1), paths)
            for p in paths:
                segs = [x for x in p.split(" as ")[0].split("::") if x]
                if not segs:
                    continue
                if segs[0] == "crate":
                    base, segs = [], segs[1:]
                elif segs[0] == "super":
                    base, segs = me[:-1], segs[1:]
                elif segs[0] == "self":
                    base, segs = me, segs[1:]
                elif resolve(me + segs[:1]):
                    base = me
                else:
                    continue
                r = longest(base, segs)
                if r and r != f:
                    deps.add(r)
        for m in re.finditer(r"\bcrate::([\w:]+)", src):
            r = longest([], m.group(1).split("::"))
            if r and r not in (f, "lib.rs"):
                deps.add(r)
        # Paths in code relative to this module: `super::x::f(..)`, `self::x`, and a child
        # module's items called without a `use` (`avx2::parallax::row(..)` in `simd/mod.rs`).
        for m in re.finditer(r"(?<![\w:])(super|self|[a-z_][a-z0-9_]*)::([\w:]+)", src):
            head, segs = m.group(1), m.group(2).split("::")
            if head == "super":
                base = me[:-1]
            elif head == "self":
                base = me
            elif resolve(me + [head]):
                base, segs = me, [head] + segs
            else:
                continue
            r = longest(base, segs)
            if r and r != f:
                deps.add(r)
        edges[f] = deps
    found = cycles(edges)
    for comp in found:
        print(f"{root}: cycle of {len(comp)} files: {' -> '.join(closed_path(comp, edges))}")
        print(f"    files: {', '.join(comp)}")
    imports = sum(len(d) for d in edges.values())
    print(f"{root}: {len(files)} files, {imports} imports, {len(found)} cycles")
    return len(found)


if __name__ == "__main__":
    sys.exit(main())
