#!/usr/bin/env python3
"""Runs the libFuzzer targets of a TESSERA_FUZZ build and summarises them (`make fuzz`, fuzz/README.md).

Usage: python3 fuzz/run_fuzz.py --build build-fuzz [--seconds 60] [--jobs 1] [--targets tframe,gltf]
                                [--rss-limit-mb 2048] [--timeout 10]

For each target, one after the other, libFuzzer's fork mode runs `--jobs` worker processes for `--seconds`
seconds over the seeds of fuzz/corpus/<target>/ (read only) and the work corpus
<build>/fuzz-corpus/<target>/, which receives every new input and is kept between runs. Crashes, timeouts
(an input running longer than --timeout seconds), out-of-memory (beyond --rss-limit-mb, or one malloc that
large) and leaks are written to <build>/crashes/<target>/ and do not stop the run. libFuzzer's full output
goes to <build>/fuzz-logs/<target>.log. The inputs kept in fuzz/crashers/<target>/ are then run once each
to report which still fail.

Prints a table per target (executions, exec/s, cov, ft, corpus units, new findings, known crashers still
failing) and writes it as <build>/fuzz-summary.json. Exit status 1 if any run found something new, else 0.
Standard library only.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import time

TARGETS = ["tframe", "mta", "gltf", "obj", "ac3d", "camera_path", "tab", "scene_manifest"]
FINDING_PREFIXES = ("crash-", "timeout-", "oom-", "leak-", "slow-unit-")
# Fork mode: "#95409: cov: 1812 ft: 2319 corp: 154 exec/s 6715 oom/timeout/crash: 0/0/0 time: 18s job: 4 ..."
FORK_STATUS = re.compile(r"^#(\d+): cov: (\d+) ft: (\d+) corp: (\d+) exec/s:? (\d+) oom/timeout/crash: (\d+)/(\d+)/(\d+)"
                         r" time: (\d+)s")


def findings(directory):
    return {f for f in os.listdir(directory) if f.startswith(FINDING_PREFIXES)} if os.path.isdir(directory) else set()


def run_target(args, source, target):
    exe = os.path.join(args.build, "fuzz", "fuzz_" + target)
    if not os.access(exe, os.X_OK):
        sys.exit(f"run_fuzz: {exe} is missing: build it first (cmake --build {args.build} --target fuzzers)")
    seeds = os.path.join(source, "fuzz", "corpus", target)
    work = os.path.join(args.build, "fuzz-corpus", target)
    crashes = os.path.join(args.build, "crashes", target)
    logs = os.path.join(args.build, "fuzz-logs")
    for d in (work, crashes, logs):
        os.makedirs(d, exist_ok=True)
    before = findings(crashes)
    cmd = [exe, work, seeds, f"-fork={args.jobs}", "-ignore_crashes=1", "-ignore_timeouts=1", "-ignore_ooms=1",
           f"-max_total_time={args.seconds}", f"-rss_limit_mb={args.rss_limit_mb}", f"-timeout={args.timeout}",
           f"-artifact_prefix={crashes}/", "-print_final_stats=1"]
    dictionary = os.path.join(source, "fuzz", "dict", target + ".dict")
    if os.path.isfile(dictionary):
        cmd.append(f"-dict={dictionary}")
    log_path = os.path.join(logs, target + ".log")
    print(f"fuzz {target}: {args.seconds} s, {args.jobs} job(s), log {log_path}", file=sys.stderr, flush=True)
    start = time.monotonic()
    with open(log_path, "w") as log:
        log.write(" ".join(cmd) + "\n")
        log.flush()
        rc = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT).returncode
    wall = time.monotonic() - start
    last = None
    with open(log_path, errors="replace") as log:
        for line in log:
            m = FORK_STATUS.match(line)
            if m:
                last = m
    new = sorted(findings(crashes) - before)
    result = {"seconds": args.seconds, "wall_seconds": round(wall, 1), "exit_code": rc,
              "work_corpus_files": len(os.listdir(work)), "new_findings": new,
              "findings_dir": crashes, "log": log_path}
    if last:
        execs, cov, ft, corp, _, oom, tmo, crash, secs = (int(x) for x in last.groups())
        result.update({"executions": execs, "exec_per_sec": round(execs / max(secs, 1)), "cov": cov, "ft": ft,
                       "corpus_units": corp, "ooms": oom, "timeouts": tmo, "crashes": crash})
    else:
        result.update({"executions": None, "exec_per_sec": None, "cov": None, "ft": None, "corpus_units": None,
                       "ooms": None, "timeouts": None, "crashes": None,
                       "note": "no libFuzzer status line in the log (did the target start?)"})
    result["known_crashers"] = replay_crashers(args, source, target, exe)
    return result


def replay_crashers(args, source, target, exe):
    """Runs each kept crasher once; returns {file: "fails" | "passes"}."""
    directory = os.path.join(source, "fuzz", "crashers", target)
    out = {}
    if not os.path.isdir(directory):
        return out
    # Judged strictly: a known descriptor leak still counts as failing while fuzzing runs past it.
    env = {k: v for k, v in os.environ.items() if k != "TESSERA_FUZZ_ALLOW_FD_LEAKS"}
    for name in sorted(os.listdir(directory)):
        path = os.path.join(directory, name)
        if not os.path.isfile(path):
            continue
        rc = subprocess.run([exe, f"-rss_limit_mb={args.rss_limit_mb}", f"-timeout={args.timeout}", path],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env).returncode
        out[name] = "passes" if rc == 0 else "fails"
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build-fuzz")
    ap.add_argument("--seconds", type=int, default=60)
    ap.add_argument("--jobs", type=int, default=1, help="libFuzzer -fork workers per target (the machine's cores)")
    ap.add_argument("--targets", default=",".join(TARGETS))
    ap.add_argument("--rss-limit-mb", type=int, default=2048)
    ap.add_argument("--timeout", type=int, default=10)
    ap.add_argument("--summary", help="where to write the JSON summary (default: BUILD/fuzz-summary.json); lets two "
                    "campaigns over different --targets run side by side")
    args = ap.parse_args()
    source = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    targets = [t for t in args.targets.split(",") if t]
    unknown = [t for t in targets if t not in TARGETS]
    if unknown:
        sys.exit(f"run_fuzz: unknown target(s) {', '.join(unknown)} (known: {', '.join(TARGETS)})")
    summary = {"seconds_per_target": args.seconds, "jobs": args.jobs, "rss_limit_mb": args.rss_limit_mb,
               "timeout_seconds": args.timeout, "targets": {}}
    for t in targets:
        summary["targets"][t] = run_target(args, source, t)

    def cell(v):
        return "-" if v is None else str(v)

    header = ["target", "execs", "exec/s", "cov", "ft", "corpus", "crash", "timeout", "oom", "new files", "crashers"]
    rows = []
    for t, r in summary["targets"].items():
        kc = r["known_crashers"]
        failing = sum(1 for v in kc.values() if v == "fails")
        rows.append([t, cell(r["executions"]), cell(r["exec_per_sec"]), cell(r["cov"]), cell(r["ft"]),
                     cell(r["corpus_units"]), cell(r["crashes"]), cell(r["timeouts"]), cell(r["ooms"]),
                     str(len(r["new_findings"])), f"{failing}/{len(kc)} fail"])
    widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(header)]
    print("  ".join(h.ljust(w) for h, w in zip(header, widths)))
    for r in rows:
        print("  ".join(c.ljust(w) for c, w in zip(r, widths)))
    for t, r in summary["targets"].items():
        for f in r["new_findings"]:
            print(f"new finding: {os.path.join(r['findings_dir'], f)}")
        for f, v in r["known_crashers"].items():
            if v == "passes":
                print(f"fuzz/crashers/{t}/{f} no longer fails: move it into fuzz/corpus/{t}/ (fuzz/README.md)")
    path = args.summary or os.path.join(args.build, "fuzz-summary.json")
    with open(path + ".tmp", "w") as f:
        json.dump(summary, f, indent=1, sort_keys=True)
        f.write("\n")
    os.replace(path + ".tmp", path)
    print(f"summary: {path}")
    return 1 if any(r["new_findings"] for r in summary["targets"].values()) else 0


if __name__ == "__main__":
    sys.exit(main())
