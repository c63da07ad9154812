#!/usr/bin/env bash
# Remakes the frames splash_000.ply ... splash_040.ply with LAMMPS (README.md, "Reproducing"):
# runs splash.in and converts its dumps with dump_to_ply.py.
#
#   data/lammps_splash/make.sh
#
# LAMMPS_WORK: the run folder (default /tmp/lammps_splash); SEED: the thermal velocities' seed
# (default splash.in's). Takes about 30 s of CPU on one core.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
WORK="${LAMMPS_WORK:-/tmp/lammps_splash}"
# The smoothing length written beside every atom, sigma (README.md).
H=1.35

PACKAGES=(lammps python3)
"$HERE/../../scripts/install-packages" "${PACKAGES[@]}"

rm -rf "$WORK"
mkdir -p "$WORK/dumps"
echo "make.sh: running LAMMPS ($(lmp -h | sed -n 's/^Large-scale.* - \(.*\)$/\1/p' | head -1))"
seed=()
[ -n "${SEED:-}" ] && seed=(-var seed "$SEED")
(cd "$WORK" && lmp -in "$HERE/splash.in" -var dir "$WORK/dumps" "${seed[@]}" -log "$WORK/log.lammps" -screen none)
grep -E "^Loop time|^Total wall time" "$WORK/log.lammps"

echo "make.sh: converting to PLY"
/usr/bin/python3 "$HERE/dump_to_ply.py" "$WORK/frames" "$H" "$WORK"/dumps/splash.*.dump

same=0
total=0
for f in "$WORK/frames"/*.ply; do
  total=$((total + 1))
  cmp -s "$f" "$HERE/$(basename "$f")" && same=$((same + 1))
done
echo "make.sh: $same of $total frames byte-identical to the previous ones"
for f in "$WORK/frames"/*.ply; do
  cp "$f" "$HERE/$(basename "$f").tmp"
  mv "$HERE/$(basename "$f").tmp" "$HERE/$(basename "$f")"
done
echo "make.sh: wrote $total frames to $HERE"
