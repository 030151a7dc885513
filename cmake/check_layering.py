#!/usr/bin/env python3
"""Fails when a source folder includes a header it may not: the dependency table below.

Each library folder lists the folders whose headers it may include (besides its own). The
table follows the data: core is the floor; imaging sits on it; the driver families, the
frontend and the backend sit on imaging and never include each other (drivers never include
OpenCV feature code either); slam/ is the SLAM library that ties them together: its core,
with its configuration (slam/config) and session file (slam/session) below it, then its rooms
slam/localization, slam/outputs, slam/jobs and the live runtime (slam/live), each above the
one before. The evaluation never enters the SLAM library: eval and eval/compare score what
frontend and backend make and include nothing of slam/; app (the whole configuration file,
with the evaluation's sections), eval/jobs (the evaluation's commands) and eval/tour (scores of
whole runs) sit above slam/; tools is the command line (and core/, the floor every layer
shares). docs/architecture.md describes each folder.

The same rule holds for linking: the SLAM library's targets (ROBOT_TARGETS) may not link,
directly or through another target, the evaluation's libraries or PCL (FORBIDDEN_LINKS), read
from the target_link_libraries() calls of every CMakeLists.txt.

Only quoted includes that name a project folder (`#include "backend/pose_graph.h"`) are
checked, against the longest folder of the table that holds the header; `<...>` includes are
not the project's, except the OpenCV feature headers in drivers. test/, bench/ and fuzz/ sit
on top of everything and are not checked. A folder with C++ sources that the table does not
name is an error too, so a new folder must be given its row.

Usage: check_layering.py [ROOT]   (ROOT defaults to the repository holding this script).
Exit 0 when every include is allowed, 1 with one line per violation.
Standard library only: runs from `make layering-check`, `.ci/run` and ctest.
"""
import os
import re
import sys

from repo_check import run_check

DRIVERS = ["drivers/rosbag", "drivers/logs", "drivers/sim", "drivers/live", "drivers/dds"]
BELOW_SLAM = ["core", "imaging", *DRIVERS, "drivers/emulators", "frontend",
              "frontend/place_recognition", "backend"]
# The evaluation: scores what frontend and backend make; never included by the SLAM library.
EVAL = ["eval", "eval/compare"]
SLAM_ROOMS = ["slam", "slam/localization", "slam/outputs", "slam/jobs"]
SLAM_PARTS = [*SLAM_ROOMS, "slam/config", "slam/session", "slam/live"]

# folder -> the folders whose headers it may include (its own always).
ALLOWED = {
    "core": [],
    "imaging": ["core"],
    "drivers/rosbag": ["core"],
    "drivers/logs": ["core"],
    "drivers/sim": ["core", "imaging", "drivers/rosbag", "drivers/logs"],
    "drivers/live": ["core", "imaging"],
    "drivers/dds": ["core", "imaging"],
    "drivers/emulators": ["core", "imaging", *DRIVERS],
    "frontend": ["core", "imaging"],
    "frontend/place_recognition": ["core", "imaging", "frontend"],
    "backend": ["core", "imaging"],
    "eval": ["core", "imaging", "frontend", "frontend/place_recognition", "backend"],
    "eval/compare": ["core", "imaging", "backend"],
    "slam/config": ["core", "imaging", "frontend", "frontend/place_recognition", "backend"],
    "slam/session": ["core", "imaging", "frontend", "frontend/place_recognition", "backend",
                     "slam/config"],
    "slam": [*BELOW_SLAM, "slam/config", "slam/session"],
    "slam/localization": [*BELOW_SLAM, "slam", "slam/config", "slam/session"],
    "slam/outputs": [*BELOW_SLAM, "slam", "slam/localization", "slam/config", "slam/session"],
    "slam/jobs": [*BELOW_SLAM, "slam", "slam/localization", "slam/outputs", "slam/config",
                  "slam/session"],
    "slam/live": [*BELOW_SLAM, *SLAM_ROOMS, "slam/config", "slam/session"],
    # Above the SLAM library: the whole configuration file, the evaluation's jobs and tours.
    "app": [*BELOW_SLAM, *SLAM_PARTS, "eval/compare"],
    "eval/jobs": [*BELOW_SLAM, *SLAM_PARTS, *EVAL, "app"],
    "eval/tour": [*BELOW_SLAM, *SLAM_PARTS, *EVAL],
    "tools": ["core", *SLAM_PARTS, "app", "eval/jobs", "eval/compare"],
}
# The libraries that run on the robot, and what none of them may link, even transitively.
ROBOT_TARGETS = ["uwbsar_slam", "uwbsar_slam_localization", "uwbsar_slam_outputs",
                 "uwbsar_slam_jobs", "uwbsar_live"]
FORBIDDEN_LINKS = ["uwbsar_eval", "uwbsar_compare", "uwbsar_eval_jobs", "uwbsar_tour_eval",
                   "uwbsar_app_config", "${PCL_LIBRARIES}"]
LINK_RE = re.compile(r"target_link_libraries\s*\(([^)]*)\)", re.S)
LINK_KEYWORDS = {"PUBLIC", "PRIVATE", "INTERFACE"}

# Folders whose sources may not include these system headers (drivers: no feature code).
FORBIDDEN_SYSTEM = {folder: ("opencv2/features2d", "opencv2/xfeatures2d")
                    for folder in [*DRIVERS, "drivers/emulators"]}
# Folders above the table (they may include anything) or without project C++ code.
EXEMPT = {"test", "bench", "fuzz", "build", "cmake", "config", "docs", ".git", ".venv", "out"}

SOURCE_SUFFIXES = (".h", ".hpp", ".cc", ".cpp")
INCLUDE_RE = re.compile(r'^\s*#\s*include\s+([<"])([^">]+)[">]')


def folder_of(rel_path):
    """The longest folder of the table holding `rel_path`, or None."""
    parts = rel_path.split("/")[:-1]
    for n in range(len(parts), 0, -1):
        candidate = "/".join(parts[:n])
        if candidate in ALLOWED:
            return candidate
    return None


def source_files(root):
    for top in sorted(os.listdir(root)):
        path = os.path.join(root, top)
        if not os.path.isdir(path) or top in EXEMPT or top.startswith((".", "build")):
            continue
        for dirpath, dirnames, names in os.walk(path):
            dirnames.sort()
            for name in sorted(names):
                if name.endswith(SOURCE_SUFFIXES):
                    yield os.path.relpath(os.path.join(dirpath, name), root).replace(os.sep, "/")


def check(root):
    errors = []
    for folder in ALLOWED:
        if not os.path.isdir(os.path.join(root, folder)):
            errors.append(f"{folder}/: folder of the dependency table is missing (update ALLOWED)")
    for rel in source_files(root):
        own = folder_of(rel)
        if own is None:
            errors.append(f"{rel}: its folder has no row in ALLOWED of {__file__}")
            continue
        with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
            for line_no, line in enumerate(f, 1):
                m = INCLUDE_RE.match(line)
                if not m:
                    continue
                kind, header = m.groups()
                if kind == "<":
                    if header.startswith(FORBIDDEN_SYSTEM.get(own, ())):
                        errors.append(f"{rel}:{line_no}: {own}/ may not include <{header}>")
                    continue
                if "/" not in header:
                    continue
                target = folder_of(header)
                if target is None or target == own or target in ALLOWED[own]:
                    continue
                errors.append(f'{rel}:{line_no}: {own}/ may not include "{header}" from '
                              f"{target}/ (it may include: {', '.join(ALLOWED[own]) or 'nothing'})")
    return errors


def link_graph(root):
    """target -> the items of its target_link_libraries() calls, over every CMakeLists.txt."""
    graph = {}
    for dirpath, dirnames, names in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if d not in EXEMPT - {"cmake"}
                             and not d.startswith((".", "build")))
        if "CMakeLists.txt" not in names:
            continue
        with open(os.path.join(dirpath, "CMakeLists.txt"), encoding="utf-8") as f:
            text = re.sub(r"#[^\n]*", "", f.read())
        for m in LINK_RE.finditer(text):
            words = m.group(1).split()
            if words:
                graph.setdefault(words[0], []).extend(w for w in words[1:]
                                                      if w not in LINK_KEYWORDS)
    return graph


def check_links(root):
    """One line per robot target that reaches a forbidden library, with the chain."""
    graph = link_graph(root)
    errors = []
    for target in ROBOT_TARGETS:
        if target not in graph:
            errors.append(f"{target}: no target_link_libraries() found (update ROBOT_TARGETS)")
            continue
        chain = {target: [target]}
        todo = [target]
        while todo:
            t = todo.pop()
            for dep in graph.get(t, []):
                if dep in chain:
                    continue
                chain[dep] = chain[t] + [dep]
                if dep in FORBIDDEN_LINKS:
                    errors.append(f"{target} links {dep} (the SLAM library links no evaluation): "
                                  + " -> ".join(chain[dep]))
                todo.append(dep)
    return errors


def check_all(root):
    return check(root) + check_links(root)


def main():
    return run_check(check_all,
                     "{} include(s) or link(s) break the dependency table (cmake/check_layering.py)",
                     "layering: every include and link is allowed by the dependency table")


if __name__ == "__main__":
    sys.exit(main())
