#!/usr/bin/env bash
# Reproduces frames/ from a clean Debian 12 machine: fetches OpenSPH at a pinned commit, builds
# its core library and driver.cpp, runs the collision and converts the outputs to PLY.
#
#   data/opensph_collision/make.sh
#
# OPENSPH_REPO: where to clone OpenSPH from (default GitHub; a local clone or mirror works too).
# OPENSPH_WORK: the build and run folder (default /tmp/opensph_collision), kept for a second run.
# JOBS: parallel compile jobs (default 2).
# Takes about 3.5 minutes of CPU to build and 15 s of CPU to run (README.md).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
COMMIT=f3033faf4422a056dcb79cc6643c7c6f3d9fee19
REPO="${OPENSPH_REPO:-https://github.com/pavelsevecek/OpenSPH.git}"
WORK="${OPENSPH_WORK:-/tmp/opensph_collision}"
JOBS="${JOBS:-2}"
# Frames also kept as OpenSPH's own .ssf files: before contact, and mid-collision.
KEEP_SSF=(0000 0012)

PACKAGES=(build-essential cmake git ca-certificates libtbb-dev python3-numpy)
"$HERE/../../scripts/install-packages" "${PACKAGES[@]}"

mkdir -p "$WORK"
SRC="$WORK/opensph"
if [ ! -d "$SRC/.git" ]; then
  echo "make.sh: cloning $REPO"
  rm -rf "$SRC.tmp"
  git clone --quiet --no-checkout --filter=blob:none "$REPO" "$SRC.tmp"
  mv "$SRC.tmp" "$SRC"
fi
# Only the core library and the licence: the rest (GUI, tests, reference files) is not needed.
git -C "$SRC" checkout --quiet "$COMMIT" -- core LICENSE

echo "make.sh: building OpenSPH $COMMIT (core) and the driver"
cmake -S "$HERE" -B "$WORK/build" -DCMAKE_BUILD_TYPE=Release -DOPENSPH_SOURCE="$SRC" \
  -DOPENSPH_VERSION="$COMMIT" >/dev/null
cmake --build "$WORK/build" -j "$JOBS" --target collision >/dev/null

echo "make.sh: running the collision"
rm -rf "$WORK/ssf"
"$WORK/build/collision" "$WORK/ssf" >"$WORK/run.log"
sed -n '1,2p;$p' "$WORK/run.log"

echo "make.sh: converting to PLY"
rm -rf "$WORK/frames"
mkdir -p "$WORK/frames"
/usr/bin/python3 "$HERE/ssf_to_ply.py" "$WORK/frames" "$WORK/ssf"/collision_*.ssf
for f in "${KEEP_SSF[@]}"; do cp "$WORK/ssf/collision_$f.ssf" "$WORK/frames/"; done

if [ -d "$HERE/frames" ]; then
  same=0
  total=0
  for f in "$WORK/frames"/*; do
    total=$((total + 1))
    cmp -s "$f" "$HERE/frames/$(basename "$f")" && same=$((same + 1))
  done
  # A later .ssf frame differs at least in the wallclock time OpenSPH writes into its header.
  echo "make.sh: $same of $total files byte-identical to the previous frames/"
fi
rm -rf "$HERE/frames.tmp"
cp -r "$WORK/frames" "$HERE/frames.tmp"
rm -rf "$HERE/frames"
mv "$HERE/frames.tmp" "$HERE/frames"
echo "make.sh: wrote $(find "$HERE/frames" -type f | wc -l) files, $(du -sh "$HERE/frames" | cut -f1), to $HERE/frames"
