#!/usr/bin/env python3
"""Converts LAMMPS text dumps (`id x y z`, sorted by id, as splash.in writes them) to the binary
little-endian PLY frames of this folder: float x y z h per atom, h the smoothing length given.

    dump_to_ply.py OUT_DIR H DUMP...

Frame k is the k-th dump in time-step order, written as OUT_DIR/splash_%03d.ply."""
import struct
import sys
from pathlib import Path


def read_dump(path: Path):
    """The dump's time step and its atoms' (x, y, z), in id order."""
    lines = path.read_text().splitlines()
    step = int(lines[lines.index("ITEM: TIMESTEP") + 1])
    count = int(lines[lines.index("ITEM: NUMBER OF ATOMS") + 1])
    start = next(i for i, line in enumerate(lines) if line.startswith("ITEM: ATOMS")) + 1
    columns = lines[start - 1].split()[2:]
    if columns[:4] != ["id", "x", "y", "z"]:
        sys.exit(f"{path}: columns {columns}, expected id x y z")
    atoms = [line.split() for line in lines[start:start + count]]
    ids = [int(a[0]) for a in atoms]
    if ids != sorted(ids) or len(atoms) != count:
        sys.exit(f"{path}: atoms not sorted by id, or fewer than {count}")
    return step, [(float(a[1]), float(a[2]), float(a[3])) for a in atoms]


def write_ply(path: Path, step: int, atoms, h: float):
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        "comment LAMMPS Lennard-Jones liquid drop onto a reflecting wall, reduced units, "
        f"timestep {step}\n"
        f"element vertex {len(atoms)}\n"
        "property float x\nproperty float y\nproperty float z\nproperty float h\nend_header\n")
    body = b"".join(struct.pack("<4f", x, y, z, h) for x, y, z in atoms)
    path.write_bytes(header.encode() + body)


def main() -> int:
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    out, h = Path(sys.argv[1]), float(sys.argv[2])
    frames = sorted(read_dump(Path(p)) for p in sys.argv[3:])
    out.mkdir(parents=True, exist_ok=True)
    for k, (step, atoms) in enumerate(frames):
        write_ply(out / f"splash_{k:03d}.ply", step, atoms, h)
    return 0


if __name__ == "__main__":
    sys.exit(main())
