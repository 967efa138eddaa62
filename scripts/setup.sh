#!/usr/bin/env bash
# Installs what ccal needs on a Debian 12 machine (only what is missing), fetches the charting library of
# `ccal report` from npm into web/node_modules (only when web/package-lock.json changed), then configures and
# builds ccal in ./build. Idempotent: a second run only rebuilds what changed; compilations go through Debian's
# ccache, so that a rebuild in a fresh clone (CI) recompiles only what changed.
#   bash scripts/setup.sh         everything: library, program, Python module, tests, benchmarks
#   bash scripts/setup.sh ccal    the library and the program only (the README's first command)
# Node.js, npm and the charting library are only needed from the program's link on: they are installed in the
# background while the library compiles (on a fresh machine npm alone brings some 360 Debian packages), and
# their output goes to build/web-fetch.log, shown if that fails.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS=0
# The library and the program need the first list; the tests, benchmarks, Python module, the report's browser
# check, the certificate's PDF check (Chromium prints it, poppler-utils reads it back), the check of every
# instruction set's bits (qemu-user emulates processors without AVX-512 or AVX2) and the test of the Python
# results' to_frame() (pandas, about 38 MB installed; ccal itself does not need it) the second.
packages=(cmake ninja-build g++ pkg-config libeigen3-dev libcli11-dev nlohmann-json3-dev libtomlplusplus-dev
          libfmt-dev libboost-math-dev libsqlite3-dev libssl-dev ccache)
case "${1:-all}" in
  all) targets=()
       parts=(-DCCAL_BUILD_TESTS=ON -DCCAL_BUILD_BENCH=ON -DCCAL_BUILD_PYTHON=ON)
       packages+=(libgtest-dev libgmock-dev libbenchmark-dev pybind11-dev python3-dev python3-numpy chromium
                 poppler-utils zsh fish qemu-user python3-venv python3-pip python3-setuptools python3-wheel
                 python3-pandas) ;;
  ccal) targets=(--target ccal_cli)
        parts=(-DCCAL_BUILD_TESTS=OFF -DCCAL_BUILD_BENCH=OFF -DCCAL_BUILD_PYTHON=OFF) ;;
  *) echo "setup: '$1' is not a build choice; accepted: 'ccal' (library and program) or nothing (everything)" >&2
     exit 2 ;;
esac

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
apt_updated=false
missing_of() {  # the packages of "$@" that are not installed
  local p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || echo "$p"
  done
}
apt_install() {  # apt_install <package>...
  if ! $apt_updated; then
    "${sudo_cmd[@]}" apt-get update -qq
    apt_updated=true
  fi
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "$@" >/dev/null
}

mapfile -t missing < <(missing_of "${packages[@]}")
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  apt_install "${missing[@]}"
fi
packages_done=$SECONDS

# Node.js with npm (Debian's nodejs package, and its npm package where nodejs does not bring npm), then vega,
# vega-lite, vega-embed (embedded into ccal for `ccal report`) and playwright-core (the report's browser test),
# exactly as web/package-lock.json pins them; npm ci is skipped when node_modules already matches the lock file.
web_missing=()
command -v node >/dev/null || web_missing+=(nodejs)
command -v npm >/dev/null || web_missing+=(npm)
fetch_web() {
  if ((${#web_missing[@]})); then
    echo "setup: installing ${web_missing[*]}"
    apt_install "${web_missing[@]}"
  fi
  if ! cmp -s web/package-lock.json web/node_modules/.ccal-package-lock.json 2>/dev/null; then
    echo "setup: fetching web/node_modules (npm ci)"
    npm ci --prefix web --no-audit --no-fund --loglevel=error
    cp web/package-lock.json web/node_modules/.ccal-package-lock.json
  fi
}
mkdir -p build
web_log=build/web-fetch.log
web_pending=OFF
if ((${#web_missing[@]})) || ! cmp -s web/package-lock.json web/node_modules/.ccal-package-lock.json 2>/dev/null
then
  echo "setup: Node.js, npm and web/node_modules in the background, while the library compiles ($web_log)" >&2
  # A password prompt cannot reach a background job: ask for it now.
  if ((${#web_missing[@]})) && ((${#sudo_cmd[@]})); then sudo -v; fi
  fetch_web >"$web_log" 2>&1 &
  web_job=$!
  web_pending=ON
fi
web_fetched() {  # waits for the background fetch; fails with its log if it failed
  if ! wait "$web_job"; then
    echo "setup: installing Node.js/npm or fetching web/node_modules failed; its output ($web_log):" >&2
    cat "$web_log" >&2
    exit 1
  fi
}
trap '[ "$web_pending" = ON ] && kill "$web_job" 2>/dev/null; true' EXIT

# Paths below the source folder are hashed relative to it, so that a clone in another folder reuses the cache.
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR="$PWD"
configure() {
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCCAL_WERROR=ON "${parts[@]}" "${launcher[@]}" \
        -DCCAL_WEB_MODULES_PENDING="$web_pending" >/dev/null
}
configure
if [ "$web_pending" = ON ]; then
  # The library meanwhile; then configure again, now that the charting library is there to be embedded.
  cmake --build build -j "$(nproc)" --target libccal.a
  web_fetched
  web_pending=OFF
  configure
fi
cmake --build build -j "$(nproc)" "${targets[@]}"
echo "setup: packages ${packages_done} s, build $((SECONDS - packages_done)) s" >&2
