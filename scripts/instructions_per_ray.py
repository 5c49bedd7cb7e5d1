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

With `--by-instruction N` it also says where the instructions go: callgrind counts each
executed instruction (`--dump-instr=yes`), the counts are divided by the rays and joined with
`objdump -d` of the binary (or of Embree's library), and for ours and for Embree's it prints
the instructions grouped by how often they run a ray (a loop's body shares one count: "6.92 x
36" is a 36-instruction block run 6.92 times a ray), largest share first, then the N most
executed instructions with their disassembly:

    scripts/instructions_per_ray.py target/release/examples/profile_set out/embree_bench \\
        out/embree/blob.bin bounce --by-instruction 40

Session 27 found with it that ours and Embree's make the same 6.92 node tests a ray on the
blob's bounce rays, ours at 36 instructions a test and Embree's at 24 (BENCHMARKS.md, Round 12).
"""
import collections
import os
import re
import subprocess
import sys
import tempfile


def collected(cmd, toggles, env=None, by_instruction=False):
    """Instructions callgrind collected inside the `toggles` functions while running `cmd`, what
    `cmd` printed, and with `by_instruction` callgrind's output (each instruction's count; else
    None)."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "callgrind.out")
        args = ["valgrind", "--tool=callgrind", "--collect-atstart=no", f"--callgrind-out-file={out}"]
        if by_instruction:
            args.append("--dump-instr=yes")
        args += [f"--toggle-collect={t}" for t in toggles]
        run = subprocess.run(args + cmd, capture_output=True, text=True, env=env)
        if run.returncode != 0:
            # The program's own messages, without valgrind's.
            said = " ".join(l for l in run.stderr.splitlines() if l and not l.startswith("=="))
            sys.exit(f"instructions_per_ray: {' '.join(cmd)} failed: {said[-500:]}")
        m = re.search(r"Collected : (\d+)", run.stderr)
        if not m:
            sys.exit(f"instructions_per_ray: no count from callgrind for {cmd[0]}")
        text = None
        if by_instruction:
            with open(out) as f:
                text = f.read()
        return int(m.group(1)), run.stdout, text


def counts(text):
    """Executed instructions per address (`Ir`) and the object file of each address."""
    cost = collections.Counter()
    objects = {}
    names = {}
    obj = None
    cur = 0
    after_call = False
    for line in text.splitlines():
        if not line:
            continue
        if line.startswith(("ob=", "cob=")):
            # An object's name comes with its first mention, which may be a callee's (`cob=`);
            # only `ob=` changes the object of the lines that follow.
            m = re.match(r"c?ob=\((\d+)\)(?: (.*))?", line)
            if m:
                if m.group(2):
                    names[m.group(1)] = m.group(2)
                if line.startswith("ob="):
                    obj = names.get(m.group(1))
            continue
        if line.startswith("calls="):
            after_call = True
            continue
        if line[0] not in "0123456789+-*":
            continue
        parts = line.split()
        tok = parts[0]
        if tok.startswith("0x"):
            cur = int(tok, 16)
        elif tok[0] == "+":
            cur += int(tok[1:])
        elif tok[0] == "-":
            cur -= int(tok[1:])
        elif tok != "*":
            continue
        if after_call:
            # The inclusive cost of a call, counted where the callee's instructions are.
            after_call = False
            continue
        if len(parts) >= 3:
            cost[cur] += int(parts[2])
            objects[cur] = obj
    return cost, objects


def disassembly(path, addresses):
    """`objdump -d` text of `path` for each address in `addresses` (as it runs unrelocated)."""
    text = {}
    # Nearby addresses in one call of objdump, distant ones (a library's entry point and its
    # kernel) in separate calls.
    spans = []
    for a in sorted(addresses):
        if spans and a - spans[-1][1] < 65536:
            spans[-1][1] = a
        else:
            spans.append([a, a])
    for lo, hi in spans:
        run = subprocess.run(["objdump", "-d", "--no-show-raw-insn", f"--start-address={lo:#x}",
                              f"--stop-address={hi + 16:#x}", path], capture_output=True, text=True)
        for line in run.stdout.splitlines():
            a, sep, rest = line.strip().partition(":")
            if not sep:
                continue
            try:
                text[int(a, 16)] = rest.strip()
            except ValueError:
                pass
    return text


def report(who, text, rays, listing):
    """The instructions of `text` (callgrind's output with `--dump-instr=yes`) grouped by how
    often they run a ray, largest share first, and the `listing` most executed with their
    disassembly."""
    cost, objects = counts(text)
    print(f"{who}, by instruction:")
    groups = collections.Counter()
    sizes = collections.Counter()
    for a, c in cost.items():
        k = round(c / rays, 2)
        groups[k] += c / rays
        sizes[k] += 1
    for k, share in sorted(groups.items(), key=lambda kv: -kv[1])[:14]:
        print(f"  {k:6.2f} x {sizes[k]:4d} instructions = {share:7.1f} a ray")
    if listing:
        by_object = collections.defaultdict(list)
        for a in cost:
            by_object[objects.get(a)].append(a)
        text = {}
        for obj, addrs in by_object.items():
            if obj and os.path.exists(obj):
                text.update(disassembly(obj, addrs))
        for a, c in sorted(cost.items(), key=lambda kv: -kv[1])[:listing]:
            print(f"  {c / rays:6.2f}  {a:x}: {text.get(a, '?')}")


def main():
    args = sys.argv[1:]
    listing = None
    if "--by-instruction" in args:
        i = args.index("--by-instruction")
        if i + 1 >= len(args) or not args[i + 1].isdigit():
            sys.exit("instructions_per_ray: --by-instruction takes a count of instructions to list")
        listing = int(args[i + 1])
        del args[i:i + 2]
    if len(args) != 4:
        sys.exit("usage: instructions_per_ray.py PROFILE_SET EMBREE_BENCH SCENE.bin SET [--by-instruction N]")
    ours_exe, embree_exe, scene, name = args
    by_instruction = listing is not None
    # A mesh's queries enter at `dispatch::blas`, an instanced scene's at `dispatch::tlas` (whose
    # walk enters the meshes without it): counting both never counts a call twice.
    queries = [f"renderlab_trace::traverse::dispatch::{level}" for level in ("blas", "tlas")]
    ours, printed, ours_text = collected([ours_exe, scene, name, "single", "1"], queries, None, by_instruction)
    # `profile_set` reports the set's size: "SET single: N rays in 1 passes, ...".
    m = re.search(r": (\d+) rays in 1 passes", printed)
    if not m:
        sys.exit(f"instructions_per_ray: {ours_exe} did not report the rays it traced")
    n = int(m.group(1))
    env = dict(os.environ, EMBREE_BENCH_ONLY=f"{name}:1")
    with tempfile.TemporaryDirectory() as tmp:
        # Two passes: the warm-up and one timed pass.
        hits = os.path.join(tmp, "hits")
        embree, _, embree_text = collected(
            [embree_exe, scene, hits, "1"], ["rtcIntersect1", "rtcOccluded1"], env, by_instruction
        )
    a, b = ours / n, embree / (2 * n)
    print(f"{os.path.basename(scene)} {name}: {n} rays; instructions per ray: ours {a:.1f}, "
          f"Embree {b:.1f}, ours / Embree {a / b:.3f}")
    if by_instruction:
        report("ours", ours_text, n, listing)
        report("Embree", embree_text, 2 * n, listing)


if __name__ == "__main__":
    main()
