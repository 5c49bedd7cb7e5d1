#!/usr/bin/env python3
"""Compares the images of two relief-lab runs byte for byte.

Usage: compare_relief_images.py BEFORE_DIR AFTER_DIR

Each directory is a `renderlab relief bench --out DIR` (or a report's `relief/`). Every PNG
under BEFORE_DIR/img must exist under AFTER_DIR/img with identical bytes, after the renames
below (technique names retired in the relief catalogue's rebuild); every PNG of AFTER_DIR
must have a counterpart. Exits 0 when all match, 1 otherwise, listing each difference.
"""

import pathlib
import sys

# Old file-name stem → new one: cone-step refinement became a parameter, the fast cone method
# is named for what it does, and POM's packed vector kernel is a kernel option.
RENAMES = [
    ("cone-secant-", "cone-", "-secant"),
    ("cone-fast-", "cone-newton-", "-simd"),
    ("pom-simd-", "pom-", "-simd"),
    ("pom-packed-", "pom-", "-simd"),
]


def new_name(old: str) -> str:
    stem, _, rest = old.partition("_")  # technique slug, then angle and suffix
    for prefix, new_prefix, suffix in RENAMES:
        if stem.startswith(prefix):
            return new_prefix + stem[len(prefix):] + suffix + "_" + rest
    # `cone:STEPS:BINARY` gained its refinement parameter: `cone:STEPS:BINARY:binary`.
    parts = stem.split("-")
    if parts[0] == "cone" and len(parts) == 3:
        return stem + "-binary_" + rest
    return old


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    before = pathlib.Path(sys.argv[1]) / "img"
    after = pathlib.Path(sys.argv[2]) / "img"
    problems = []
    seen = set()
    olds = sorted(p.name for p in before.glob("*.png"))
    for old in olds:
        new = new_name(old)
        seen.add(new)
        target = after / new
        if not target.exists():
            problems.append(f"missing: {old} (expected {new})")
        elif (before / old).read_bytes() != target.read_bytes():
            problems.append(f"differs: {old} vs {new}")
    for extra in sorted(p.name for p in after.glob("*.png")):
        if extra not in seen:
            problems.append(f"new image without a counterpart: {extra}")
    renamed = sum(1 for o in olds if new_name(o) != o)
    for p in problems:
        print(p)
    print(f"{len(olds)} images compared ({renamed} renamed), {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
