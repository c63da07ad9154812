#!/usr/bin/env python3
"""No file of the repository names a path outside it (a clone stands alone). Run by ctest as
Repository.NamesNoPathOutsideIt.

Checked: every file git tracks or would add (untracked, not ignored); without git, every file
under the source folder but build*/ and out/, but this file, whose patterns and made-up lines
name such paths on purpose. In binary files (a NUL byte) only their runs of printable text are
read, for absolute paths; an image's metadata (EXR attributes, PNG text chunks, compressed ones
too), which may hold the command line that made it, is read through OpenImageIO's Python module
(python3-openimageio) and may hold no absolute path at all. Found:
- a path that climbs with `..` out of the folder of the file naming it (scene files and
  Markdown links are read from their own folder);
- a path that climbs with `..` into a folder the repository has nowhere (code, scripts and
  comments name paths from the root or a variable: `$ROOT/..`, `SOURCE_DIR "/..`,
  `path / ".." / "x"`), whatever it was taken from;
- an absolute path into a home or work folder of one machine (see MACHINE).
The matcher checks itself first on made-up lines, so an empty or broken pattern cannot pass."""
import argparse
import re
import struct
import subprocess
import sys
import tempfile
import zlib
from pathlib import Path, PurePosixPath

try:
    import OpenImageIO as oiio
except ImportError:
    # An interpreter of its own (a virtual environment, pyenv) does not see Debian's modules.
    sys.path.append("/usr/lib/python3/dist-packages")
    try:
        import OpenImageIO as oiio
    except ImportError:
        oiio = None

SELF = "tests/outside_paths_test.py"
# `../` at least once, then a name: `cd ..` and a lone `..` are not paths to anything.
CLIMB = re.compile(r"(?:\.\./)+[A-Za-z0-9_.%$*{}-][^\s\"'`)<>\]|,;\\]*")
# Folders that exist on one machine only. /tmp is left out: scripts use it as a work folder.
MACHINE = re.compile(r"(?<![\w.])(?:/home/[a-z_][\w.-]*|/root/|/Users/|/work/|[A-Za-z]:\\Users)")
# C++ and Python build paths from parts: X / ".." / "y" reads as X/../y.
JOIN = re.compile(r"(\"|\))\s*/\s*\"")
# A path taken from the source folder, as C++ sources name one.
ANCHOR = re.compile(r"SOURCE_DIR\W{0,8}$")
C_SOURCES = {".cpp", ".h", ".hpp", ".c", ".cc"}
# A name that stands for something else: a variable, a frame pattern, a glob.
PLACEHOLDER = re.compile(r"[$%*{]")
# Images whose metadata OpenImageIO reads. Their attributes name no absolute path at all: a
# tool's command line there names where the image was made (`oiiotool ... -o /x/y/one.exr`).
IMAGES = {".exr", ".png", ".jpg", ".jpeg", ".tif", ".tiff", ".hdr", ".webp"}
ABSOLUTE = re.compile(r"(?<![\w.:/])(?:/[\w.-]+){2,}|[A-Za-z]:\\[\w.-]+")


def within(root: PurePosixPath, path: PurePosixPath) -> bool:
    """Whether `path` (relative, may hold ..) stays inside `root` (a relative folder)."""
    depth = 0
    for part in (root / path).parts:
        depth = depth - 1 if part == ".." else depth + (part != ".")
        if depth < 0:
            return False
    return True


def in_literal(line: str, at: int) -> bool:
    """Whether `at` lies inside a C-style "string literal" of `line`."""
    return len(re.findall(r'(?<!\\)"', line[:at])) % 2 == 1


def problems_in(name: str, text: str, folders: set) -> list:
    """The outside paths that `text`, the content of the file `name` (relative to the root),
    names, as (line number, what was found, why); `folders` holds the name of every folder of
    the repository. In C and C++ sources, a string literal is a path only where it is taken
    from the source folder (`SOURCE_DIR "/..`): tests hand paths that climb out to the tool
    on purpose. In Markdown, a fenced block's paths are the example's own (a scene file's are
    taken from the scene's folder), so they only must not climb into a folder the repository
    has nowhere."""
    folder = PurePosixPath(name).parent
    literals_are_data = PurePosixPath(name).suffix in C_SOURCES
    markdown = PurePosixPath(name).suffix == ".md"
    fenced = False
    found = []
    for number, line in enumerate(text.splitlines(), 1):
        if markdown and line.lstrip().startswith("```"):
            fenced = not fenced
        line = JOIN.sub(lambda m: "/" if m[1] == '"' else ")/", line)
        for m in CLIMB.finditer(line):
            if (literals_are_data and in_literal(line, m.start())
                    and not ANCHOR.search(line[:m.start()])):
                continue
            target = PurePosixPath(m.group(0))
            below = [p for p in target.parts if p != ".."]
            if not fenced and not within(folder, target):
                found.append((number, m.group(0), f"climbs out of {folder}/"))
            elif (len(below) > 1 and not PLACEHOLDER.search(below[0])
                  and below[0] not in folders):
                found.append((number, m.group(0), f"no folder {below[0]}/ in the repository"))
        for m in MACHINE.finditer(line):
            found.append((number, m.group(0), "an absolute path on one machine"))
    return found


def self_check() -> list:
    """The matcher on made-up lines: every `bad` is found, no `good` is."""
    up = "../"
    bad = {
        "scenes/x.toml": f'path = "{up}{up}elsewhere/data/ball.ssf"',
        "README.md": f"see `{up}elsewhere/NOTES.md`",
        "docs/c.md": f'```toml\npath = "{up}{up}elsewhere/data/ball.ssf"\n```',
        "core/scene.h": f"// The scene format ({up}elsewhere/NOTES.md).",
        "scripts/run": f'DATA="$ROOT/{up}elsewhere/data"',
        "core/t.h": 'return fs::path(SOURCE_DIR) / ".." / "elsewhere" / "x.ssf";',
        "tests/t.cpp": f'constexpr auto P = SOURCE_DIR "/{up}elsewhere/x.ssf";',
        "docs/a.md": "built in " + "/" + "home/someone/src/twinrender",
        "ci/x.yml": "cd " + "/" + "work/main && make",
    }
    good = {
        "scenes/x.toml": f'path = "{up}data/lammps_splash/splash_%03d.ply"',
        "app/studies.cpp": f'"{up}planet.toml", and "{up}index.html" from a report page',
        "app/x.cpp": f'#include "{up}core/scene.h"',
        "scripts/run": 'ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"',
        "data/a/make.sh": 'WORK="${WORK:-/tmp/a}"; cd ..; ls "$WORK/../$X/y"',
        "docs/b.md": "1..10 and a.b..c, a range 0..1/2",
        "README.md": f'```toml\npath = "{up}data/lammps_splash/splash_020.ply"\n```',
        "tests/t_test.cpp": f'render("{up}{up}escaped/out", "a\\"{up}{up}b\\"");',
    }
    folders = {"data", "lammps_splash", "core", "scenes", "scripts", "docs", "ci"}
    failures = [f"not found in {n}: {t}" for n, t in bad.items() if not problems_in(n, t, folders)]
    failures += [f"found in {n}: {t}" for n, t in good.items() if problems_in(n, t, folders)]
    # An EXR's Software attribute as oiiotool writes it, between binary bytes.
    blob = b"\0\x01Software\0string\0oiiotool -o " + b"/" + b"work/x/one.exr\0\x7f"
    if not binary_problems(blob):
        failures.append("not found in a binary file's text")
    if binary_problems(b"\0\x01Software\0string\0oiiotool -o ./one.exr\0"):
        failures.append("found in a binary file's relative path")
    failures += image_self_check()
    return failures


def image_self_check() -> list:
    """The metadata reader on made-up images: an EXR whose Software attribute holds oiiotool's
    command line, and a PNG whose zTXt chunk (compressed: no printable run shows it) holds one;
    the same images with a relative path pass."""
    if oiio is None:
        return ["OpenImageIO's Python module (python3-openimageio) is missing: image metadata "
                "cannot be read"]
    import numpy  # OpenImageIO's module needs it: where that imports, this does
    failures = []
    with tempfile.TemporaryDirectory() as folder:
        for name, where in (("one.exr", "/" + "tmp/made/one.exr"), ("two.exr", "./two.exr")):
            path = Path(folder) / name
            spec = oiio.ImageSpec(2, 1, 1, "float")
            spec.attribute("Software", "oiiotool --pattern constant 2x1 1 -o " + where)
            out = oiio.ImageOutput.create(str(path))
            if not (out and out.open(str(path), spec)
                    and out.write_image(numpy.zeros((1, 2, 1), numpy.float32)) and out.close()):
                return ["cannot write a made-up EXR: " + oiio.geterror()]
            if bool(image_problems(path)) != where.startswith("/"):
                failures.append(f"image metadata {'not ' if where[0] == '/' else ''}found: {where}")
        for name, where in (("one.png", "/" + "tmp/made/one.png"), ("two.png", "two.png")):
            path = Path(folder) / name
            path.write_bytes(png_with_ztxt(b"Software", ("oiiotool -o " + where).encode()))
            if binary_problems(path.read_bytes()):
                failures.append("a zTXt chunk read as text: the self-check shows nothing")
            if bool(image_problems(path)) != where.startswith("/"):
                failures.append(f"PNG zTXt {'not ' if where[0] == '/' else ''}found: {where}")
    return failures


def png_with_ztxt(keyword: bytes, text: bytes) -> bytes:
    """A 1 x 1 grey PNG with one compressed text chunk."""
    def chunk(kind: bytes, data: bytes) -> bytes:
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))
    return (b"\x89PNG\r\n\x1a\n"
            + chunk(b"IHDR", struct.pack(">IIBBBBB", 1, 1, 8, 0, 0, 0, 0))
            + chunk(b"zTXt", keyword + b"\0\0" + zlib.compress(text))
            + chunk(b"IDAT", zlib.compress(b"\0\x80"))
            + chunk(b"IEND", b""))


def image_problems(path: Path) -> list:
    """The absolute paths in an image's metadata, as OpenImageIO reads its header (never its
    pixels: a malformed regression input may claim a huge image). An image OpenImageIO cannot
    open is left to the binary reading."""
    found = []
    image = oiio.ImageInput.open(str(path))
    if not image:
        oiio.geterror()
        return found
    try:
        for index in range(64):
            if not image.seek_subimage(index, 0):
                break
            for attribute in image.spec().extra_attribs:
                value = attribute.value
                for text in value if isinstance(value, (tuple, list)) else (value,):
                    if isinstance(text, str):
                        found += [(0, f"{attribute.name}: {m.group(0)}",
                                   "an absolute path in the image's metadata")
                                  for m in ABSOLUTE.finditer(text)]
    finally:
        image.close()
    return found


def binary_problems(data: bytes) -> list:
    """The absolute paths on one machine in the printable runs of a binary file's bytes."""
    found = []
    for run in re.findall(rb"[\x20-\x7e]{4,}", data):
        text = run.decode("ascii")
        found += [(0, m.group(0), "an absolute path on one machine, in binary data")
                  for m in MACHINE.finditer(text)]
    return found


def repository_files(root: Path) -> list:
    try:
        out = subprocess.run(["git", "-C", str(root), "ls-files", "-z", "--cached", "--others",
                              "--exclude-standard"], capture_output=True, check=True).stdout
        return sorted({f for f in out.decode().split("\0") if f and (root / f).is_file()})
    except (OSError, subprocess.CalledProcessError):
        skip = re.compile(r"^(build[^/]*|out|\.git)(/|$)")
        return sorted(str(p.relative_to(root)) for p in root.rglob("*")
                      if p.is_file() and not skip.match(str(p.relative_to(root))))


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--source", required=True, type=Path)
    args = parser.parse_args()
    root = args.source.resolve()

    failures = self_check()
    if failures:
        print("the matcher itself is wrong:\n  " + "\n  ".join(failures))
        return 1

    files = [f for f in repository_files(root) if f != SELF]
    folders = {part for f in files for part in PurePosixPath(f).parts[:-1]}
    # A repository this size holds hundreds of files, scenes among them: fewer means the
    # listing failed, and nothing was checked.
    if len(files) < 100 or not any(f.startswith("scenes/") and f.endswith(".toml") for f in files):
        print(f"only {len(files)} files listed under {root}: nothing to check")
        return 1

    found = []
    for name in files:
        data = (root / name).read_bytes()
        if PurePosixPath(name).suffix.lower() in IMAGES:
            found += [f"{name}: {what} ({why})" for _, what, why in image_problems(root / name)]
        if b"\0" in data:
            found += [f"{name}: {what} ({why})" for _, what, why in binary_problems(data)]
            continue
        text = data.decode("utf-8", errors="replace")
        found += [f"{name}:{n}: {what} ({why})" for n, what, why in problems_in(name, text, folders)]
    if found:
        print(f"{len(found)} paths outside the repository (a clone must stand alone):")
        print("\n".join("  " + f for f in found))
        return 1
    print(f"{len(files)} files, no path outside the repository")
    return 0


if __name__ == "__main__":
    sys.exit(main())
