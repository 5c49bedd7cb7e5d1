#!/usr/bin/env python3
"""Where a single-ray query's instructions go, instruction by instruction, ours and Embree's.

`instructions_per_ray.py` gives one total per ray. This runs the same two programs under
`valgrind --tool=callgrind --dump-instr=yes`, reads each executed instruction's count, divides
it by the rays, and joins it with `objdump -d` of the binary (or of Embree's library), so that
the counts say what the code does: how many node tests a ray makes (the count of the node
test's instructions), how many instructions a node test takes, how many run once a ray.

    scripts/instruction_profile.py PROFILE_SET EMBREE_BENCH SCENE.bin SET [--list N]

It prints, for ours and for Embree's, the total per ray and the instructions grouped by how
often they run per ray (a loop's body shares one count: "6.92 x 36" is a 36-instruction block
run 6.92 times a ray), largest share first; with `--list N`, the N most executed instructions
with their disassembly. Example (from the repository root, after the `embree` example has
written the scenes and `cc -O2 -o out/embree_bench scripts/embree_bench/embree_bench.c
-lembree3 -lm`):

    cargo build --release -p renderlab-trace --example profile_set
    scripts/instruction_profile.py target/release/examples/profile_set out/embree_bench \\
        out/embree/blob.bin bounce

Session 27 found with it that ours and Embree's make the same 6.92 node tests a ray on the
blob's bounce rays, ours at 36 instructions a test and Embree's at 24 (BENCHMARKS.md, Round 12).
"""
import collections
import os
import re
import subprocess
import sys
import tempfile


def run_callgrind(cmd, toggles, env=None):
    """The callgrind output file's text for `cmd`, collecting inside `toggles`, and what `cmd`
    printed."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "callgrind.out")
        args = ["valgrind", "--tool=callgrind", "--dump-instr=yes", "--collect-atstart=no",
                f"--callgrind-out-file={out}"]
        args += [f"--toggle-collect={t}" for t in toggles]
        run = subprocess.run(args + cmd, capture_output=True, text=True, env=env)
        if run.returncode != 0:
            said = " ".join(l for l in run.stderr.splitlines() if l and not l.startswith("=="))
            sys.exit(f"instruction_profile: {' '.join(cmd)} failed: {said[-500:]}")
        with open(out) as f:
            return f.read(), run.stdout


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
    cost, objects = counts(text)
    total = sum(cost.values()) / rays
    print(f"{who}: {total:.1f} instructions a ray")
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
    listing = 0
    if "--list" in args:
        i = args.index("--list")
        listing = int(args[i + 1])
        del args[i:i + 2]
    if len(args) != 4:
        sys.exit("usage: instruction_profile.py PROFILE_SET EMBREE_BENCH SCENE.bin SET [--list N]")
    ours_exe, embree_exe, scene, name = args
    queries = [f"renderlab_trace::traverse::dispatch::{level}" for level in ("blas", "tlas")]
    text, printed = run_callgrind([ours_exe, scene, name, "single", "1"], queries)
    m = re.search(r": (\d+) rays in 1 passes", printed)
    if not m:
        sys.exit(f"instruction_profile: {ours_exe} did not report the rays it traced")
    rays = int(m.group(1))
    report("ours", text, rays, listing)
    env = dict(os.environ, EMBREE_BENCH_ONLY=f"{name}:1")
    with tempfile.TemporaryDirectory() as tmp:
        # Two passes: the warm-up and one timed pass.
        text, _ = run_callgrind([embree_exe, scene, os.path.join(tmp, "hits"), "1"],
                                ["rtcIntersect1", "rtcOccluded1"], env)
    report("Embree", text, 2 * rays, listing)


if __name__ == "__main__":
    main()
