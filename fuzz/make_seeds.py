#!/usr/bin/env python3
"""Writes the small seed inputs of fuzz/corpus/ (CONTRIBUTING.md, "Fuzzing"). Larger real files
(scenes/, data/) are given to the fuzzer by path by scripts/fuzz, not copied."""
import math
import os
import struct
import sys

ROOT = os.path.dirname(os.path.abspath(__file__))


def write(target, name, data):
    d = os.path.join(ROOT, "corpus", target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def particles(n):
    """A small cluster: positions on a 2-particle-spacing lattice, h, m, rho, u, v, T, body."""
    out = []
    for i in range(n):
        x, y, z = (i % 3) * 0.5 - 0.5, (i // 3 % 3) * 0.5 - 0.5, (i // 9) * 0.5 - 0.5
        out.append((x, y, z, 0.65, 0.1 + 0.01 * i, 1.0, (i % 4) / 4, (i % 5) / 5,
                    300.0 + 10 * i, i % 2))
    return out


def ssf(parts, materials):
    """OpenSPH BinaryOutput, version 20210808 (core/ssf_reader.cpp): position, mass, density,
    flag (index), temperature, uvw."""
    n = len(parts)
    quantities = [(0, 0, 1), (1, 0, 0), (3, 0, 0), (42, 0, 5), (46, 0, 0), (1000, 0, 1)]
    head = bytearray(256)
    head[0:4] = b"SPH\0"
    struct.pack_into("<dqqqdq", head, 4, 0.0, n, len(quantities), materials, 0.01, 20210808)
    out = bytes(head)
    for q in quantities:
        out += struct.pack("<qqq", *q)
    blocks = [(0, n)] if materials == 0 else [(0, n // 2), (n // 2, n)][:materials]
    for m, (a, b) in enumerate(blocks):
        if materials == 0:
            out += b"NOMAT\0"
        else:
            out += b"MAT\0" + struct.pack("<qq", m, 2)
            out += struct.pack("<qqd", 7, 2, 2700.0)  # a Float parameter
            out += struct.pack("<qq", 9, 4) + b"basalt\0"  # a String parameter
            for q in quantities:
                out += struct.pack("<qddd", q[0], 0.0, 1e10, 1e-6)
        out += struct.pack("<qq", a, b)
        ps = parts[a:b]
        out += b"".join(struct.pack("<dddd", p[0], p[1], p[2], p[3]) for p in ps)
        out += b"".join(struct.pack("<d", p[4]) for p in ps)
        out += b"".join(struct.pack("<d", p[5]) for p in ps)
        out += b"".join(struct.pack("<q", p[9]) for p in ps)
        out += b"".join(struct.pack("<d", p[8]) for p in ps)
        out += b"".join(struct.pack("<dddd", p[6], p[7], 0.0, 0.0) for p in ps)
    return out + struct.pack("<q", 0)  # no attractors


def ply_header(fmt, n, props):
    lines = ["ply", f"format {fmt} 1.0", f"element vertex {n}"]
    lines += [f"property {t} {name}" for t, name in props]
    return ("\n".join(lines + ["end_header"]) + "\n").encode()


def main():
    ps = particles(27)
    write("ssf", "nomat.ssf", ssf(ps, 0))
    write("ssf", "two_materials.ssf", ssf(ps, 2))

    names = ["x", "y", "z", "h", "m", "rho", "u", "v", "temperature", "body"]
    props = [("float", n) for n in names[:-1]] + [("int", "body")]
    text = "".join(" ".join(repr(v) for v in p) + "\n" for p in ps)
    write("ply", "ascii.ply", ply_header("ascii", len(ps), props) + text.encode())
    body = b"".join(struct.pack("<9fi", *p) for p in ps)
    write("ply", "binary_le.ply", ply_header("binary_little_endian", len(ps), props) + body)
    dprops = [("double", n) for n in names[:4]]
    body = b"".join(struct.pack(">4d", *p[:4]) for p in ps)
    write("ply", "binary_be.ply", ply_header("binary_big_endian", len(ps), dprops) + body)

    csv = ",".join(names) + "\n" + "".join(",".join(repr(v) for v in p) + "\n" for p in ps)
    write("csv", "all_columns.csv", csv)
    write("csv", "xyzh.csv", "x,y,z,h\n" + "".join(f"{p[0]},{p[1]},{p[2]},{p[3]}\n" for p in ps))

    write("scene", "overrides.toml", """name = "small"
[camera]
width = 16
height = 12
[[materials]]
name = "rock"
diffuse = [0.5, 0.4, 0.3]
[[bodies]]
name = "ball"
shape = "ball"
radius = 1.0
particles = 200
material = "rock"
[[bodies]]
name = "ring"
shape = "ring"
inner_radius = 1.5
outer_radius = 2.0
thickness = 0.1
particles = 300
material = "rock"
[compare.thresholds]
"beauty.flip" = { max = 0.1 }
%%
camera.width=20
bodies.ball.particles=100
raymarch.spp=2
realtime.particles.radius=fixed
""")

    write("thresholds", "scenes.toml", """"beauty.flip" = { max = 0.12, warn_max = 0.10 }
["beauty.ssim"]
min = 0.8
warn_min = 0.84
[scenes.planet]
"beauty.flip" = { max = 0.2 }
"depth.rmse" = { max = 1e-3 }
""")

    write("baseline", "baseline.json", """{
  "format": "twinrender-baseline",
  "version": 1,
  "blessed_from": "out/summary.json",
  "tolerances": {
    "beauty.flip": {"better": "lower", "origin": 0.0, "relative": 0.05, "absolute": 0.002, "checked": true},
    "beauty.psnr": {"better": "higher", "origin": 0.0, "relative": 0.0, "absolute": 0.5, "checked": true}
  },
  "scenes": {
    "planet": {"metrics": {"beauty.flip": 0.07, "beauty.psnr": 30.5, "time.realtime_ms": 120.0},
               "settings": {"camera.width": 320}},
    "contact": {"metrics": {"beauty.flip": 0.03}, "settings": null}
  }
}
""")


if __name__ == "__main__":
    sys.exit(main())
