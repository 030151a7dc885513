#!/usr/bin/env python3
"""Fails when the user documentation stops being readable by users.

- No line of README.md or docs/*.md is longer than 200 characters (a table row of 2,000
  characters cannot be read in a terminal or a review).
- docs/cli.md and docs/configuration.md are for users: they name no source file (`x.cc`, `x.h`),
  no path into the code's folders, and no C++ type, function or namespace (a class or struct
  name declared in the sources, `Name::member`, `Name()`). That content belongs in
  docs/architecture.md.
- docs/configuration.md explains every key of config/default.yaml: a key counts as explained when
  its dotted name appears in backticks (`slam.map_resolution_m`), or when a list item names its
  last part in backticks before its first colon (- `map_resolution_m` (default `0.01`): ...) under a heading that names its section in
  backticks followed by `.*` (### Maps: `slam.*`). Radars' keys are `radars[].name` and so on.
  A default the page states (- `name` (default `0.01`)) is the file's, for a key the file has.

Usage: check_docs.py [ROOT]   (ROOT defaults to the repository holding this script).
Exit 0 when all hold, 1 with one line per finding ("file:line: what"). Standard library only:
runs from `make path-check` and ctest.
"""
import glob
import os
import re
import sys

from repo_check import run_check

MAX_LINE = 200
USER_PAGES = ("docs/cli.md", "docs/configuration.md")
CODE_FOLDERS = ("core", "imaging", "drivers", "frontend", "backend", "eval", "slam", "tools",
                "test", "bench", "fuzz", "cmake")
SOURCE_FILE = re.compile(r"\b[\w./-]*\w\.(?:cc|h|cpp|hpp)\b")
CODE_PATH = re.compile(r"(?<![\w./-])(?:%s)/[\w./-]*" % "|".join(CODE_FOLDERS))
SCOPED_NAME = re.compile(r"\b[A-Za-z_]\w*::\w+")
CALL = re.compile(r"\b[A-Z]\w*\(\)")
DECLARED_TYPE = re.compile(r"^\s*(?:class|struct|enum(?:\s+class)?|using)\s+([A-Z]\w*)", re.M)
# A compound PascalCase name (two capitalised parts): `SystemConfig`, not `Config` or `ORB`.
PASCAL = re.compile(r"^[A-Z][a-z0-9]+[A-Z]\w*$")
KEY_LINE = re.compile(r"^(\s*)(- )?([A-Za-z_]\w*):(.*)$")
HEADING_SECTION = re.compile(r"`([\w.\[\]]+)\.\*`")
ITEM_KEY = re.compile(r"`(\w+)`")
# `name` (default `value`: the default a list item states for its key.
STATED_DEFAULT = re.compile(r"`([\w.\[\]]+)` \(default `([^`]*)`")
DOTTED = re.compile(r"`([\w\[\]]+(?:\.[\w\[\]]+)+)`")


def read_lines(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read().splitlines()


def long_lines(root):
    pages = ["README.md"] + sorted(os.path.relpath(p, root)
                                   for p in glob.glob(os.path.join(root, "docs", "*.md")))
    return [f"{rel}:{n}: {len(line)} characters (at most {MAX_LINE})"
            for rel in pages for n, line in enumerate(read_lines(os.path.join(root, rel)), 1)
            if len(line) > MAX_LINE]


def code_type_names(root):
    """Compound PascalCase types declared in the C++ sources (not tests: their fixtures)."""
    names = set()
    for folder in CODE_FOLDERS[:8]:
        for path in glob.glob(os.path.join(root, folder, "**", "*.h"), recursive=True):
            with open(path, encoding="utf-8", errors="replace") as f:
                names.update(n for n in DECLARED_TYPE.findall(f.read()) if PASCAL.match(n))
    return names


def code_names_in_user_pages(root):
    types = code_type_names(root)
    word = re.compile(r"(?<![\w/])([A-Z]\w+)")
    errors = []
    for rel in USER_PAGES:
        for n, line in enumerate(read_lines(os.path.join(root, rel)), 1):
            found = SOURCE_FILE.findall(line) + CODE_PATH.findall(line)
            found += SCOPED_NAME.findall(line) + CALL.findall(line)
            found += [w for w in word.findall(line) if w in types]
            errors += [f"{rel}:{n}: names '{x}' (code: it belongs in docs/architecture.md)"
                       for x in dict.fromkeys(found)]
    return errors


def default_keys(root):
    """Dotted leaf keys of config/default.yaml (`radars[].topic` for the radars' list), each with
    its value as written (the first radar's for the radars)."""
    keys, stack = {}, []
    for line in read_lines(os.path.join(root, "config", "default.yaml")):
        m = KEY_LINE.match(line)
        if not m or line.lstrip().startswith("#"):
            continue
        indent = len(m.group(1)) + (2 if m.group(2) else 0)
        while stack and stack[-1][0] >= indent:
            stack.pop()
        parent = [k for _, k in stack]
        if m.group(2) and not parent[-1].endswith("[]"):  # an item of a list of mappings
            parent[-1] += "[]"
            stack[-1] = (stack[-1][0], parent[-1])
        key = ".".join(parent + [m.group(3)])
        value = m.group(4).split("#", 1)[0].strip()
        stack.append((indent, m.group(3)))
        if value and key not in keys:
            keys[key] = value
    return keys


def same_value(doc, yaml):
    doc, yaml = doc.strip("'\""), yaml.strip("'\"")
    try:
        return float(doc) == float(yaml)
    except ValueError:
        return doc.replace(" ", "") == yaml.replace(" ", "")


def key_findings(root):
    """Keys of config/default.yaml the page does not explain, and keys it states a default of
    that the file does not have or has with another value."""
    defaults, explained, errors, section = default_keys(root), set(), [], None
    rel = "docs/configuration.md"
    for n, line in enumerate(read_lines(os.path.join(root, rel)), 1):
        if line.startswith("#"):
            m = HEADING_SECTION.search(line)
            section = m.group(1) if m else None
        explained.update(DOTTED.findall(line))
        if not line.startswith("- "):
            continue
        head = line.split(": ", 1)[0]  # the names before its first ": "
        if section:
            explained.update(f"{section}.{k}" for k in ITEM_KEY.findall(head))
        for name, value in STATED_DEFAULT.findall(head):
            key = name if "." in name else f"{section}.{name}"
            if key not in defaults:
                errors.append(f"{rel}:{n}: states a default of '{key}', not a key of "
                              "config/default.yaml")
            elif not same_value(value, defaults[key]):
                errors.append(f"{rel}:{n}: '{key}' defaults to {defaults[key]} in "
                              f"config/default.yaml, not {value}")
    errors += [f"{rel}: explains no key '{k}' of config/default.yaml"
               for k in defaults if k not in explained]
    return errors


def check(root):
    return long_lines(root) + code_names_in_user_pages(root) + key_findings(root)


def main():
    return run_check(check, "{} finding(s) in the user documentation (cmake/check_docs.py)",
                     "docs: lines fit, user pages name no code, every configuration key explained")


if __name__ == "__main__":
    sys.exit(main())
