#!/usr/bin/env python3
"""Instructions per single-ray query, ours against Embree's, counted exactly by callgrind.

Timing on a shared machine drifts by several per cent; an instruction count does not. This
runs the trace crate's `profile_set` example (one pass of single-ray queries over one ray set)
and the Embree program (`scripts/embree_bench`, the same set through `rtcIntersect1` or
`rtcOccluded1`: its warm-up pass and one timed pass) under `valgrind --tool=callgrind`,
collecting only inside the query functions, and prints the instructions each spends per ray.

    scripts/instructions_per_ray.py PROFILE_SET EMBREE_BENCH SCENE.bin SET

Example (from the repository root, after the `embree` example has written the scenes):

    cargo build --release -p renderlab-trace --example profile_set
    scripts/instructions_per_ray.py target/release/examples/profile_set out/embree_bench \\
        out/embree/blob.bin bounce

Ours is counted from the entry of `renderlab_trace::traverse::dispatch::blas` or `::tlas` (an
instanced scene's), Embree's from `rtcIntersect1` / `rtcOccluded1`: both include their
library's dispatch to the kernel. A count is not a time (session 25 cut instructions without
making rays faster), but it moves only when the code does.
"""
import os
import re
import subprocess
import sys
import tempfile


def collected(cmd, toggles, env=None):
    """Instructions callgrind collected inside the `toggles` functions while running `cmd`, and
    what `cmd` printed."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "callgrind.out")
        args = ["valgrind", "--tool=callgrind", "--collect-atstart=no", f"--callgrind-out-file={out}"]
        args += [f"--toggle-collect={t}" for t in toggles]
        run = subprocess.run(args + cmd, capture_output=True, text=True, env=env)
        if run.returncode != 0:
            # The program's own messages, without valgrind's.
            said = " ".join(l for l in run.stderr.splitlines() if l and not l.startswith("=="))
            sys.exit(f"instructions_per_ray: {' '.join(cmd)} failed: {said[-500:]}")
        m = re.search(r"Collected : (\d+)", run.stderr)
        if not m:
            sys.exit(f"instructions_per_ray: no count from callgrind for {cmd[0]}")
        return int(m.group(1)), run.stdout


def main():
    if len(sys.argv) != 5:
        sys.exit("usage: instructions_per_ray.py PROFILE_SET EMBREE_BENCH SCENE.bin SET")
    ours_exe, embree_exe, scene, name = sys.argv[1:]
    # A mesh's queries enter at `dispatch::blas`, an instanced scene's at `dispatch::tlas` (whose
    # walk enters the meshes without it): counting both never counts a call twice.
    queries = [f"renderlab_trace::traverse::dispatch::{level}" for level in ("blas", "tlas")]
    ours, printed = collected([ours_exe, scene, name, "single", "1"], queries)
    # `profile_set` reports the set's size: "SET single: N rays in 1 passes, ...".
    m = re.search(r": (\d+) rays in 1 passes", printed)
    if not m:
        sys.exit(f"instructions_per_ray: {ours_exe} did not report the rays it traced")
    n = int(m.group(1))
    env = dict(os.environ, EMBREE_BENCH_ONLY=f"{name}:1")
    with tempfile.TemporaryDirectory() as tmp:
        # Two passes: the warm-up and one timed pass.
        hits = os.path.join(tmp, "hits")
        embree, _ = collected([embree_exe, scene, hits, "1"], ["rtcIntersect1", "rtcOccluded1"], env)
    a, b = ours / n, embree / (2 * n)
    print(f"{os.path.basename(scene)} {name}: {n} rays; instructions per ray: ours {a:.1f}, "
          f"Embree {b:.1f}, ours / Embree {a / b:.3f}")


if __name__ == "__main__":
    main()
