#!/bin/bash
# Writes the sample DAQ folders of examples/daq anew from their configurations, with the program of the build
# tree (or $CCAL): the commands each folder's configuration names in its header, and the 5 s dropout of the
# semicolon folder. The tests and the tutorial read these folders; run this after a change to how logs are
# written, and commit the folders it rewrites.
#
#   bash scripts/make_daq_examples.sh
set -euo pipefail
cd "$(dirname "$0")/.."
ccal=${CCAL:-build/ccal}
daq=examples/daq
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$ccal" simulate $daq/lab_short.toml --truth examples/lab_truth.toml --logs-out "$work/comma" -o /dev/null
"$ccal" simulate $daq/lab_short.toml --truth examples/lab_truth.toml --logs-out "$work/semicolon" \
  --log-layout $daq/semicolon_layout.toml -o /dev/null
# The dropout: the rows of 10 s < t < 15 s taken out of 20g.csv (t in ms, the first field; the first four lines
# are the preamble, the header and the units row).
awk -F';' 'NR <= 4 || !($1 + 0 > 10000 && $1 + 0 < 15000)' "$work/semicolon/20g.csv" > "$work/20g.csv"
mv "$work/20g.csv" "$work/semicolon/20g.csv"
"$ccal" simulate $daq/two_short.toml --draw-truth --seed 7 --logs-out "$work/two_instruments" -o /dev/null

for folder in comma semicolon two_instruments; do
  rm -rf "${daq:?}/$folder"
  mv "$work/$folder" "$daq/$folder"
  echo "make_daq_examples: wrote $daq/$folder ($(ls "$daq/$folder" | wc -l) files)"
done
