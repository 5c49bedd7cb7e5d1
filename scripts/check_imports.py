#!/usr/bin/env python3
"""Lists pairs of files of a crate that import each other.

Usage: check_imports.py CRATE_SRC_DIR

Unit-test modules (`#[cfg(test)] mod …`) are left out. Follows `use crate::…`, `use super::…`, `use self::…`, `use child::…` (from a module's own
file) and `crate::…` paths in code (comments and doc links are ignored), resolving each to
the file that defines the longest matching module path. Exits 1 when a pair imports each
other, printing the pairs.
"""

import pathlib
import re
import sys


def main() -> int:
    if len(sys.argv) != 2:
        print("usage: check_imports.py CRATE_SRC_DIR", file=sys.stderr)
        return 2
    root = pathlib.Path(sys.argv[1])
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
                elif resolve(me + segs[:1]) and (f.endswith("mod.rs") or f == "lib.rs"):
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
        edges[f] = deps
    pairs = sorted((a, b) for a in edges for b in edges[a] if a < b and a in edges.get(b, ()))
    for a, b in pairs:
        print(f"{a} <-> {b}")
    print(f"{len(files)} files, {sum(len(d) for d in edges.values())} imports, {len(pairs)} mutual pairs")
    return 1 if pairs else 0


if __name__ == "__main__":
    sys.exit(main())
