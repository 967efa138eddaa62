#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ with clang (AddressSanitizer + UndefinedBehaviorSanitizer) in
# ./build-fuzz and runs each: first every input of its regression corpus fuzz/corpus/<target> (inputs that
# once crashed it, and seeds), then coverage-guided fuzzing for SECONDS (default 30) or RUNS executions.
#   bash scripts/fuzz.sh            30 s per target (the CI smoke run)
#   bash scripts/fuzz.sh 600        10 minutes per target
#   RUNS=1000000 bash scripts/fuzz.sh   a fixed number of executions per target
# New findings are written to build-fuzz/findings/<target>/; add each, once fixed, to fuzz/corpus/<target>.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
packages=(clang libclang-rt-14-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "fuzz: installing ${missing[*]}" >&2
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# Through ccache where it is installed (scripts/setup.sh installs it), as scripts/setup.sh does.
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR="$PWD"
# -O1, as fuzzing services build: a cold build takes 400 s instead of 450-670 s at -O3 on 2 cores, and for a short
# run the coverage found matters more than executions per second.
CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG" \
  "${launcher[@]}" -DCCAL_BUILD_FUZZ=ON \
  -DCCAL_SANITIZE=fuzzer-no-link,address,undefined -DCCAL_BUILD_TESTS=OFF -DCCAL_BUILD_BENCH=OFF \
  -DCCAL_BUILD_PYTHON=OFF >/dev/null
targets=(fuzz_units fuzz_config fuzz_csv fuzz_run_log)
cmake --build build-fuzz -j "$(nproc)" --target "${targets[@]}"

export ASAN_OPTIONS=abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
for t in "${targets[@]}"; do
  work=build-fuzz/corpus/$t findings=build-fuzz/findings/$t
  mkdir -p "$work" "$findings"
  limit=(-max_total_time="$seconds")
  [ -n "${RUNS:-}" ] && limit=(-runs="$RUNS")
  echo "fuzz: $t" >&2
  # The work corpus first (new inputs go there), then the kept regression inputs and seeds.
  ./build-fuzz/fuzz/$t "${limit[@]}" -max_len=4096 -timeout=10 -print_final_stats=1 \
    -artifact_prefix="$findings/" "$work" "fuzz/corpus/$t" 2>&1 | grep -E "^(stat::|#[0-9]+ +DONE|==|SUMMARY|INFO: Seed)" >&2
done
