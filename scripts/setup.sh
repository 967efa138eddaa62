#!/usr/bin/env bash
# Installs what ccal needs on a Debian 12 machine (only what is missing), fetches the charting library of
# `ccal report` from npm into web/node_modules (only when web/package-lock.json changed), then configures and
# builds ccal in ./build. Idempotent: a second run only rebuilds what changed; compilations go through Debian's
# ccache, so that a rebuild in a fresh clone (CI) recompiles only what changed.
#   bash scripts/setup.sh         everything: library, program, Python module, tests, benchmarks
#   bash scripts/setup.sh ccal    the library and the program only (the README's first command)
set -euo pipefail
cd "$(dirname "$0")/.."
# The library and the program need the first list; the tests, benchmarks, Python module, the report's browser
# check and the certificate's PDF check (Chromium prints it, poppler-utils reads it back) the second.
packages=(cmake ninja-build g++ pkg-config libeigen3-dev libcli11-dev nlohmann-json3-dev libtomlplusplus-dev
          libfmt-dev libboost-math-dev libsqlite3-dev libssl-dev nodejs ccache)
case "${1:-all}" in
  all) targets=()
       parts=(-DCCAL_BUILD_TESTS=ON -DCCAL_BUILD_BENCH=ON -DCCAL_BUILD_PYTHON=ON)
       packages+=(libgtest-dev libgmock-dev libbenchmark-dev pybind11-dev python3-dev python3-numpy chromium
                 poppler-utils) ;;
  ccal) targets=(--target ccal_cli)
        parts=(-DCCAL_BUILD_TESTS=OFF -DCCAL_BUILD_BENCH=OFF -DCCAL_BUILD_PYTHON=OFF) ;;
  *) echo "setup: '$1' is not a build choice; accepted: 'ccal' (library and program) or nothing (everything)" >&2
     exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# npm comes with Debian's nodejs package, or separately (package npm) where nodejs does not bring it.
if ! command -v npm >/dev/null; then
  dpkg-query -W -f='${Status}' npm 2>/dev/null | grep -q "install ok installed" || {
    echo "setup: installing npm" >&2
    sudo_cmd=()
    [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
    DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends npm >/dev/null
  }
fi
# vega, vega-lite, vega-embed (embedded into ccal for `ccal report`) and playwright-core (the report's browser
# test), exactly as web/package-lock.json pins them; skipped when node_modules already matches the lock file.
if ! cmp -s web/package-lock.json web/node_modules/.ccal-package-lock.json 2>/dev/null; then
  echo "setup: fetching web/node_modules (npm ci)" >&2
  npm ci --prefix web --no-audit --no-fund --loglevel=error >/dev/null
  cp web/package-lock.json web/node_modules/.ccal-package-lock.json
fi

# Paths below the source folder are hashed relative to it, so that a clone in another folder reuses the cache.
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR="$PWD"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCCAL_WERROR=ON "${parts[@]}" "${launcher[@]}" \
      >/dev/null
cmake --build build -j "$(nproc)" "${targets[@]}"
