#!/usr/bin/env python3
"""docs/cli.md documents every command and option that `twinrender --help` lists: each command
has a section whose heading names it, and each of its options appears in that section (or, for
the options every command that renders shares, in the section about them). Run by ctest as
Docs.CliOptionsAreDocumented."""
import argparse
import re
import subprocess
import sys
from pathlib import Path

SHARED = "## Options of every command that renders"


def help_text(tool, *args):
    return subprocess.run([tool, *args, "--help"], capture_output=True, text=True,
                          check=False).stdout


def sections(page):
    """{heading line: its text up to the next heading of the same level}; code blocks are text."""
    out, heading, fenced = {}, None, False
    for line in page.splitlines():
        fenced ^= line.startswith("```")
        if line.startswith("## ") and not fenced:
            heading = line
            out[heading] = ""
        elif heading:
            out[heading] += line + "\n"
    return out


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--twinrender", required=True)
    parser.add_argument("--doc", required=True, type=Path)
    args = parser.parse_args()
    parts = sections(args.doc.read_text())
    shared = parts.get(SHARED, "")
    top = help_text(args.twinrender)
    commands = re.findall(r"^  ([a-z]+)\s", top.split("Subcommands:", 1)[-1], re.M)
    problems = []
    if not commands:
        problems.append("twinrender --help lists no commands")
    for command in commands:
        heading = next((h for h in parts if f"twinrender {command}`" in h), None)
        if heading is None:
            problems.append(f"no section of {args.doc} is headed `twinrender {command}`")
            continue
        options = set(re.findall(r"^\s+(?:-\w,\s*)?(--[a-z][a-z0-9-]*)",
                                 help_text(args.twinrender, command), re.M)) - {"--help"}
        for option in sorted(options):
            if f"`{option}" not in parts[heading] and f"`{option}" not in shared:
                problems.append(f"`twinrender {command} {option}` is not in {args.doc}")
    print("\n".join(problems + [f"{len(commands)} commands checked, {len(problems)} problems"]))
    return int(bool(problems))


if __name__ == "__main__":
    sys.exit(main())
