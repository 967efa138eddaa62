#!/usr/bin/env bash
# The speed figures of docs/model.md §12 side by side with those of a previous release: the Monte Carlo of the
# bundled example (trials/s on 2 threads), a draw's normal quantile (ns), the statement's Monte Carlo check on
# the lab example (µs a trial),
# `ccal design` of the bundled example (s), the streamed reduction of a
# run log (MB/s on one core), and the kernels behind them. Both are built in Release (through ccache): this
# tree in ./build (scripts/setup.sh must have run), the release in ./build-bench/<ref> from a git worktree.
#   bash scripts/bench.sh            against the newest release tag (v*), or without tags the last commit of
#                                    the day CHANGELOG.md dates its newest release
#   bash scripts/bench.sh v0.1.0     against a given tag or commit
# A figure the release has no benchmark for is shown as "-". Run it on a quiet machine: the figures are wall
# times.
set -euo pipefail
cd "$(dirname "$0")/.."
ref=${1:-$(git tag --list 'v*' --sort=-version:refname | head -n1)}
if [ -z "$ref" ]; then
  # A clone without tags: the newest release CHANGELOG.md dates ("## [0.1.0] - 2026-12-01"), as the last
  # commit of that day (UTC).
  release=$(grep -m1 -E '^## \[[0-9]+\.[0-9]+\.[0-9]+\] - [0-9]{4}-[0-9]{2}-[0-9]{2}' CHANGELOG.md || true)
  if [ -n "$release" ]; then
    day=${release##* - }
    ref=$(git rev-list -1 --before="${day}T23:59:59Z" HEAD)
    version=${release#*[}
    echo "bench: no release tag; comparing with ${version%%]*}, the last commit of $day: $(git log -1 --format='%h' "$ref")"
  fi
fi
if [ -z "$ref" ]; then
  echo "bench: no release tag (v*) and no dated release in CHANGELOG.md to compare with; accepted: a tag or commit as the argument" >&2
  exit 2
fi
if ! git rev-parse --verify --quiet "$ref^{commit}" >/dev/null; then
  echo "bench: '$ref' is not a tag or commit of this repository" >&2
  exit 2
fi

export CCACHE_BASEDIR="$PWD"
targets=(bench_montecarlo bench_statement bench_design bench_reduce)
cmake --build build --target "${targets[@]}" >/dev/null

# The release: its own worktree and build folder (kept, so that a second run only reruns the benchmarks).
out=build-bench
ref_dir=$out/$(echo "$ref" | tr '/' '_')
if [ ! -d "$ref_dir/src" ]; then
  mkdir -p "$ref_dir"
  git worktree add --detach "$ref_dir/src" "$ref" >/dev/null 2>&1
fi
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# (Its configure log is kept, and shown only if it fails: the release's own warnings are not this run's.)
if ! cmake -S "$ref_dir/src" -B "$ref_dir/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCCAL_BUILD_TESTS=OFF \
      -DCCAL_BUILD_PYTHON=OFF -DCCAL_BUILD_BENCH=ON "${launcher[@]}" >"$ref_dir/configure.log" 2>&1; then
  cat "$ref_dir/configure.log" >&2
  exit 1
fi
ref_targets=()
for t in "${targets[@]}"; do
  [ -f "$ref_dir/src/bench/$t.cpp" ] && ref_targets+=("$t")
done
CCACHE_BASEDIR="$PWD/$ref_dir/src" cmake --build "$ref_dir/build" --target "${ref_targets[@]}" >/dev/null

# Each benchmark program of both builds as JSON, each figure the median of three repetitions (the log
# reduction on a 512 MB log).
run() {  # run <build folder> <program> <json out>
  if [ -x "$1/bench/$2" ]; then
    CCAL_BENCH_LOG_MB=512 "$1/bench/$2" --benchmark_filter="$filter" --benchmark_format=json \
      --benchmark_min_time=1 --benchmark_repetitions=3 --benchmark_report_aggregates_only=true >"$3" 2>/dev/null || echo '{"benchmarks": []}' >"$3"
  else
    echo '{"benchmarks": []}' >"$3"
  fi
}
filter='^(Pipeline/[12](/0)?/real_time|StatementCheck/100000/2/|WholeDesign|CandidateCache|StreamedLog|RunMeansKernel|NormalQuantiles)'
for t in "${targets[@]}"; do
  run build "$t" "$out/now_$t.json"
  run "$ref_dir/build" "$t" "$out/ref_$t.json"
done

/usr/bin/python3 - "$ref" "$out" "${targets[@]}" <<'EOF'
import json, re, sys
ref, out, targets = sys.argv[1], sys.argv[2], sys.argv[3:]

def load(prefix):
    """The medians of the repetitions, under the benchmark's own name."""
    rows = []
    for t in targets:
        for b in json.load(open(f"{out}/{prefix}_{t}.json")).get("benchmarks", []):
            if b.get("run_type") == "aggregate":
                if b.get("aggregate_name") != "median":
                    continue
                b = dict(b, name=b["name"].removesuffix("_median"))
            rows.append(b)
    return rows

# (label, name pattern, value, unit): the value of the first benchmark whose name matches.
figures = [
    ("Monte Carlo, bundled example, 1 thread", r"^Pipeline/1(/0)?/real_time$", "items_per_second", "trials/s"),
    ("Monte Carlo, bundled example, 2 threads", r"^Pipeline/2(/0)?/real_time$", "items_per_second", "trials/s"),
    ("run means of one trial (kernel)", r"^RunMeansKernel$", "real_time", "us"),
    ("run means of a trial in a batch of 32 (kernel)", r"^RunMeansKernelBatch$", "us_per_trial", "us/trial"),
    ("a draw's normal quantile (in lanes)", r"^NormalQuantiles$", "ns_per_item", "ns"),
    ("statement's Monte Carlo check, lab, 2 threads", r"^StatementCheck/100000/2/", "us_per_trial", "us/trial"),
    ("design, bundled example (whole, first time)", r"^WholeDesign(/0)?/", "real_time", "s"),
    ("design, again from the cache", r"^WholeDesign/1/", "real_time", "s"),
    ("design, candidate rows", r"^CandidateCache", "real_time", "s"),
    ("run log reduction, one core", r"^StreamedLog", "bytes_per_second", "MB/s"),
]

def value(rows, pattern, key):
    for b in rows:
        if re.search(pattern, b["name"]):
            if key == "ns_per_item":
                return 1e9 / b["items_per_second"]
            v = b[key]
            if key == "bytes_per_second":
                return v / 2**20
            if key == "real_time":
                scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
                return v * scale
            return v
    return None

def shown(v, unit):
    if v is None:
        return "-"
    if unit == "us":
        return f"{v * 1e6:.3g}"
    return f"{v:.4g}"

now, before = load("now"), load("ref")
label = ref if len(ref) < 13 else ref[:7]
print(f"{'figure':44} {'unit':9} {label:>12} {'now':>12} {'speed-up':>12}")
for label, pattern, key, unit in figures:
    a, b = value(before, pattern, key), value(now, pattern, key)
    # A ratio above 1 is faster: rates divide now by before, times before by now.
    ratio = "-" if a is None or b is None else f"{(b / a if key not in ('real_time', 'us_per_trial', 'ns_per_item') else a / b):.2f}x"
    print(f"{label:44} {unit:9} {shown(a, unit):>12} {shown(b, unit):>12} {ratio:>12}")
EOF
