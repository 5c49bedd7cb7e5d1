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

Ours is counted from the entry of `renderlab_trace::traverse::dispatch::blas` (or `::tlas` for
an instanced scene), Embree's from `rtcIntersect1` / `rtcOccluded1`: both include their
library's dispatch to the kernel. A count is not a time (session 25 cut instructions without
making rays faster), but it moves only when the code does.
"""
import os
import re
import struct
import subprocess
import sys
import tempfile


def ray_count(scene, name):
    """The number of rays in set `name` of a scene file, and whether the scene is instanced."""
    with open(scene, "rb") as f:
        data = f.read()
    magic = data[:8]
    if magic not in (b"RLTRACE1", b"RLTRACE2"):
        sys.exit(f"instructions_per_ray: {scene} is not a scene file")
    nv, nt = struct.unpack_from("<II", data, 8)
    at = 16 + 12 * nv + 12 * nt
    instanced = magic == b"RLTRACE2"
    if instanced:
        (ninst,) = struct.unpack_from("<I", data, at)
        at += 4 + 48 * ninst
    (nsets,) = struct.unpack_from("<I", data, at)
    at += 4
    names = []
    for _ in range(nsets):
        set_name = data[at:at + 16].rstrip(b"\0").decode()
        _flags, n = struct.unpack_from("<II", data, at + 16)
        if set_name == name:
            return n, instanced
        names.append(set_name)
        at += 24 + 32 * n
    sys.exit(f"instructions_per_ray: no set `{name}` in {scene} (it has {names})")


def collected(cmd, toggles, env=None):
    """Instructions callgrind collected inside the `toggles` functions while running `cmd`."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "callgrind.out")
        args = ["valgrind", "--tool=callgrind", "--collect-atstart=no", f"--callgrind-out-file={out}"]
        args += [f"--toggle-collect={t}" for t in toggles]
        run = subprocess.run(args + cmd, capture_output=True, text=True, env=env)
        if run.returncode != 0:
            sys.exit(f"instructions_per_ray: {' '.join(cmd)} failed:\n{run.stderr[-2000:]}")
        m = re.search(r"Collected : (\d+)", run.stderr)
        if not m:
            sys.exit(f"instructions_per_ray: no count from callgrind for {cmd[0]}")
        return int(m.group(1))


def main():
    if len(sys.argv) != 5:
        sys.exit("usage: instructions_per_ray.py PROFILE_SET EMBREE_BENCH SCENE.bin SET")
    ours_exe, embree_exe, scene, name = sys.argv[1:]
    n, instanced = ray_count(scene, name)
    query = "renderlab_trace::traverse::dispatch::tlas" if instanced else "renderlab_trace::traverse::dispatch::blas"
    ours = collected([ours_exe, scene, name, "single", "1"], [query])
    env = dict(os.environ, EMBREE_BENCH_ONLY=f"{name}:1")
    with tempfile.TemporaryDirectory() as tmp:
        # Two passes: the warm-up and one timed pass.
        embree = collected([embree_exe, scene, os.path.join(tmp, "hits"), "1"], ["rtcIntersect1", "rtcOccluded1"], env)
    a, b = ours / n, embree / (2 * n)
    print(f"{os.path.basename(scene)} {name}: {n} rays; instructions per ray: ours {a:.1f}, "
          f"Embree {b:.1f}, ours / Embree {a / b:.3f}")


if __name__ == "__main__":
    main()
