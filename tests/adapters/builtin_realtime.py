#!/usr/bin/python3
"""twinrender's own real-time renderer as an external renderer of the protocol: it renders the
request's source scene (scene.json's "source") with `twinrender render --renderer realtime
--frames FRAME` at the request's size and frame, and hands its AOV image over. The protocol's own end-to-end test
(tests/external_renderer_test.cpp) runs a suite through it and through the built-in path and
finds the same metrics. Usage: builtin_realtime.py TWINRENDER REQUEST.json"""
import shutil
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent.parent / "examples" / "external"))
from twinrender_external import read_request  # noqa: E402


def main() -> int:
    tool, request_path = sys.argv[1], Path(sys.argv[2])
    request, scene = read_request(request_path)
    folder = request_path.parent
    out = folder / "builtin"
    frame = request["frame"]
    cmd = [tool, "render", scene["source"], "--renderer", "realtime", "--out", str(out),
           "--frames", str(frame), "--set", f"camera.width={request['width']}",
           "--set", f"camera.height={request['height']}"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    # render --frames writes each frame into its folder: four digits, a minus sign below zero.
    folder_name = f"{frame:04d}" if frame >= 0 else f"-{-frame:04d}"
    shutil.copy(out / scene["scene"] / folder_name / "realtime.exr",
                folder / request["output"]["image"])
    return 0


if __name__ == "__main__":
    sys.exit(main())
