#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Makes the real-data inputs of the tests and the benchmark from Debian's own solvers and
# datasets (nothing is bundled in this repository): CalculiX stress fields, OpenFOAM strain
# rates, CGAL's CC0 surfaces and the compressor. Idempotent: an input that exists is kept.
# Documentation/real-data.md lists each input, its package, licence, size and field.
#
# usage: scripts/make-real-data.sh [OUTDIR]      (default build/real-data)
# env:   AV_REAL_DATA_NO_INSTALL=1  never call apt-get (fail if a package is missing)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
OUT=${1:-$ROOT/build/real-data}
# Absolute: the solvers run in their own folders and write their logs here.
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
HERE=$ROOT/scripts/real-data
START=$SECONDS

# Packages the inputs come from (not needed to build AnisoVoronoi, so not in setup.sh).
PACKAGES=(calculix-ccx calculix-ccx-test calculix-cgx-examples openfoam openfoam-examples
  libcgal-demo paraview python3-paraview python3-numpy)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  if [[ ${AV_REAL_DATA_NO_INSTALL:-0} == 1 ]]; then
    echo "[real-data] missing packages: ${missing[*]}" >&2
    exit 1
  fi
  echo "[real-data] installing: ${missing[*]}" >&2
  SUDO=""
  [[ $(id -u) -ne 0 ]] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends -o DPkg::Lock::Timeout=600 \
    "${missing[@]}" >/dev/null
fi

mkdir -p "$OUT/work" "$OUT/logs"
MADE=()
KEPT=()

# step NAME OUTPUT... : true when every OUTPUT exists already (then NAME is reported as kept)
have() {
  local name=$1
  shift
  for f in "$@"; do
    [[ -s $OUT/$f ]] || return 1
  done
  KEPT+=("$name")
}

# CalculiX: a test deck with nodal output requested (prepare_ccx_deck.py), solved by ccx.
ccx_input() {
  local name=$1 deck=$2
  shift 2
  have "$name" "$name.frd" && return 0
  local t=$SECONDS dir=$OUT/work/$name
  rm -rf "$dir" && mkdir -p "$dir"
  python3 "$HERE/prepare_ccx_deck.py" \
    "/usr/share/doc/calculix-ccx-test/examples/test/$deck.inp.gz" "$dir/$deck.inp" "$@"
  # One thread: the CI machine has two cores and the solves are small.
  if ! (cd "$dir" && OMP_NUM_THREADS=1 ccx -i "$deck" >"$OUT/logs/$name.log" 2>&1); then
    echo "[real-data] ccx failed on $deck, see $OUT/logs/$name.log" >&2
    exit 1
  fi
  grep -q "^ -4  STRESS" "$dir/$deck.frd" || { echo "[real-data] $deck.frd has no STRESS" >&2; exit 1; }
  mv "$dir/$deck.frd" "$OUT/$name.frd"
  rm -rf "$dir"
  MADE+=("$name ($((SECONDS - t)) s)")
}

# OpenFOAM: a tutorial at a coarser block resolution, blockMesh + N solver iterations, then
# the strain rate (foam_to_vtu.py, pvpython) as .vtu and .frd.
foam_input() {
  local name=$1 tutorial=$2 solver=$3 velocity=$4 scale=$5 iterations=$6
  have "$name" "$name.vtu" "$name.frd" && return 0
  local t=$SECONDS dir=$OUT/work/$name
  rm -rf "$dir" && mkdir -p "$dir"
  cp -r "/usr/share/doc/openfoam-examples/examples/$tutorial/." "$dir/"
  find "$dir" -name '*.gz' -exec gunzip -f {} +
  python3 "$HERE/scale_block_mesh.py" "$dir/system/blockMeshDict" "$scale"
  sed -i -E "s/^(endTime[[:space:]]+)[0-9]+;/\1$iterations;/; \
    s/^(writeInterval[[:space:]]+)[0-9]+;/\1$iterations;/" "$dir/system/controlDict"
  if ! (
    set +eu
    # shellcheck disable=SC1091
    source /usr/share/openfoam/etc/bashrc >/dev/null 2>&1
    set -e
    cd "$dir"
    blockMesh >"$OUT/logs/$name.blockMesh.log" 2>&1
    "$solver" >"$OUT/logs/$name.$solver.log" 2>&1
  ); then
    echo "[real-data] OpenFOAM failed on $tutorial, see $OUT/logs/$name.*.log" >&2
    exit 1
  fi
  pvpython "$HERE/foam_to_vtu.py" "$dir" "$velocity" "$OUT/work/$name-out" \
    >"$OUT/logs/$name.convert.log" 2>&1 || {
    echo "[real-data] conversion failed, see $OUT/logs/$name.convert.log" >&2
    exit 1
  }
  mv "$OUT/work/$name-out.vtu" "$OUT/$name.vtu"
  mv "$OUT/work/$name-out.frd" "$OUT/$name.frd"
  rm -rf "$dir"
  MADE+=("$name ($((SECONDS - t)) s)")
}

# CGAL's demo meshes (CC0): the .off as shipped and a .vtp copy.
surface_inputs() {
  local names=(turbine knot1 mushroom fandisk_large)
  local files=()
  for n in "${names[@]}"; do files+=("$n.off" "$n.vtp"); done
  have "surfaces" "${files[@]}" && return 0
  local t=$SECONDS
  local members=()
  for n in "${names[@]}"; do members+=("data/meshes/$n.off"); done
  tar xzf /usr/share/doc/libcgal-dev/data.tar.gz -C "$OUT/work" "${members[@]}"
  for n in "${names[@]}"; do
    mv "$OUT/work/data/meshes/$n.off" "$OUT/$n.off"
  done
  pvpython "$HERE/off_to_vtp.py" "$OUT" "${names[@]}" >"$OUT/logs/surfaces.log" 2>&1 || {
    echo "[real-data] .off -> .vtp failed, see $OUT/logs/surfaces.log" >&2
    exit 1
  }
  rm -rf "$OUT/work/data"
  MADE+=("surfaces ($((SECONDS - t)) s)")
}

compressor_input() {
  have compressor compressor.frd && return 0
  cp /usr/share/doc/calculix-cgx-examples/examples/result.frd "$OUT/compressor.frd"
  MADE+=("compressor")
}

compressor_input
surface_inputs
foam_input foam-squarebend incompressible/simpleFoam/squareBend simpleFoam U 0.5 100
foam_input foam-mixer incompressible/SRFSimpleFoam/mixer SRFSimpleFoam Urel 0.6 100
ccx_input ccx-rotor rotor --keep-steps 1
ccx_input ccx-segmenttet segmenttet --modes 4
ccx_input ccx-cubef2f1 cubef2f1
ccx_input ccx-hueeber1 hueeber1

rmdir "$OUT/work" 2>/dev/null || true
echo "[real-data] $OUT: made ${#MADE[@]}${MADE:+: ${MADE[*]}}; kept ${#KEPT[@]}${KEPT:+: ${KEPT[*]}}"
echo "[real-data] total $((SECONDS - START)) s"
