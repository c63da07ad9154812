#!/usr/bin/env python3
"""`cmake --install` gives a twinrender that runs on its own: installed into a fresh prefix, run
from a folder outside both the prefix and the source tree, `twinrender run` with no scene
renders and compares the installed default scenes (found beside the program, not in the
source tree) and writes EXRs through the installed image module. The scenes are rendered at
48x36 so that this takes seconds. Run by ctest as Install.RunsItsDefaultScenesFromAnyFolder."""
import argparse
import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True, type=Path)
    parser.add_argument("--scratch", required=True, type=Path)
    args = parser.parse_args()
    shutil.rmtree(args.scratch, ignore_errors=True)
    args.scratch.mkdir(parents=True)
    prefix, elsewhere = args.scratch / "prefix", args.scratch / "elsewhere"
    elsewhere.mkdir()

    install = subprocess.run(["cmake", "--install", str(args.build), "--prefix", str(prefix)],
                             capture_output=True, text=True)
    if install.returncode != 0:
        print(f"cmake --install failed:\n{install.stdout}{install.stderr}")
        return 1
    share = prefix / "share" / "twinrender"
    expected = [prefix / "bin" / "twinrender", share / "scenes" / "thresholds.toml",
                share / "data" / "lammps_splash" / "splash_020.ply",
                share / "data" / "opensph_ball" / "ball.ssf",
                share / "examples" / "surface_pass_through.glsl", share / "ci" / "examples",
                share / "docs", share / "README.md"]
    missing = [str(p) for p in expected if not p.exists()]
    modules = list(prefix.glob("lib*/**/twinrender_oiio.so"))
    if missing or not modules:
        print("not installed: " + ", ".join(missing + ([] if modules else ["twinrender_oiio.so"])))
        return 1

    small = ["--set", "camera.width=48", "--set", "camera.height=36"]
    run = subprocess.run([str(prefix / "bin" / "twinrender"), "run", "--out", "out"] + small,
                         cwd=elsewhere, capture_output=True, text=True, timeout=300)
    # 0 pass, 1 warn, 2 fail: at this size some thresholds may fail; 3 and 4 mean it could not
    # run (no scenes, no image module, bad input).
    if run.returncode > 2:
        print(f"twinrender run exited {run.returncode}:\n{run.stdout}{run.stderr}")
        return 1
    summary = json.loads((elsewhere / "out" / "summary.json").read_text())
    scenes = sorted(s["name"] for s in summary["scenes"])
    installed = sorted(p.stem for p in (share / "scenes").glob("*.toml") if p.stem != "thresholds")
    problems = []
    if scenes != installed:
        problems.append(f"ran {scenes}, installed {installed}")
    read = [s["settings"]["scene_file"] for s in summary["scenes"]
            if "scene_file" in s.get("settings", {})]
    problems += [f"{s['name']}: {s['error']}" for s in summary["scenes"] if s.get("error")]
    problems += [f"read {f}, not the installed scene" for f in read
                 if not Path(f).resolve().is_relative_to(share.resolve())]
    if not read:
        problems.append("the report names no scene file")
    exrs = list((elsewhere / "out").glob("*/raymarch.exr"))
    if not exrs:
        problems.append("no EXR written (the image module)")
    for p in problems:
        print(p)
    print(f"installed into {prefix}, ran {len(scenes)} scenes from {elsewhere}: "
          f"exit {run.returncode}, {len(problems)} problems")
    if not problems:
        shutil.rmtree(args.scratch, ignore_errors=True)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
