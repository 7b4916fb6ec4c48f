#!/usr/bin/env bash
# asan_defaults.sh TESSERA WORK BINARY...: the sanitizer build's programs carry their default ASan
# options (base/sanitizer_defaults.cpp), so a test run by hand behaves as under ctest. Each BINARY must
# export __asan_default_options (the runtime finds it only in the dynamic symbol table), and TESSERA,
# writing a PNG through the dlopened image module, must not intercept __tls_get_addr, while an explicit
# ASAN_OPTIONS=intercept_tls_get_addr=1 must (so the check can see the interception at all).
set -euo pipefail
tessera=$1; work=$2; shift 2
rm -rf "$work"; mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
for bin in "$tessera" "$@"; do
  syms=$(nm -D --defined-only "$bin") || fail "nm -D $bin failed"
  grep -qE ' T __asan_default_options$' <<< "$syms" \
    || fail "$bin does not export __asan_default_options: it runs without the build's default ASan options (CMakeLists.txt, tessera_sanitizer_defaults)"
  echo "ok: $bin exports __asan_default_options"
done
# verbosity=2 makes the runtime log every intercepted __tls_get_addr call that creates a block.
ASAN_OPTIONS=verbosity=2 "$tessera" render blend -o "$work/default.png" > /dev/null 2> "$work/default.err" \
  || fail "render with the default options failed: $(tail -5 "$work/default.err")"
ASAN_OPTIONS=verbosity=2:intercept_tls_get_addr=1 "$tessera" render blend -o "$work/forced.png" > /dev/null 2> "$work/forced.err" \
  || fail "render with intercept_tls_get_addr=1 failed: $(tail -5 "$work/forced.err")"
grep -q '__tls_get_addr:' "$work/forced.err" \
  || fail "with intercept_tls_get_addr=1 no interception was logged: this check is blind (did the image module load?)"
if grep -q '__tls_get_addr:' "$work/default.err"; then
  fail "the default options intercept __tls_get_addr: $(grep -m1 '__tls_get_addr:' "$work/default.err")"
fi
echo "ok: __tls_get_addr is intercepted only when ASAN_OPTIONS asks for it"
rm -rf "$work"
