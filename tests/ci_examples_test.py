#!/usr/bin/env python3
"""The CI files users copy (ci/examples/): each parses as YAML and shows both ways. Built from
source: it shards the run over a matrix and merges the shards, uploads the report, and runs
exactly the twinrender commands docs/cli.md shows (and scripts/setup). Installed: it builds the
Debian package (scripts/package), installs it with apt-get and runs the installed `twinrender`.
Every twinrender command has the options it gives. Run by ctest as
CiExamples.ParseAndRunTheReadmesCommands."""
import argparse
import re
import shlex
import subprocess
import sys
from pathlib import Path

try:
    import yaml
except ImportError:
    sys.exit("python3-yaml is not installed (scripts/setup installs it)")

TOOL = "build/app/twinrender"
# The command as the Debian package installs it, on the PATH.
INSTALLED = "twinrender"


def readme_lines(readme: Path) -> set:
    """Every line inside the page's ```sh blocks, stripped."""
    lines, inside = set(), False
    for line in readme.read_text().splitlines():
        if line.startswith("```"):
            inside = line.strip() == "```sh" if not inside else False
            continue
        if inside:
            lines.add(line.strip())
    return lines


def github_scripts(doc: dict, problems: list) -> list:
    jobs = doc.get("jobs", {})
    if not any("matrix" in job.get("strategy", {}) for job in jobs.values()):
        problems.append("no job has a strategy.matrix to shard over")
    uses = [s.get("uses", "") for job in jobs.values() for s in job.get("steps", [])]
    if not any(u.startswith("actions/upload-artifact@") for u in uses):
        problems.append("nothing is uploaded with actions/upload-artifact")
    if not any(u.startswith("actions/download-artifact@") for u in uses):
        problems.append("the shards are not downloaded for the merge")
    # PyYAML reads the key `on` as the boolean true (YAML 1.1).
    if "on" not in doc and True not in doc:
        problems.append("no `on:` triggers")
    return [s["run"] for job in jobs.values() for s in job.get("steps", []) if "run" in s]


def gitlab_scripts(doc: dict, problems: list) -> list:
    jobs = {k: v for k, v in doc.items() if isinstance(v, dict) and k not in ("variables", "default")}
    if not any("parallel" in job for job in jobs.values()):
        problems.append("no job has `parallel:` to shard over")
    if not any(job.get("artifacts", {}).get("paths") for job in jobs.values()):
        problems.append("no job keeps artifacts")
    return [line for job in jobs.values()
            for key in ("before_script", "script", "after_script") for line in job.get(key) or []]


def command_lines(scripts: list) -> list:
    """The lines that run scripts/, the tool or the installed tool, or install a package."""
    return [line.strip() for script in scripts for line in str(script).splitlines()
            if line.strip().startswith(("scripts/", TOOL, INSTALLED + " ", "apt-get install"))]


def check_options(line: str, twinrender: str, problems: list, where: str):
    words = shlex.split(line.split("||")[0])
    subcommand = words[1]
    result = subprocess.run([twinrender, subcommand, "--help"], capture_output=True, text=True)
    if result.returncode != 0:
        problems.append(f"{where}: `twinrender {subcommand} --help` failed: {result.stderr}")
        return
    for option in (w for w in words[2:] if w.startswith("--")):
        if not re.search(r"(^|[\s,])" + re.escape(option) + r"\b", result.stdout):
            problems.append(f"{where}: `twinrender {subcommand}` has no option {option}")


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--source", required=True, type=Path)
    parser.add_argument("--twinrender", required=True)
    args = parser.parse_args()
    readme = readme_lines(args.source / "docs" / "cli.md")
    readme_tool = {line for line in readme if line.startswith(TOOL + " ")}
    problems = []
    examples = {"github-actions.yml": github_scripts, "gitlab-ci.yml": gitlab_scripts}
    for name, scripts_of in examples.items():
        path = args.source / "ci" / "examples" / name
        try:
            doc = yaml.safe_load(path.read_text())
        except (OSError, yaml.YAMLError) as e:
            problems.append(f"{path}: {e}")
            continue
        if not isinstance(doc, dict):
            problems.append(f"{path}: not a YAML mapping")
            continue
        local = []
        commands = command_lines(scripts_of(doc, local))
        problems += [f"{path}: {p}" for p in local]
        for line in commands:
            if line.startswith(INSTALLED + " "):
                check_options(line, args.twinrender, problems, str(path))
                continue
            if line.startswith("apt-get"):
                continue
            if line not in readme:
                problems.append(f"{path}: runs a command docs/cli.md does not show: {line}")
            if line.startswith(TOOL + " "):
                check_options(line, args.twinrender, problems, str(path))
        if "scripts/setup" not in commands:
            problems.append(f"{path}: does not set up with scripts/setup")
        missing = readme_tool - set(commands)
        for line in sorted(missing):
            problems.append(f"{path}: does not run docs/cli.md's {line}")
        if not any(" run " in c and "--shard" in c for c in commands):
            problems.append(f"{path}: no `twinrender run --shard`")
        if not any(c.startswith(TOOL + " merge ") for c in commands):
            problems.append(f"{path}: no `twinrender merge`")
        if "scripts/package" not in commands:
            problems.append(f"{path}: does not build the Debian package with scripts/package")
        if not any(re.match(r"apt-get install .*\./\S*twinrender_\*\.deb$", c) for c in commands):
            problems.append(f"{path}: does not install the package with apt-get install ./...deb")
        if not any(c.startswith(INSTALLED + " run ") for c in commands):
            problems.append(f"{path}: does not run the installed `twinrender run`")
    for p in problems:
        print(p)
    print(f"{len(examples)} CI examples checked, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
