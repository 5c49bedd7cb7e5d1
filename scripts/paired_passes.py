#!/usr/bin/env python3
"""Two builds of the trace crate's `profile_set` example timed pass by pass, alternately.

On a shared machine the rate of one build drifts by 10-40 % within a minute, so two builds
timed in separate runs are hard to compare. This starts both builds once (each builds its
hierarchy, then waits: `profile_set SCENE SET QUERY serve`), then asks each for one pass at a
time, alternating (and swapping which goes first on every other pair). A process keeps a few
per cent of luck or bad luck in where its memory lands for its whole life, so this is done in
ROUNDS (default 4) of fresh processes, PAIRS (default 12) pairs each, the first started swapped
every round. It reports the median of the rounds' median speed ratios, each round's, and the
ratio of the total times.

    scripts/paired_passes.py BUILD_A BUILD_B SCENE.bin SET single|packet [ROUNDS [PAIRS]]

Example (run from the repository root after the `embree` example has written the scenes):

    scripts/paired_passes.py /tmp/profile_set_base target/release/examples/profile_set \\
        out/embree/terrain.bin shadow single

A ratio above 1 means BUILD_B is faster.

A build named `embree:PATH` is the Embree program (`scripts/embree_bench`) at PATH, serving the
same set with `rtcIntersect1`/`rtcOccluded1` (query `single`) or in MODE (`embree:PATH:MODE`,
one of 1, 8, 16, 1M): ours against Embree's, pass by pass, the two processes sharing the
machine's moments. For example

    scripts/paired_passes.py embree:out/embree_bench target/release/examples/profile_set \
        out/embree/blob.bin bounce single 5 16
"""
import os
import statistics
import subprocess
import sys


def start(build, scene, ray_set, query):
    env = None
    if build.startswith("embree:"):
        path, _, mode = build[len("embree:"):].partition(":")
        env = dict(os.environ, EMBREE_BENCH_ONLY=f"{ray_set}:{mode or '1'}")
        command = [path, scene, "-", "serve"]
        build = path
    else:
        command = [build, scene, ray_set, query, "serve"]
    try:
        p = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
                             bufsize=1, env=env)
    except OSError as e:
        sys.exit(f"paired_passes: cannot run {build}: {e}")
    for line in p.stdout:
        if line.strip() == "ready":
            return p
    sys.exit(f"paired_passes: {build} ended before it was ready (exit {p.wait()})")


def one_pass(p):
    p.stdin.write("pass\n")
    p.stdin.flush()
    line = p.stdout.readline()
    if not line:
        sys.exit(f"paired_passes: a build ended early (exit {p.wait()})")
    return float(line)


def main():
    usage = "usage: paired_passes.py BUILD_A BUILD_B SCENE.bin SET single|packet [ROUNDS [PAIRS]]"
    if len(sys.argv) not in (6, 7, 8):
        sys.exit(usage)
    a_build, b_build, scene, ray_set, query = sys.argv[1:6]
    try:
        rounds = int(sys.argv[6]) if len(sys.argv) > 6 else 4
        pairs = int(sys.argv[7]) if len(sys.argv) > 7 else 12
    except ValueError:
        sys.exit(usage)
    if rounds < 1 or pairs < 1:
        sys.exit(usage)
    medians, ta, tb = [], 0.0, 0.0
    for r in range(rounds):
        # Fresh processes each round, the first started swapped each round: where a process's
        # memory lands moves its rate by a few per cent, for the whole of its life.
        if r % 2 == 0:
            a, b = start(a_build, scene, ray_set, query), start(b_build, scene, ray_set, query)
        else:
            b, a = start(b_build, scene, ray_set, query), start(a_build, scene, ray_set, query)
        one_pass(a), one_pass(b)  # warm both
        ratios = []
        for i in range(pairs):
            if i % 2 == 0:
                x, y = one_pass(a), one_pass(b)
            else:
                y, x = one_pass(b), one_pass(a)
            ratios.append(x / y)
            ta, tb = ta + x, tb + y
        for p in (a, b):
            p.stdin.close()
            p.wait()
        medians.append(statistics.median(ratios))
    n = rounds * pairs
    print(f"{ray_set} {query}: B/A speed, median of the rounds' medians {statistics.median(medians):.3f} "
          f"(rounds {' '.join(f'{m:.3f}' for m in medians)}), total {ta / tb:.3f}; "
          f"A {ta / n * 1e3:.1f} ms, B {tb / n * 1e3:.1f} ms a pass")


if __name__ == "__main__":
    main()
