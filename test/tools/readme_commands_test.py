#!/usr/bin/env python3
"""The README's commands run: every `uwbsar ...` line of its ```sh blocks exits 0.

Convention (also an HTML comment in README.md, and docs/development.md):
- In a ```sh fenced block of README.md, every line that starts with `uwbsar ` is a command the
  test runs; a line ending in `\\` continues on the next. Text after ` #` is a comment.
- Other lines of a ```sh block may only be blank, comments, `make ...` (the build itself) or
  `export ...` (the PATH hint); anything else fails the test, so no command the reader is told
  to type is silently left out.
- Commands that need a robot, ROS or the user's own recording are written in ```text blocks,
  which the test does not read.

The commands run in order, each as its own process (no shell: no pipes or redirections),
with `uwbsar` replaced by the binary under test, in one fresh temporary folder that holds a
copy of the repository's `config/` (so `config/...` paths resolve and nothing is written into
the repository). A command that names an absolute path or `..` is refused: it could write
outside that folder. The first command that exits non-zero fails the test, naming it.

Usage: readme_commands_test.py UWBSAR_BINARY REPOSITORY_ROOT
Standard library only.
"""
import os
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

PER_COMMAND_TIMEOUT_S = 300
ALLOWED_OTHER = ("make ", "export ")


def sh_commands(readme_path):
    """(line number, command text) of every `uwbsar` line in the ```sh blocks, in order."""
    commands, errors = [], []
    in_fence = in_sh = False
    pending, pending_line = None, 0
    with open(readme_path, encoding="utf-8") as f:
        for line_no, raw in enumerate(f, 1):
            stripped = raw.strip()
            if stripped.startswith("```"):
                if in_fence and pending is not None:
                    errors.append(f"README.md:{pending_line}: block ends inside a continued line")
                    pending = None
                in_sh = not in_fence and stripped[3:].strip() == "sh"
                in_fence = not in_fence
                continue
            if not in_sh:
                continue
            if pending is not None:
                pending += " " + stripped.rstrip("\\").strip()
                if not stripped.endswith("\\"):
                    commands.append((pending_line, pending))
                    pending = None
                continue
            if not stripped or stripped.startswith("#"):
                continue
            if stripped.startswith("uwbsar "):
                if stripped.endswith("\\"):
                    pending, pending_line = stripped.rstrip("\\").strip(), line_no
                else:
                    commands.append((line_no, stripped))
                continue
            if stripped.startswith(ALLOWED_OTHER):
                continue
            errors.append(f"README.md:{line_no}: a ```sh line the test cannot run: {stripped!r} "
                          "(start it with `uwbsar `, or move it to a ```text block)")
    return commands, errors


def main():
    if len(sys.argv) != 3:
        print("usage: readme_commands_test.py UWBSAR_BINARY REPOSITORY_ROOT", file=sys.stderr)
        return 2
    binary = os.path.abspath(sys.argv[1])
    root = os.path.abspath(sys.argv[2])
    commands, errors = sh_commands(os.path.join(root, "README.md"))
    if errors:
        print("\n".join(errors))
        return 1
    if not commands:
        print("README.md: no `uwbsar` command in a ```sh block")
        return 1
    for line_no, text in commands:
        argv = shlex.split(text, comments=True)
        bad = [a for a in argv if os.path.isabs(a) or ".." in a.split("/")]
        if bad:
            print(f"README.md:{line_no}: `{text}` names a path outside the working folder: {bad}")
            return 1

    env = dict(os.environ, UWBSAR_PROGRESS="0")
    total_start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="uwbsar_readme_") as work:
        shutil.copytree(os.path.join(root, "config"), os.path.join(work, "config"))
        env["TMPDIR"] = work
        for line_no, text in commands:
            argv = shlex.split(text, comments=True)
            argv[0] = binary
            start = time.monotonic()
            try:
                proc = subprocess.run(argv, cwd=work, env=env, stdout=subprocess.PIPE,
                                      stderr=subprocess.STDOUT, text=True, errors="replace",
                                      timeout=PER_COMMAND_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                print(f"FAILED README.md:{line_no}: `{text}` ran past {PER_COMMAND_TIMEOUT_S} s")
                return 1
            took = time.monotonic() - start
            if proc.returncode != 0:
                tail = "\n".join(proc.stdout.splitlines()[-20:])
                print(f"FAILED README.md:{line_no}: `{text}` exited {proc.returncode} "
                      f"after {took:.1f} s; its last output:\n{tail}")
                return 1
            print(f"ok {took:6.1f} s  README.md:{line_no}: {text}")
    print(f"{len(commands)} README commands ran in {time.monotonic() - total_start:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
