#!/usr/bin/env bash
# tools/dev/paired_bench.py divides each binary's time by the first binary's of the same round, tells a
# binary given twice apart, passes an environment setting to one binary only, writes its JSON whole, and
# names the argument and the reason for each bad input: paired_bench_test.sh SCRIPT WORKDIR
set -euo pipefail
script=$1; work=$2/paired_bench
fail() { echo "FAIL: $*" >&2; exit 1; }
rm -rf "$work"; mkdir -p "$work"
trap 'rm -rf "$work"' EXIT
# A stand-in for a Google Benchmark binary: per repetition one console line per benchmark, the time
# MS (or $FAKE_MS when set) times the round (every binary's runs counted together, $FAKE_PER_ROUND
# per round) plus the repetition's index, so the least repetition is MS * round: a host that gets
# slower round by round, which only ratios within a round cancel. The filter selects lines by name, as Google Benchmark selects benchmarks.
fake() {
  cat > "$work/$1" <<SH
#!/usr/bin/env bash
n=\$(( \$(cat "$work/runs" 2>/dev/null || echo 0) + 1 )); echo \$n > "$work/runs"
ms=\$(( \${FAKE_MS:-$2} * ((n - 1) / \${FAKE_PER_ROUND:-1} + 1) )); reps=1; filter=.
for a in "\$@"; do
  case \$a in --benchmark_repetitions=*) reps=\${a#*=};; --benchmark_filter=*) filter=\${a#*=};; esac
done
for ((r = 0; r < reps; ++r)); do
  echo "frame/1/manual_time \$((ms + r)).00 ms 99.0 ms 7 items=1"
  echo "other/1/manual_time \$((2 * ms + r)).00 ms 99.0 ms 7"
done | grep -E -- "\$filter" || true
echo "frame/1/manual_time_median \$ms.00 ms 99.0 ms 3" | grep -E -- "\$filter" || true
SH
  chmod +x "$work/$1"
}
fake a 20; fake b 30; fake broken 1
printf '#!/bin/sh\necho boom >&2\nexit 3\n' > "$work/broken"
out=$(FAKE_PER_ROUND=4 python3 "$script" --rounds 3 --json "$work/r.json" '.' "$work/a" "$work/b" "FAKE_MS=10 $work/a" "$work/a" 2> "$work/err")
grep -q "round 3/3 done" "$work/err" || fail "no progress lines: $(cat "$work/err")"
line() { grep -F "$1" <<< "$out" | grep -F -- "$2" || fail "no line for $1 $2 in: $out"; }
[[ $(line frame/1 "$work/b ") == *"1.500 [1.500, 1.500], 3 of 3"* ]] || fail "b/a: $out"
[[ $(line frame/1 "FAKE_MS=10") == *"0.500 [0.500, 0.500], 0 of 3"* ]] || fail "the setting: $out"
[[ $(line other/1 "#4 $work/a") == *"1.000 [1.000, 1.000], 0 of 3"* ]] || fail "a given twice: $out"
# a's least repetitions over the rounds are 20, 40, 60: the least 20, the median 40.
[[ $(line frame/1 "#1 $work/a") == *"   20.00    40.00  1.000"* ]] || fail "least repetition: $out"
python3 - "$work/r.json" <<'PY' || fail "the JSON"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["repetitions"] == 2 and len(d["summary"]) == 8, d
assert all(len(v) == 3 for v in d["rounds"].values()), d["rounds"]
PY
[ -z "$(ls "$work" | grep tmp-)" ] || fail "a temporary file was left"
# expect TEXT ARGS...: the script exits non-zero and its message holds TEXT.
expect() {
  local text=$1; shift
  local rc=0; python3 "$script" --rounds 1 "$@" > "$work/out" 2>&1 || rc=$?
  [ "$rc" != 0 ] || fail "exit 0 for: $*"
  grep -qF -- "$text" "$work/out" || fail "the message lacks '$text' for $*: $(cat "$work/out")"
}
expect "give at least two binaries" '.' "$work/a"
expect "$work/nope is not an executable file" '.' "$work/a" "$work/nope"
expect "'FOO' is not a NAME=VALUE setting" '.' "$work/a" "FOO $work/b"
expect "no benchmark matched '^none'" '^none' "$work/a" "$work/b"
expect "$work/broken exited with 3" '.' "$work/a" "$work/broken"
expect "boom" '.' "$work/a" "$work/broken"
expect "must be at least 1" --rounds 0 '.' "$work/a" "$work/b"
expect "--json $work/no/r.json: the directory $work/no does not exist" --json "$work/no/r.json" '.' "$work/a" "$work/b"
echo "paired_bench_test: all cases passed"
