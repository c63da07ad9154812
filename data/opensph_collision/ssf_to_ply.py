#!/usr/bin/python3
"""Converts OpenSPH binary outputs (.ssf) to binary little-endian PLY files with the vertex
properties twinrender reads: float x y z h and uchar body (OpenSPH's body flag). Mass and density
are left out: in this collision m/rho exceeds the raymarcher's volume cap 0.1 (4/3) pi h^3 almost
everywhere (README.md), so they would not change a render, and they would add half again to the
files' size.

    ssf_to_ply.py OUT_DIR FILE.ssf...

writes OUT_DIR/<stem>.ply for each file, through a temporary name, so an interrupted run leaves no
partial file. The .ssf layout is OpenSPH's BinaryOutput::dump (core/io/Output.cpp), version
20210808: little-endian, integers as int64, floating-point values as double, vectors as 4 doubles
(x, y, z, h), per material block the values of each quantity followed by its derivatives.
"""
import os
import struct
import sys

import numpy as np

HEADER_SIZE = 256
VERSION = 20210808
# OpenSPH QuantityId values (core/quantities/QuantityIds.h).
POSITION, MASS, DENSITY, FLAG = 0, 1, 3, 42
# Bytes per value of OpenSPH's ValueEnum: scalar, vector, tensor, symmetric tensor, traceless
# tensor, index.
VALUE_SIZES = [8, 32, 72, 48, 40, 8]
# Bytes of a material parameter by its Settings::Value type index (bool, int, Float, Interval,
# String, Vector, SymmetricTensor, TracelessTensor, EnumWrapper); None: a zero-terminated string.
SETTING_SIZES = [8, 8, 8, 16, None, 32, 48, 40, 16]


class SsfError(Exception):
    pass


class Reader:
    def __init__(self, path):
        self.path = path
        with open(path, "rb") as f:
            self.data = f.read()
        self.pos = 0

    def take(self, n, what):
        if self.pos + n > len(self.data):
            raise SsfError(f"{self.path}: truncated: expected {what} at byte {self.pos}")
        chunk = self.data[self.pos:self.pos + n]
        self.pos += n
        return chunk

    def int64(self, what):
        return struct.unpack("<q", self.take(8, what))[0]

    def cstring(self, what):
        end = self.data.find(b"\0", self.pos)
        if end < 0:
            raise SsfError(f"{self.path}: truncated: expected {what} at byte {self.pos}")
        text = self.data[self.pos:end].decode("latin-1")
        self.pos = end + 1
        return text

    def tag(self, expected):
        found = self.cstring(f'the tag "{expected}"')
        if found != expected:
            raise SsfError(f'{self.path}: expected the tag "{expected}" at byte {self.pos}, '
                           f'found "{found[:32]}"')


def read_ssf(path):
    """Returns (time in s, dict quantity id -> array of the particles' values)."""
    r = Reader(path)
    head = r.take(HEADER_SIZE, "the 256-byte header")
    if head[:4] != b"SPH\0":
        raise SsfError(f"{path}: not an OpenSPH binary output (no \"SPH\" at the start)")
    time = struct.unpack_from("<d", head, 4)[0]
    n, quantity_count, material_count = struct.unpack_from("<qqq", head, 12)
    version = struct.unpack_from("<q", head, 44)[0]
    if version != VERSION:
        raise SsfError(f"{path}: format version {version}, this converter reads {VERSION}")
    quantities = [(r.int64("a quantity id"), r.int64("an order"), r.int64("a value type"))
                  for _ in range(quantity_count)]
    wanted = {POSITION: (4, "<f8"), MASS: (1, "<f8"), DENSITY: (1, "<f8"), FLAG: (1, "<i8")}
    values = {q: np.empty((n, wanted[q][0]), dtype=wanted[q][1])
              for q, _, _ in quantities if q in wanted}
    begin = 0
    for m in range(max(material_count, 1)):
        if material_count > 0:
            r.tag("MAT")
            if r.int64("a material index") != m:
                raise SsfError(f"{path}: material block {m} carries another index")
            for _ in range(r.int64("a parameter count")):
                r.int64("a parameter id")
                size = SETTING_SIZES[r.int64("a parameter type")]
                if size is None:
                    r.cstring("a string parameter")
                else:
                    r.take(size, "a parameter value")
            r.take(32 * quantity_count, "the quantity ranges")
        else:
            r.tag("NOMAT")
        first, end = r.int64("the first particle"), r.int64("the end particle")
        if first != begin or not first <= end <= n:
            raise SsfError(f"{path}: material {m} covers particles [{first}, {end})")
        count = end - first
        for q, order, value_type in quantities:
            for k in range(order + 1):
                chunk = r.take(count * VALUE_SIZES[value_type], f"the values of quantity {q}")
                if k == 0 and q in wanted:
                    values[q][first:end] = np.frombuffer(chunk, dtype=wanted[q][1]).reshape(
                        count, wanted[q][0])
        begin = end
    if begin != n:
        raise SsfError(f"{path}: the material blocks hold {begin} of {n} particles")
    return time, values


def write_ply(path, time, values, source):
    pos = values[POSITION]
    n = len(pos)
    columns = [("x", "float"), ("y", "float"), ("z", "float"), ("h", "float"), ("body", "uchar")]
    vertex = np.empty(n, dtype=[(name, "<f4" if t == "float" else "u1") for name, t in columns])
    for i, name in enumerate("xyzh"):
        vertex[name] = pos[:, i]
    vertex["body"] = values[FLAG][:, 0]
    header = (f"ply\nformat binary_little_endian 1.0\n"
              f"comment OpenSPH output {source}, converted by ssf_to_ply.py\n"
              f"comment time {time:.6g} s, positions and h in metres; body 0 target, 1 impactor\n"
              f"element vertex {n}\n"
              + "".join(f"property {t} {name}\n" for name, t in columns)
              + "end_header\n")
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(vertex.tobytes())
    os.replace(tmp, path)


def main(argv):
    if len(argv) < 3:
        sys.exit("usage: ssf_to_ply.py OUT_DIR FILE.ssf...")
    out_dir = argv[1]
    for path in argv[2:]:
        try:
            time, values = read_ssf(path)
        except (SsfError, OSError) as e:
            sys.exit(f"ssf_to_ply.py: {e}")
        missing = [name for q, name in [(POSITION, "position"), (FLAG, "flag")] if q not in values]
        if missing:
            sys.exit(f"ssf_to_ply.py: {path}: no {', '.join(missing)} quantity")
        stem = os.path.splitext(os.path.basename(path))[0]
        write_ply(os.path.join(out_dir, stem + ".ply"), time, values, os.path.basename(path))


if __name__ == "__main__":
    main(sys.argv)
