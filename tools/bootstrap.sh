#!/usr/bin/env bash
# Installs the Debian 12 packages Tessera builds against, only those missing.
# Idempotent: a machine that has everything returns in well under a second.
#   bash tools/bootstrap.sh          what `make demo` / `make test` (and CI) need
#   bash tools/bootstrap.sh --fuzz   that, plus clang with its libFuzzer / sanitizer runtime and
#                                    llvm-symbolizer, for `make fuzz` only (fuzz/README.md)
set -euo pipefail
PKGS=(
  build-essential cmake ninja-build pkg-config
  libopenimageio-dev openimageio-tools libglm-dev libembree-dev libtbb-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev nlohmann-json3-dev libfmt-dev libhwy-dev
  libegl-dev libegl-mesa0 libgl1-mesa-dri libopengl-dev libgles-dev
  libtinygltf-dev libtinyobjloader-dev libstb-dev libassimp-dev
)
# The unversioned Debian packages follow the default clang (clang 14 and libclang-rt-14-dev on Debian 12).
FUZZ_PKGS=(clang libclang-rt-dev llvm)
for arg in "$@"; do
  case "$arg" in
    --fuzz) PKGS+=("${FUZZ_PKGS[@]}") ;;
    *) echo "bootstrap: unknown option '$arg' (known: --fuzz)" >&2; exit 2 ;;
  esac
done
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then exit 0; fi
echo "bootstrap: installing ${#missing[@]} missing Debian packages: ${missing[*]}" >&2
SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "bootstrap: done" >&2
