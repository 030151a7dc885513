#!/usr/bin/env python3
"""Fails when a source folder includes a header from a folder above it.

The project's folders form one stack, listed bottom to top in LAYERS: a file may include
headers of its own folder and of the folders below it, never of one above (the data flows
up: sensor data enters in drivers, is imaged in frontend, optimised in backend, saved and
joined in session and run as a whole by pipeline; tools is the command line over all of
it). docs/architecture.md describes each floor.

Only quoted includes that name a project folder (`#include "backend/pose_graph.h"`) are
checked; system and library headers (`<...>`) are not the project's. test/, bench/ and
fuzz/ sit on top of everything and are not checked. A top-level folder with C++ sources
that is neither a layer nor exempt is an error too, so a new folder must be given a floor.

Usage: check_layering.py [ROOT]   (ROOT defaults to the repository holding this script).
Exit 0 when every include points down or sideways, 1 with one line per violation.
Standard library only: runs from `make layering-check`, `.ci/run` and ctest.
"""
import os
import re
import sys

# Bottom to top. A folder may include its own headers and those of any folder before it.
LAYERS = [
    "slam",      # core: types, pose2, config (+ loading, validation), log, errors
    "imaging",   # imaging core: image grid and files, enhancement, pulse, sensor geometry
    "drivers",   # sensors, bags, simulator, live device drivers, DDS (drivers/dds)
    "frontend",  # scans -> keyframe SAR tiles, place recognition
    "backend",   # pose graph, global map, occupancy, map comparison (backend/compare)
    "session",   # saved sessions (session.uwbsar), joining them, localising in them
    "pipeline",  # SlamSystem, mapping and imaging jobs, map outputs, live runtime
    "tools",     # the `uwbsar` command line: flags and printing
]
# Folders above every layer (they may include anything) or without project C++ code.
EXEMPT = {"test", "bench", "fuzz", "build", "cmake", "config", "docs", ".git", ".venv"}

SOURCE_SUFFIXES = (".h", ".hpp", ".cc", ".cpp")
INCLUDE_RE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def layer_of(top_folder):
    return LAYERS.index(top_folder) if top_folder in LAYERS else None


def check(root):
    errors = []
    for entry in sorted(os.listdir(root)):
        path = os.path.join(root, entry)
        if not os.path.isdir(path) or entry in EXEMPT or entry.startswith((".", "build")):
            continue
        has_sources = any(
            name.endswith(SOURCE_SUFFIXES) for _, _, names in os.walk(path) for name in names
        )
        if has_sources and entry not in LAYERS:
            errors.append(f"{entry}/: folder with C++ sources is not in LAYERS of {__file__}")
    for folder in LAYERS:
        if not os.path.isdir(os.path.join(root, folder)):
            errors.append(f"{folder}/: layer folder is missing (update LAYERS)")
    for folder in LAYERS:
        own = layer_of(folder)
        for dirpath, _, names in os.walk(os.path.join(root, folder)):
            for name in sorted(names):
                if not name.endswith(SOURCE_SUFFIXES):
                    continue
                file_path = os.path.join(dirpath, name)
                rel = os.path.relpath(file_path, root)
                with open(file_path, encoding="utf-8", errors="replace") as f:
                    for line_no, line in enumerate(f, 1):
                        m = INCLUDE_RE.match(line)
                        if not m or "/" not in m.group(1):
                            continue
                        target = m.group(1).split("/", 1)[0]
                        other = layer_of(target)
                        if other is not None and other > own:
                            errors.append(
                                f"{rel}:{line_no}: {folder}/ (layer {own}) includes "
                                f'"{m.group(1)}" from {target}/ (layer {other}), a higher layer'
                            )
    return errors


def main(argv):
    root = argv[1] if len(argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    errors = check(root)
    for e in errors:
        print(e)
    if errors:
        print(f"layering check: {len(errors)} violation(s); order, bottom to top: "
              + " -> ".join(LAYERS))
        return 1
    print("layering check: no include runs upward (" + " -> ".join(LAYERS) + ")")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
