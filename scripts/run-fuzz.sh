#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Builds the libFuzzer targets of the file parsers (clang-14, ASan + UBSan) in build-fuzz/ and
# runs each for SECONDS, one after the other, niced. Usage:
#   scripts/run-fuzz.sh SECONDS [FuzzMeditMesh FuzzMeditSol FuzzFrd FuzzOff]
# The corpus of each target grows in build-fuzz/corpus/<target> (seeded from
# IO/Kernel/Fuzzing/seeds, Data/ and, when installed, a cut of the CalculiX example result.frd);
# crash inputs land in build-fuzz/crashes/<target>. Exits 1 if any target found a crash.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_PER_TARGET=${1:?usage: run-fuzz.sh SECONDS [target...]}
shift
TARGETS=("$@")
((${#TARGETS[@]})) || TARGETS=(FuzzMeditMesh FuzzMeditSol FuzzFrd FuzzOff)
BUILD_DIR=${AV_FUZZ_BUILD_DIR:-build-fuzz}
ROOT=$PWD

for p in clang-14 libfuzzer-14-dev; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    echo "[fuzz] installing $p" >&2
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "$p" >/dev/null
  fi
done
if [[ ! -f "$BUILD_DIR/build.ninja" ]]; then
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DAV_KERNELS_ONLY=ON \
    -DAV_BUILD_FUZZERS=ON -DBUILD_TESTING=OFF \
    -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 >/dev/null
fi
nice cmake --build "$BUILD_DIR" --target av_fuzzers

seed() # target dir: copies the seed files of a target into its corpus
{
  local target=$1 dir=$2
  mkdir -p "$dir"
  case $target in
    FuzzMeditMesh) cp "$ROOT"/IO/Kernel/Fuzzing/seeds/*.mesh "$ROOT"/Data/*.mesh "$dir"/ ;;
    FuzzMeditSol) cp "$ROOT"/IO/Kernel/Fuzzing/seeds/*.sol "$ROOT"/Data/*.sol "$dir"/ ;;
    FuzzOff) cp "$ROOT"/IO/Kernel/Fuzzing/seeds/*.off "$dir"/ ;;
    FuzzFrd)
      cp "$ROOT"/IO/Kernel/Fuzzing/seeds/*.frd "$dir"/
      local frd=/usr/share/doc/calculix-cgx-examples/examples/result.frd
      # The example is not ours to commit: a small cut of it (20 nodes, 1 he20, 2 results).
      [[ -f $frd ]] && python3 "$ROOT"/IO/Kernel/Fuzzing/cut_frd.py "$frd" "$dir"/compressor-cut.frd
      ;;
  esac
}

status=0
for t in "${TARGETS[@]}"; do
  corpus=$BUILD_DIR/corpus/$t
  crashes=$BUILD_DIR/crashes/$t
  mkdir -p "$crashes"
  seed "$t" "$corpus"
  echo "[fuzz] $t for ${SECONDS_PER_TARGET}s (corpus $(ls "$corpus" | wc -l) files)" >&2
  # One worker process (-fork=1) that goes on after a crash, so that one run finds them all;
  # 64 KB inputs at most; 2 GB RSS and 1 GB per allocation: a parser that allocates what a
  # header claims without checking it against the file's size is a finding too.
  before=$(ls "$crashes" | wc -l)
  nice "$BUILD_DIR/bin/$t" -fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 \
    -max_total_time="$SECONDS_PER_TARGET" -max_len=65536 -rss_limit_mb=2048 \
    -malloc_limit_mb=1024 -timeout=10 -print_final_stats=1 \
    -artifact_prefix="$crashes/" "$corpus" 2>"$BUILD_DIR/$t.log" || true
  found=$(($(ls "$crashes" | wc -l) - before))
  if ((found > 0)); then
    echo "[fuzz] $t FOUND $found CRASH INPUT(S): see $BUILD_DIR/$t.log and $crashes/" >&2
    status=1
  fi
  grep -E "^#[0-9]+: cov|DONE|stat::" "$BUILD_DIR/$t.log" | tail -n 3 >&2 || true
  echo "[fuzz] $t corpus now $(ls "$corpus" | wc -l) files, $(du -sk "$corpus" | cut -f1) KB" >&2
done
exit $status
