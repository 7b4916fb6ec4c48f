#!/usr/bin/env bash
# The unity-build lint (CONTRIBUTING.md, "Code"; CMakeLists.txt, tessera_unity_build): the test binaries
# and the CLI are compiled in unity batches, several .cpp files of a target in one translation unit, so
# what one file declares at namespace scope is seen by the files after it in its batch. Which files share
# a batch changes whenever a file is added, so within each target
#   - a file-local name (a function, type, alias or variable in an anonymous namespace, or declared
#     `static` at namespace scope) is declared in one .cpp file only: the same signature twice stops the
#     build at the next reshuffle of the batches, a different one silently joins an overload set;
#   - no .cpp file has a `using namespace` at namespace scope: it would reach every later file of the
#     batch. (Put the file's code in the namespace instead: `namespace tessera::verify {`.)
# Shared helpers go into a header of the module's tests (tests/<module>/*.h), declared once.
# The parse relies on the repository's formatting (.clang-format): namespace contents start in column 0,
# anonymous namespaces open with `namespace {` and close with `}  // namespace`. Operators are exempt
# (overloads for different types are what they are for), and so are upper-case names (macros).
#
# Usage: tools/lint_unity.sh -- FILE... [-- FILE...]...   one group of .cpp files per target (ctest
# lint.unity_targets_share_no_file_local_name_and_no_using_namespace passes every unity-built target).
# Exit 0: clean; 1: violations, listed as name: file:line of each declaration; 2: bad usage.
set -uo pipefail
if [ "${1:-}" != "--" ]; then
  echo "usage: lint_unity.sh -- FILE... [-- FILE...]...  (one group of .cpp files per target)" >&2
  exit 2
fi
status=0
# The file-local names of one .cpp file, as "name<TAB>file:line" lines.
locals() {
  awk '
    # A column-0 declaration with string literals and the insides of (), {} and [] removed.
    function flatten(s,   t) {
      gsub(/\\./, "", s)
      gsub(/"[^"]*"/, "\"\"", s)
      gsub(/'"'"'[^'"'"']*'"'"'/, "0", s)
      do { t = s; gsub(/\([^()]*\)/, "()", s); gsub(/\{[^{}]*\}/, "{}", s); gsub(/\[[^][]*\]/, "[]", s) } while (s != t)
      return s
    }
    function emit(name) {
      if (name == "" || name ~ /^operator/ || name ~ /^[A-Z0-9_]+$/) return
      printf "%s\t%s:%d\n", name, FILENAME, FNR
    }
    function declaration(line,   s, n, parts, i, p, m) {
      if (line ~ /^(\/\/|#|}|\{|namespace|template|TEST|static_assert|typedef|extern|friend|public|private|protected)/) return
      if (match(line, /^(struct|class|union|enum( class| struct)?) +[A-Za-z_][A-Za-z0-9_]*/)) {
        s = substr(line, RSTART, RLENGTH); sub(/.* /, "", s); emit(s); return
      }
      if (match(line, /^using +[A-Za-z_][A-Za-z0-9_]* *=/)) {
        s = substr(line, RSTART, RLENGTH); sub(/^using +/, "", s); sub(/ *=$/, "", s); emit(s); return
      }
      if (line ~ /^using /) return
      s = line
      sub(/\/\/.*/, "", s)
      # A function: the identifier before the first "(" when no "=" comes before it.
      p = index(s, "("); m = index(s, "=")
      if (p > 0 && (m == 0 || p < m)) {
        s = substr(s, 1, p - 1)
        if (match(s, /[A-Za-z_][A-Za-z0-9_]*$/)) emit(substr(s, RSTART, RLENGTH))
        return
      }
      # Variables: each declarator of "type a = 1, b{2}, c;" names the identifier before its =, {, [ or ;.
      s = flatten(s)
      n = split(s, parts, ",")
      for (i = 1; i <= n; ++i) {
        p = parts[i]
        if (p !~ /[={[;]/) continue
        sub(/[ ]*(=|\{|\[|;).*/, "", p)
        if (match(p, /[A-Za-z_][A-Za-z0-9_]*$/)) emit(substr(p, RSTART, RLENGTH))
      }
    }
    # Lines inside a raw string literal are text, not declarations: skip to its closing )delimiter".
    raw != "" { if (index($0, raw) > 0) raw = ""; next }
    {
      line = $0
      while (match(line, /R"[^( ]*\(/)) {
        delim = ")" substr(line, RSTART + 2, RLENGTH - 3) "\""
        line = substr(line, RSTART + RLENGTH)
        if (index(line, delim) == 0) { raw = delim; break }
        line = substr(line, index(line, delim) + length(delim))
      }
    }
    /^namespace \{/ { anon++; next }
    /^}  \/\/ namespace$/ { if (anon > 0) anon--; next }
    anon > 0 && /^[^ \t]/ { declaration($0); next }
    /^static / { s = $0; sub(/^static +/, "", s); declaration(s) }
  ' "$1"
}
check() {  # check FILE...: one target
  [ $# -gt 0 ] || return
  local hits dups
  # using namespace at namespace scope (column 0: namespace contents are not indented).
  hits=$(grep -Hn '^using namespace ' "$@" || true)
  if [ -n "$hits" ]; then
    echo "lint_unity: \`using namespace\` at namespace scope reaches the later files of a unity batch:" >&2
    echo "$hits" >&2
    status=1
  fi
  dups=$(for f in "$@"; do locals "$f" | sort -u -t$'\t' -k1,1; done |
         awk -F'\t' '{ where[$1] = where[$1] " " $2; n[$1]++ } END { for (k in n) if (n[k] > 1) print k ":" where[k] }' |
         sort)
  if [ -n "$dups" ]; then
    echo "lint_unity: file-local names declared in more than one file of a target (a unity batch joins them):" >&2
    echo "$dups" >&2
    status=1
  fi
}
group=()
shift
for arg in "$@" --; do
  if [ "$arg" = "--" ]; then
    check "${group[@]+"${group[@]}"}"
    group=()
  else
    [ -f "$arg" ] || { echo "lint_unity: no such file: $arg" >&2; exit 2; }
    group+=("$arg")
  fi
done
[ $status -eq 0 ] && echo "lint_unity: clean"
exit $status
