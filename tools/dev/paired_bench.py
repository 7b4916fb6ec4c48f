#!/usr/bin/env python3
"""Paired A/B timing of Google Benchmark binaries on a noisy machine (docs/bench.md, "Paired runs").

Usage: tools/dev/paired_bench.py [--rounds N] [--repetitions R] [--json OUT] FILTER A B [C ...]

Each argument after FILTER is a benchmark binary (build/bench_raster of one commit), optionally with
environment settings before it, as in `TESSERA_X=1 /tmp/bench`. One round runs every binary once, in
the order given, each with --benchmark_repetitions=R; a binary's time in a round is the least of its
repetitions' manual times. Every binary's ratio to A is taken within the same round, so a slow spell of
the host, which lasts longer than one round, scales both sides of a ratio alike. The report gives per
benchmark and binary the median of the round ratios, their range, and how many rounds were slower
than A (a sign test: 7 of 8 means something, 5 of 8 does not).

Why: on a shared VM a binary's medians spread by up to 45 % from one minute to the next (docs/bench.md),
far more than the few per cent a change is worth. Alternating runs and comparing their minima, as
`--benchmark_repetitions` alone does, still reads the host's weather. Paired ratios do not.

Does not: build anything, check bytes (tools/dev/byte_snapshot.sh does) or count instructions
(tools/dev/callgrind.sh does).
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys

# A benchmark's per-repetition line in Google Benchmark's console output: name, time (the manual time
# where the benchmark sets one, as bench_raster does; else wall time), CPU time, iterations.
LINE = re.compile(r"^(\S+)\s+([0-9.]+) (ns|us|ms|s)\s+[0-9.]+ (?:ns|us|ms|s)\s+\d+")
TO_MS = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}


def parse_binary(arg):
    """'K=V K2=V2 /path/bench' -> (env dict, path); names the argument and the reason when it is bad."""
    words = arg.split()
    env = {}
    for w in words[:-1]:
        if "=" not in w or w.startswith("="):
            sys.exit(f"paired_bench.py: binary '{arg}': '{w}' is not a NAME=VALUE setting")
        k, v = w.split("=", 1)
        env[k] = v
    if not words:
        sys.exit("paired_bench.py: an empty binary argument")
    path = words[-1]
    if not (os.path.isfile(path) and os.access(path, os.X_OK)):
        sys.exit(f"paired_bench.py: binary '{arg}': {path} is not an executable file")
    return env, path


def run_once(label, env, path, filt, reps):
    """The least manual time (ms) per benchmark of one run of the binary."""
    proc = subprocess.run([path, f"--benchmark_filter={filt}", f"--benchmark_repetitions={reps}"],
                          capture_output=True, text=True, env={**os.environ, **env})
    if proc.returncode != 0:
        sys.exit(f"paired_bench.py: {label} exited with {proc.returncode}:\n{proc.stderr.strip()[-2000:]}")
    best = {}
    for line in proc.stdout.splitlines():
        m = LINE.match(line)
        if m and not m.group(1).endswith(("_mean", "_median", "_stddev", "_cv")):
            ms = float(m.group(2)) * TO_MS[m.group(3)]
            best[m.group(1)] = min(ms, best.get(m.group(1), ms))
    if not best:
        sys.exit(f"paired_bench.py: {label}: no benchmark matched '{filt}' "
                 "(list them with the binary's --benchmark_list_tests)")
    return best


def main():
    ap = argparse.ArgumentParser(
        description="Paired A/B timing of benchmark binaries on a noisy machine: per round, every "
        "binary runs once and its time is divided by A's of the same round.",
        epilog="Example: tools/dev/paired_bench.py --rounds 8 '^tiny_tris_1m/2' /tmp/bench_old build/bench_raster")
    ap.add_argument("filter", help="--benchmark_filter regex, e.g. '^tiny_tris_1m/'")
    ap.add_argument("binaries", nargs="+", help="A, then the binaries compared with it; 'K=V /path' sets an "
                    "environment variable for that binary only")
    ap.add_argument("--rounds", type=int, default=8, help="rounds (default 8; a sign test needs 6 or more)")
    ap.add_argument("--repetitions", type=int, default=2, help="repetitions per run, the least counts (default 2)")
    ap.add_argument("--json", metavar="OUT", help="also write every round's times and the summary as JSON")
    a = ap.parse_args()
    if len(a.binaries) < 2:
        ap.error("give at least two binaries: A and one to compare with it")
    if a.rounds < 1 or a.repetitions < 1:
        ap.error("--rounds and --repetitions must be at least 1")
    # A binary given twice (an A/A run, to see the noise floor) is told apart by its position.
    labels = [arg if a.binaries.count(arg) == 1 else f"#{i + 1} {arg}" for i, arg in enumerate(a.binaries)]
    bins = [(label, *parse_binary(arg)) for label, arg in zip(labels, a.binaries)]
    if a.json:  # checked before the rounds, which take minutes
        out_dir = os.path.dirname(os.path.abspath(a.json))
        if not os.path.isdir(out_dir) or not os.access(out_dir, os.W_OK):
            sys.exit(f"paired_bench.py: --json {a.json}: the directory {out_dir} does not exist or is not writable")
    times = {label: [] for label, _, _ in bins}  # per binary: per round {benchmark: ms}
    for r in range(a.rounds):
        for arg, env, path in bins:
            times[arg].append(run_once(arg, env, path, a.filter, a.repetitions))
        print(f"round {r + 1}/{a.rounds} done", file=sys.stderr, flush=True)
    base = bins[0][0]
    summary = []
    names = sorted(times[base][0])
    for name in names:
        for arg, _, _ in bins:
            ms = [t.get(name) for t in times[arg]]
            if any(v is None for v in ms):
                sys.exit(f"paired_bench.py: {arg} did not run {name} in every round")
            ratios = [v / t[name] for v, t in zip(ms, times[base])]
            summary.append({"benchmark": name, "binary": arg, "min_ms": min(ms), "median_ms": statistics.median(ms),
                            "ratio_median": statistics.median(ratios), "ratio_min": min(ratios),
                            "ratio_max": max(ratios), "rounds_slower": sum(x > 1.0 for x in ratios),
                            "rounds": len(ratios)})
    w = max(len(s["binary"]) for s in summary)
    print(f"{'benchmark':32s} {'binary':{w}s} {'min ms':>8s} {'median':>8s}  ratio to A: median [range], rounds slower")
    for s in summary:
        print(f"{s['benchmark']:32s} {s['binary']:{w}s} {s['min_ms']:8.2f} {s['median_ms']:8.2f}  "
              f"{s['ratio_median']:.3f} [{s['ratio_min']:.3f}, {s['ratio_max']:.3f}], "
              f"{s['rounds_slower']} of {s['rounds']}")
    if a.json:
        tmp = f"{a.json}.tmp-{os.getpid()}"
        with open(tmp, "w") as f:
            json.dump({"filter": a.filter, "repetitions": a.repetitions, "rounds": times, "summary": summary}, f, indent=1)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, a.json)  # a rename: a half-written file never has the final name


if __name__ == "__main__":
    main()
