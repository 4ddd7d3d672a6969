#!/usr/bin/env bash
# Writes the fuzz seed corpus with dmpscope's own writers.
set -euo pipefail
cd "$(dirname "$0")/.."
out=fuzz/corpus/load
mkdir -p "$out"
# DMPSCOPE_BIN: a dmpscope already built (else a release build of this one).
dmpscope() {
  if [ -n "${DMPSCOPE_BIN:-}" ]; then "$DMPSCOPE_BIN" "$@"; else dmpscope "$@"; fi
}
dmpscope gen-sample --demos 2 --out "$out/pose2-zstd.mcap"
dmpscope gen-sample --demos 3 --uncompressed --out "$out/pose3-plain.mcap"
dmpscope regen "$out/pose2-zstd.mcap" --dm 10 --km 20 --out "$out/pose-in-frame-json.mcap"
dmpscope gen-sample --demos 1 --seed 7 --out "$out/pose1.mcap"
head -c 700 "$out/pose3-plain.mcap" > "$out/truncated.mcap"
# The streaming path: the same MCAP seeds, an indexed uncompressed lab take
# (message-by-message reads), and hostile files.
mkdir -p fuzz/corpus/stream fuzz/corpus/bag
cp "$out"/*.mcap fuzz/corpus/stream/
dmpscope gen-sample --lab 3 --uncompressed --chunk-mb 1 --out fuzz/corpus/stream/lab-plain.mcap
dmpscope gen-sample --hostile fuzz/corpus/hostile
cp fuzz/corpus/hostile/*.mcap fuzz/corpus/stream/
cp fuzz/corpus/hostile/*.bag fuzz/corpus/bag/
cp core/tests/bags/*/*.bag fuzz/corpus/bag/
# The CSV readers: a plain file and a Motive export (the core's test's).
mkdir -p fuzz/corpus/csv
printf 't,x,y,z,qx,qy,qz,qw\n0,0,0,0,0,0,0,1\n0.01,0.1,0,0,0,0,0,1\n' > fuzz/corpus/csv/plain.csv
sed -n '/^Format Version/,/^";$/p' core/src/load/motive.rs | sed '$d' | sed 's/\\"/"/g' > fuzz/corpus/csv/motive.csv
ls -la "$out" fuzz/corpus/stream fuzz/corpus/bag fuzz/corpus/csv
