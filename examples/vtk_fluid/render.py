#!/usr/bin/python3
"""VTK's screen-space fluid renderer (vtkOpenGLFluidMapper, Debian's python3-vtk9) as an external
renderer of twinrender's protocol (docs/external.md): it reads the request, draws the exported
particles with the request's camera and the scene's light, and writes the EXR twinrender
compares with the reference:

  R G B      the lit surface, display mode FilteredOpaqueSurface (VTK's own shading);
  N.X N.Y N.Z  world-space normals from display mode FilteredSurfaceNormal, which writes the
             view-space normal's components as colours clamped to [0, 1] (8 bits; a negative
             component is lost). A second draw with the camera turned half a turn about its view
             axis writes the negated x and y: pixel (x, y) of the first is pixel
             (W - 1 - x, H - 1 - y) of the second, so n_x = R1 - R2', n_y = G1 - G2', n_z = B1;
  A          1 where either normal draw drew the fluid.

No Z: VTK 9.1's fluid mapper leaves 0 in the window's depth buffer wherever it draws, so depth is
"not provided". Each display mode draws in a fresh mapper and window (a second mode on the same
mapper draws nothing), with the window's multisampling off (with it the mapper draws nothing).

The mapper's particle radius is one number for every particle: --radius-scale K sets it to K
times the frame's mean smoothing length h (twinrender's impostors default to 0.9 h; the sweep of
docs/peers.md finds VTK's best K). --filter narrow_range (Truong and Yuksel 2018, VTK's default)
or bilateral, or none (the unfiltered display modes). Run under a display (xvfb-run on a machine without one):

  twinrender render SCENE --renderer external \\
      --external-command "xvfb-run -a -s '-screen 0 1280x1024x24' /usr/bin/python3 examples/vtk_fluid/render.py"
"""
import argparse
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "external"))
from twinrender_external import read_ply, read_request, write_exr  # noqa: E402

import numpy as np
import vtk
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLFluidMapper as FluidMapper


def draw(particles: dict, camera: dict, light: dict, mode, radius: float, method,
         flip: bool) -> np.ndarray:
    """One frame of the fluid mapper in display mode `mode`: RGBA floats, row 0 at the top.
    `flip`: the camera turned half a turn about its view axis."""
    points = vtk.vtkPoints()
    xyz = np.stack([particles["x"], particles["y"], particles["z"]], axis=1).astype(np.float32)
    points.SetData(numpy_to_vtk(xyz, deep=True))
    polydata = vtk.vtkPolyData()
    polydata.SetPoints(points)
    mapper = FluidMapper()
    mapper.SetInputData(polydata)
    mapper.SetParticleRadius(radius)
    mapper.SetSurfaceFilterMethod(method)
    mapper.SetDisplayMode(mode)
    mapper.SetOpaqueColor(0.6, 0.6, 0.6)
    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    renderer = vtk.vtkRenderer()
    renderer.AddVolume(volume)
    renderer.SetBackground(0.0, 0.0, 0.0)
    renderer.RemoveAllLights()
    sun = vtk.vtkLight()
    sun.SetLightTypeToSceneLight()
    sun.SetPositional(False)
    sun.SetFocalPoint(0.0, 0.0, 0.0)
    sun.SetPosition(*(-np.asarray(light["direction"], dtype=np.float64)))
    sun.SetColor(*light["color"])
    sun.SetIntensity(min(1.0, light["intensity"] / 3.0))
    renderer.AddLight(sun)
    view = renderer.GetActiveCamera()
    view.SetPosition(*camera["position"])
    view.SetFocalPoint(*camera["target"])
    up = np.asarray(camera["up"], dtype=np.float64)
    view.SetViewUp(*(-up if flip else up))
    view.SetViewAngle(camera["fov_y_deg"])
    view.SetClippingRange(camera["near"], camera["far"])
    window = vtk.vtkRenderWindow()
    window.SetMultiSamples(0)
    window.SetOffScreenRendering(1)
    window.SetSize(camera["width"], camera["height"])
    window.AddRenderer(renderer)
    window.Render()
    pixels = vtk.vtkFloatArray()
    window.GetRGBAPixelData(0, 0, camera["width"] - 1, camera["height"] - 1, 0, pixels)
    image = vtk_to_numpy(pixels).reshape(camera["height"], camera["width"], 4)[::-1].copy()
    window.Finalize()
    return image


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--radius-scale", type=float, default=1.0,
                        help="the mapper's particle radius over the mean h (default 1.0)")
    parser.add_argument("--filter", choices=("narrow_range", "bilateral", "none"),
                        default="narrow_range",
                        help="the mapper's surface filter; none: its unfiltered display modes")
    parser.add_argument("request", type=Path)
    args = parser.parse_args()
    folder = args.request.parent
    request, scene = read_request(args.request)
    particles = read_ply(folder / request["particles"])
    camera = dict(request["camera"])
    radius = args.radius_scale * float(np.mean(particles["h"]))
    method = FluidMapper.NarrowRange if args.filter == "narrow_range" else FluidMapper.BilateralGaussian
    surface = (FluidMapper.UnfilteredOpaqueSurface if args.filter == "none"
               else FluidMapper.FilteredOpaqueSurface)
    normals = (FluidMapper.UnfilteredSurfaceNormal if args.filter == "none"
               else FluidMapper.FilteredSurfaceNormal)

    start = time.perf_counter()
    beauty = draw(particles, camera, scene["light"], surface, radius, method, flip=False)
    beauty_ms = (time.perf_counter() - start) * 1e3
    first = draw(particles, camera, scene["light"], normals, radius, method, flip=False)
    turned = draw(particles, camera, scene["light"], normals, radius, method, flip=True)[::-1, ::-1]
    covered = (first[..., :3].sum(-1) + turned[..., :3].sum(-1)) > 0.0
    view_normal = np.stack([first[..., 0] - turned[..., 0], first[..., 1] - turned[..., 1],
                            np.maximum(first[..., 2], turned[..., 2])], axis=-1)
    view_normal /= np.maximum(np.linalg.norm(view_normal, axis=-1, keepdims=True), 1e-12)
    right = np.asarray(camera["right"], dtype=np.float64)
    up = np.asarray(camera["up"], dtype=np.float64)
    forward = np.asarray(camera["forward"], dtype=np.float64)
    world = (view_normal[..., 0:1] * right + view_normal[..., 1:2] * up
             - view_normal[..., 2:3] * forward)
    channels = {"R": beauty[..., 0], "G": beauty[..., 1], "B": beauty[..., 2],
                "A": covered.astype(np.float32),
                "N.X": world[..., 0], "N.Y": world[..., 1], "N.Z": world[..., 2]}
    for name in ("R", "G", "B", "N.X", "N.Y", "N.Z"):
        channels[name] = np.where(covered, channels[name], 0.0)
    write_exr(folder / request["output"]["image"], channels)
    # The frame's time: the beauty's draw (one display mode, as an application draws it).
    (folder / request["output"]["timings"]).write_text(json.dumps({"total": beauty_ms}))
    return 0


def main_with_retries(tries: int = 5) -> int:
    """main() in a child process, tried again when VTK aborted it for want of an X connection.

    VTK aborts the process (SIGABRT, "bad X server connection") when it cannot open the display
    for a window, which a loaded Xvfb sometimes refuses for a moment; the same request then draws
    on the next try. Any other failure, and the last try's, is the adapter's own result."""
    if os.environ.get("TWINRENDER_VTK_CHILD") == "1":
        return main()
    env = dict(os.environ, TWINRENDER_VTK_CHILD="1")
    for attempt in range(tries):
        child = subprocess.run([sys.executable, os.path.abspath(__file__), *sys.argv[1:]],
                               env=env, stderr=subprocess.PIPE, text=True)
        refused = (child.returncode == -signal.SIGABRT
                   and "bad X server connection" in child.stderr)
        if not refused or attempt == tries - 1:
            sys.stderr.write(child.stderr)
            return 128 + signal.SIGABRT if child.returncode == -signal.SIGABRT else child.returncode
        time.sleep(1.0 + attempt)
    return 1


if __name__ == "__main__":
    sys.exit(main_with_retries())
