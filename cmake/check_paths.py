#!/usr/bin/env python3
"""Fails when a comment, README or document names a repository path that does not exist.

A pointer to a file that moved or never existed sends the next reader nowhere. This scans the
project's own text (C++ sources and headers, CMake files, Python, shell, YAML, Markdown; every
tracked file) for tokens that look like repository paths: a top-level folder
of the project followed by at least one path component, e.g. `slam/slam_system.h`,
`drivers/live/`, `config/maps/office/README.md`. Each must exist, relative to the repository
root. Tokens with placeholders (`*`, `<`, `{`, `$`, `...`) are patterns, not paths, and are
skipped, as are paths a command is told to write (after `--out`, `-o` or `>`).

Usage: check_paths.py [ROOT]   (ROOT defaults to the repository holding this script).
Exit 0 when every named path exists, 1 with one line per missing path ("file:line: path").
Standard library only: runs from `make path-check`, `.ci/run` and ctest.
"""
import os
import re
import subprocess
import sys

from repo_check import run_check

# Top-level folders whose paths are checked (the repository's own tree).
TOP = ["core", "imaging", "drivers", "frontend", "backend", "eval", "slam", "tools", "test",
       "bench", "fuzz", "docs", "config", "cmake", ".ci",
       # Folders that existed once: a pointer into them is stale by definition.
       "pipeline", "session"]
TEXT_SUFFIXES = (".h", ".cc", ".cpp", ".hpp", ".py", ".sh", ".md", ".yaml", ".yml", ".txt",
                 ".cmake", ".html", ".json")
TEXT_NAMES = ("Makefile", "CMakeLists.txt", "run")
# A path token: a top folder, a slash, then path characters; it ends before punctuation
# that closes a sentence or a code span.
PATH_RE = re.compile(
    r"(?<![A-Za-z0-9_./-])((?:%s)/[A-Za-z0-9_./-]*)" % "|".join(re.escape(t) for t in TOP))
PLACEHOLDER = re.compile(r"[*<>{}$]|\.\.\.")
# A path a command is told to write (`--out config/calibration.yaml`) need not exist yet.
OUTPUT_FLAG = re.compile(r"(?:--out|-o|>)\s*$")


def tracked_files(root):
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-co", "--exclude-standard"],
                             check=True, capture_output=True, text=True).stdout
        return [f for f in out.splitlines() if f]
    except (OSError, subprocess.CalledProcessError):
        files = []
        for dirpath, dirnames, names in os.walk(root):
            dirnames[:] = [d for d in dirnames if not d.startswith((".", "build", "out"))]
            files += [os.path.relpath(os.path.join(dirpath, n), root) for n in names]
        return files


def candidate(token):
    """The path a token names, or None when it is a pattern or not a path at all."""
    token = token.rstrip(".,;:")
    if PLACEHOLDER.search(token) or "//" in token:
        return None
    return token


def check(root):
    errors = []
    for rel in tracked_files(root):
        if rel.startswith(("build", "out/", ".venv/")):
            continue
        if not (rel.endswith(TEXT_SUFFIXES) or os.path.basename(rel) in TEXT_NAMES):
            continue
        path = os.path.join(root, rel)
        if not os.path.isfile(path):
            continue
        with open(path, encoding="utf-8", errors="replace") as f:
            for line_no, line in enumerate(f, 1):
                for m in PATH_RE.finditer(line):
                    name = candidate(m.group(1))
                    if name is None or OUTPUT_FLAG.search(line[:m.start()]):
                        continue
                    full = os.path.join(root, name)
                    # A module named without its suffix (`backend/pose_graph`) is its .h/.cc.
                    if not any(os.path.exists(full + s) for s in ("", ".h", ".cc")):
                        errors.append(f"{rel}:{line_no}: names '{name}', which does not exist")
    return errors


def main():
    return run_check(check, "{} pointer(s) to paths that do not exist (cmake/check_paths.py)",
                     "paths: every repository path named in the sources and documents exists")


if __name__ == "__main__":
    sys.exit(main())
