#!/usr/bin/env bash
# The unity-build lint (tools/lint_unity.sh) fails on a file-local name declared in two files of one
# target and on a namespace-scope `using namespace`, and passes what a unity batch can hold:
# lint_unity_test.sh LINT WORKDIR
set -euo pipefail
lint=$1; work=$2/lint_unity
fail() { echo "FAIL: $*" >&2; exit 1; }
trap 'rm -rf "$work" "$work.out"' EXIT
# expect STATUS TEXT A B [C]: files a.cpp and b.cpp (one target) holding A and B, and c.cpp (a target of
# its own) holding C, make the lint exit STATUS, naming TEXT.
expect() {
  local want=$1 text=$2
  rm -rf "$work"; mkdir -p "$work"
  printf '%s\n' "$3" > "$work/a.cpp"; printf '%s\n' "$4" > "$work/b.cpp"; printf '%s\n' "${5:-}" > "$work/c.cpp"
  local rc=0; bash "$lint" -- "$work/a.cpp" "$work/b.cpp" -- "$work/c.cpp" > "$work.out" 2>&1 || rc=$?
  [ "$rc" = "$want" ] || fail "exit $rc, expected $want for: $3 | $4 | ${5:-}: $(cat "$work.out")"
  grep -qF -- "$text" "$work.out" || fail "the output lacks '$text' for: $3 | $4 | ${5:-}: $(cat "$work.out")"
}
anon() { printf 'namespace tessera {\nnamespace {\n\n%s\n\n}  // namespace\n}  // namespace tessera' "$1"; }
# The same helper, an overload, a type, constants, a static function, an alias: each in both files.
expect 1 "helper:" "$(anon 'int helper(int x) { return x; }')" "$(anon 'int helper(int x) { return x + 1; }')"
expect 1 "helper:" "$(anon 'int helper(int x) { return x; }')" "$(anon 'std::string helper(const std::string& s) {')"
expect 1 "TempDir:" "$(anon 'struct TempDir {')" "$(anon $'// A scratch directory.\nstruct TempDir {\n  std::string path;\n};')"
expect 1 "kH:" "$(anon 'constexpr int kW = 160, kH = 120;')" "$(anon 'constexpr uint32_t kSize = 8, kH = 96;')"
expect 1 "kBlack:" "$(anon 'const Rgba kGrid{225, 225, 225, 255}, kBlack{0, 0, 0, 255};')" "$(anon 'constexpr Rgba kBlack{0, 0, 0, 255};')"
expect 1 "kRailway:" "$(anon 'const std::string kRailway = TESSERA_SOURCE_DIR "/data/railway.glb";')" \
  "$(anon 'const std::string kRailway = std::string(TESSERA_SOURCE_DIR) + "/data/railway.glb";')"
expect 1 "dump:" 'static std::string dump(const std::vector<Diagnostic>& d) {' "$(anon 'std::string dump(const Diagnostic& d) {')"
expect 1 "Rendered:" "$(anon 'using Rendered = ProvenanceRender;')" "$(anon 'struct Rendered {')"
expect 1 "views:" "$(anon $'template <class T>\nstd::vector<T> views(const MtaMeta& meta) {')" "$(anon 'std::vector<ViewParams> views() {')"
# using namespace at namespace scope, also in a target of its own.
expect 1 "using namespace" 'using namespace tessera;' '' ''
expect 1 "using namespace" '' '' $'namespace tessera {\nusing namespace scenes;\n}  // namespace tessera'
# Allowed: the same name in two targets, overloads within one file, names inside bodies and raw strings,
# operators, using-declarations and namespace aliases, names of named namespaces, a using-directive in a
# function body.
expect 0 "clean" "$(anon 'int helper(int x) { return x; }')" '' "$(anon 'int helper(int x) { return x; }')"
expect 0 "clean" "$(anon $'int helper(int x) { return x; }\nint helper(double x) { return int(x); }')" ''
expect 0 "clean" "$(anon $'void f() {\n  const int kW = 3;\n  using namespace std::chrono;\n}')" \
  "$(anon $'void g() {\n  const int kW = 4;\n}')"
expect 0 "clean" "$(anon $'const std::string kDae = R"(<?xml version="1.0"?>\nconst int kW = 1;\n<COLLADA xmlns="x">)";')" \
  "$(anon 'const int kW = 2;')"
expect 0 "clean" "$(anon 'std::ostream& operator<<(std::ostream& os, const A& a) {')" \
  "$(anon 'std::ostream& operator<<(std::ostream& os, const B& b) {')"
expect 0 "clean" "$(anon $'using testing::TempFile;\nnamespace fs = std::filesystem;')" \
  "$(anon $'using testing::TempFile;\nnamespace fs = std::filesystem;')"
expect 0 "clean" $'namespace tessera::cli {\n\nvoid writeTextFile(const std::string& p) {\n}\n\n}  // namespace tessera::cli' \
  $'namespace tessera::cli {\n\nvoid writeTextFile(const std::string& p, int n) {\n}\n\n}  // namespace tessera::cli'
# Usage errors.
rc=0; bash "$lint" "$work/a.cpp" > /dev/null 2>&1 || rc=$?
[ "$rc" = 2 ] || fail "without --: exit $rc, expected 2"
rc=0; bash "$lint" -- /nonexistent/x.cpp > /dev/null 2>&1 || rc=$?
[ "$rc" = 2 ] || fail "a missing file: exit $rc, expected 2"
echo "lint_unity_test: ok"
