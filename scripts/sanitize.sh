#!/usr/bin/env bash
# The whole test suite built with AddressSanitizer and UndefinedBehaviorSanitizer in ./build-asan (benchmarks
# and the Python module off: the module would need the sanitizer runtime preloaded into python3; -O1, which
# keeps the build short and the checks exact). Any report fails the test that triggers it. Run after
# scripts/setup.sh (same packages).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
# Through ccache where it is installed (scripts/setup.sh installs it), as scripts/setup.sh does.
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR="$PWD"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG" \
      -DCCAL_WERROR=ON -DCCAL_SANITIZE=address,undefined \
      -DCCAL_BUILD_BENCH=OFF -DCCAL_BUILD_PYTHON=OFF >/dev/null
cmake --build build-asan -j "$(nproc)"
built=$(date +%s)
export ASAN_OPTIONS=abort_on_error=1:detect_stack_use_after_return=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Not here (docs/testing.md): the pinned outputs, bit-exact for the release build only; the HTML report's page
# and browser checks; the documentation's printed text; the statement's coverage study (100 calibrations through
# the program); and the tests whose work is large by design, each of which took from 80 s to 340 s of the
# sanitized suite (1570 s of wall time on 2 cores with them, the statement's Monte Carlo check at some 100 times
# its release cost): two 10^6-trial Monte Carlo runs, the lab's week end to end from a design of its own, a
# design beside every other verb's U, and the program's statements of the lab example (its CSV, the report's
# statement, a design's expected U, refused observations, the methods' stability over trials, the correction for
# known errors, the Monte Carlo's shared draws), the rate noise's scatter over simulated runs and the design's run
# sheet as CSV (a whole design, 150-290 s sanitized; the design tests run its search). Their code runs
# sanitized in smaller tests: StatementMonteCarlo.*, Statement.TheMonteCarloCheckStatesTheIntervalItGives,
# ReduceVerb.*, RateNoise.* and the verbs' own.
heavy="^(SamplesCli\.TheDefaultMDecidesTheValidation|Cli\.TheWholeWeekFromTheDesignedRunSheetToTheStatement"
heavy+="|OneCoverage\.EveryVerbStatesTheSameUForTheSameMethod|Statement\.IdentifyWritesCsvOfTheCoefficientsAndTheStatement"
heavy+="|ReportSections\.TheStatementIsIdentifysWithTheReportsModeAndCoverage"
heavy+="|DesignExpected\.TheDesignedPlansExpectedUIsWhatItsStatementGives"
heavy+="|Statement\.ObservationsOfAnotherConfigurationAreRefusedNamingBothFingerprints"
heavy+="|Statement\.TheLabExamplesMethodsDoNotFlipWithTheTrials|Statement\.KnownErrorsAreCorrected"
heavy+="|RateNoise\.SimulatedRunMeansScatterAsTheClosedForm|Cli\.TheMonteCarloDrawsThemAndTheStatementChecksWithThem"
heavy+="|CommandLine\.DesignCsvIsTheRunSheetInRpmSecondsAndDegrees)$"
# build.dispatch_targets runs a digest program under qemu-user as older processors; built with AddressSanitizer it
# gives no digest there (the sanitized run printed only the native one), so it is the release suite's check (its code runs sanitized natively in
# MonteCarloDraws.*, DrawQuantiles.* and MonteCarloSamplers.*).
ctest --test-dir build-asan --output-on-failure -j2 \
  -E "Golden|^report\.|^docs\.commands$|^statement\.coverage|^build\.dispatch_targets$|$heavy"
echo "sanitize: build $((built - start)) s, tests $(($(date +%s) - built)) s" >&2
