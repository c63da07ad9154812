"""What a Python renderer needs to speak twinrender's external renderer protocol
(docs/external.md): read the request and the exported scene, read the particles (binary PLY),
write the image (an EXR of named float channels). Debian's python3-numpy and
python3-openimageio. Used by examples/vtk_fluid/render.py and tests/adapters/."""
import json
from pathlib import Path

import numpy as np
import OpenImageIO as oiio


def read_request(path: Path):
    """The request (checked to be version 1) and the exported scene it names."""
    request = json.loads(path.read_text())
    if request.get("format") != "twinrender-request" or request.get("version") != 1:
        raise ValueError(f"{path}: not a twinrender request of version 1")
    scene = json.loads((path.parent / request["scene"]).read_text())
    return request, scene


def read_ply(path: Path) -> dict:
    """The vertex properties of twinrender's binary little-endian PLY as arrays by name."""
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    names, types, count = [], [], 0
    for line in data[:end].decode().splitlines():
        words = line.split()
        if words[:2] == ["element", "vertex"]:
            count = int(words[2])
        elif words[:1] == ["property"]:
            types.append({"float": "<f4", "uint": "<u4"}[words[1]])
            names.append(words[2])
    records = np.frombuffer(data, dtype=list(zip(names, types)), count=count, offset=end)
    return {name: records[name] for name in names}


def write_exr(path: Path, channels: dict) -> None:
    """One float32 EXR of the named channels (arrays of height x width, row 0 at the top)."""
    names = list(channels)
    pixels = np.stack([channels[n] for n in names], axis=-1).astype(np.float32)
    height, width = pixels.shape[:2]
    spec = oiio.ImageSpec(width, height, len(names), oiio.FLOAT)
    spec.channelnames = tuple(names)
    out = oiio.ImageOutput.create(str(path))
    if not out or not out.open(str(path), spec):
        raise OSError(f"cannot write {path}: {oiio.geterror()}")
    out.write_image(pixels)
    out.close()
