#!/usr/bin/python3
"""An external renderer for twinrender's protocol (docs/external.md) that draws one particle's
level-set sphere exactly: it reads the request, the exported scene and particles, finds the
radius where the particle's colour field falls to the surface level (bisection on the M4
kernel), casts a ray through every pixel centre with the exported view and projection matrices,
and writes beauty, coverage, eye depth and normals. Debian's python3-numpy and
python3-openimageio. Usage: analytic_sphere.py REQUEST.json

ANALYTIC_SPHERE_FAULT makes it misbehave as the protocol's tests need: "nan" (a NaN pixel),
"size" (one column too many), "depth" (a depth buffer's value in [0, 1] instead of eye depth)."""
import json
import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent.parent / "examples" / "external"))
from twinrender_external import read_ply, read_request, write_exr  # noqa: E402

import numpy as np


def m4(q):
    """w(q) of the M4 cubic spline (support 2)."""
    return np.where(q < 1.0, 1.0 - 1.5 * q * q + 0.75 * q ** 3,
                    np.where(q < 2.0, 0.25 * (2.0 - q) ** 3, 0.0))


def level_set_radius(volume: float, h: float, level: float) -> float:
    """The r where volume * w(r / h) / (pi h^3) = level (w falls monotonically)."""
    lo, hi = 0.0, 2.0 * h
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if volume * m4(mid / h) / (np.pi * h ** 3) > level:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def main() -> int:
    request_path = Path(sys.argv[1])
    folder = request_path.parent
    request, scene = read_request(request_path)
    p = read_ply(folder / request["particles"])
    if len(p["x"]) != 1:
        print(f"this renderer draws one particle; the scene has {len(p['x'])}", file=sys.stderr)
        return 2
    centre = np.array([p["x"][0], p["y"][0], p["z"][0]], dtype=np.float64)
    radius = level_set_radius(float(p["volume"][0]), float(p["h"][0]), scene["surface"]["level"])
    camera = request["camera"]
    width, height = request["width"], request["height"]
    view = np.array(camera["view_matrix"], dtype=np.float64)
    projection = np.array(camera["projection_matrix"], dtype=np.float64)
    inverse = np.linalg.inv(projection @ view)
    # Pixel centres (row 0 at the top) in NDC, through the near and far planes.
    xs = (np.arange(width) + 0.5) / width * 2.0 - 1.0
    ys = 1.0 - (np.arange(height) + 0.5) / height * 2.0
    ndc_x, ndc_y = np.meshgrid(xs, ys)
    def unproject(z):
        clip = np.stack([ndc_x, ndc_y, np.full_like(ndc_x, z), np.ones_like(ndc_x)], axis=-1)
        world = clip @ inverse.T
        return world[..., :3] / world[..., 3:4]
    origin = np.array(camera["position"], dtype=np.float64)
    direction = unproject(1.0) - unproject(-1.0)
    direction /= np.linalg.norm(direction, axis=-1, keepdims=True)
    oc = origin - centre
    b = direction @ oc
    disc = b * b - (oc @ oc - radius * radius)
    hit = disc >= 0.0
    t = -b - np.sqrt(np.where(hit, disc, 0.0))
    point = origin + t[..., None] * direction
    normal = (point - centre) / radius
    eye = np.concatenate([point, np.ones_like(t)[..., None]], axis=-1) @ view.T
    depth = np.where(hit, -eye[..., 2], np.inf)
    to_light = -np.array(scene["light"]["direction"], dtype=np.float64)
    lambert = np.clip(normal @ to_light, 0.0, None) * 0.6 * scene["light"]["intensity"]
    channels = {"R": lambert, "G": lambert, "B": lambert, "A": hit.astype(np.float64), "Z": depth,
                "N.X": normal[..., 0], "N.Y": normal[..., 1], "N.Z": normal[..., 2]}
    for name in ("R", "G", "B", "N.X", "N.Y", "N.Z"):
        channels[name] = np.where(hit, channels[name], 0.0)
    fault = os.environ.get("ANALYTIC_SPHERE_FAULT", "")
    if fault == "nan":
        channels["R"][0, 0] = np.nan
    if fault == "depth":
        n, f = camera["near"], camera["far"]
        channels["Z"] = np.where(hit, (f + n - 2.0 * f * n / np.where(hit, depth, 1.0)) /
                                 (f - n) * 0.5 + 0.5, 1.0)
    if fault == "size":
        width += 1
        channels = {k: np.concatenate([v, v[:, :1]], axis=1) for k, v in channels.items()}
    write_exr(folder / request["output"]["image"], channels)
    (folder / request["output"]["timings"]).write_text(json.dumps({"total": 0.5}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
