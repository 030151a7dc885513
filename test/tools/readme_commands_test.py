#!/usr/bin/env python3
"""The README's commands run: every `uwbsar ...` line of its ```sh blocks exits 0, and every
`evo_ape ...` line gives the ATE that uwbsar reported within 1 mm.

Convention (also an HTML comment in README.md, and docs/development.md):
- In a ```sh fenced block of README.md, every line that starts with `uwbsar ` is a command the
  test runs; a line ending in `\\` continues on the next. Text after ` #` is a comment.
- A line that starts with `evo_ape ` runs with the test tools' evo ($UWBSAR_VENV/bin, else the
  repository's .venv/bin) and must exit 0 and print an rmse within 1 mm of `ate.rmse_m` in the
  summary.json beside its estimate (its second file). An estimate under out/demo that no
  command made is first made as `make demo` makes it (its command, read from the Makefile).
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
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

PER_COMMAND_TIMEOUT_S = 300
ALLOWED_OTHER = ("make ", "export ")
RUN_PREFIXES = ("uwbsar ", "evo_ape ")
EVO_TOLERANCE_M = 0.001


def sh_commands(readme_path):
    """(line number, command text) of every `uwbsar` and `evo_ape` line in the ```sh blocks."""
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
            if stripped.startswith(RUN_PREFIXES):
                if stripped.endswith("\\"):
                    pending, pending_line = stripped.rstrip("\\").strip(), line_no
                else:
                    commands.append((line_no, stripped))
                continue
            if stripped.startswith(ALLOWED_OTHER):
                continue
            errors.append(f"README.md:{line_no}: a ```sh line the test cannot run: {stripped!r} "
                          "(start it with `uwbsar ` or `evo_ape `, or move it to a ```text block)")
    return commands, errors


def run(argv, work, env):
    """(exited 0, seconds, its output or why it failed) of one command run in `work`."""
    start = time.monotonic()
    try:
        proc = subprocess.run(argv, cwd=work, env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True, errors="replace",
                              timeout=PER_COMMAND_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return False, PER_COMMAND_TIMEOUT_S, f"ran past {PER_COMMAND_TIMEOUT_S} s"
    took = time.monotonic() - start
    if proc.returncode != 0:
        tail = "\n".join(proc.stdout.splitlines()[-20:])
        return False, took, f"exited {proc.returncode} after {took:.1f} s; its last output:\n{tail}"
    return True, took, proc.stdout


def make_demo_argv(root, binary):
    """The command `make demo` runs (the Makefile's demo recipe), with the binary under test."""
    with open(os.path.join(root, "Makefile"), encoding="utf-8") as f:
        recipe = re.search(r"^demo:.*\n\t(.+)$", f.read(), re.MULTILINE)
    argv = shlex.split(recipe.group(1))
    return [binary] + argv[1:]


def check_evo(argv, where, root, binary, work, env):
    """None when the evo_ape line runs and its rmse is uwbsar's ATE within 1 mm, else why not."""
    venv = os.environ.get("UWBSAR_VENV", os.path.join(root, ".venv"))
    evo = os.path.join(venv, "bin", "evo_ape")
    if not os.path.exists(evo):
        return f"{where}: {evo} is missing (make venv installs evo, test/requirements.txt)"
    files = [a for a in argv[2:] if not a.startswith("-")]
    if len(files) < 2:
        return f"{where}: expected `evo_ape tum REFERENCE ESTIMATE ...`"
    folder = os.path.dirname(files[1])
    if not os.path.exists(os.path.join(work, folder)) and folder == "out/demo":
        ok, took, output = run(make_demo_argv(root, binary), work, env)
        if not ok:
            return f"{where}: make demo's command {output}"
        print(f"ok {took:6.1f} s  (make demo's command, for {folder})")
    ok, took, output = run([evo] + argv[1:], work, env)
    if not ok:
        return f"{where} {output}"
    found = re.search(r"^\s*rmse\s+([0-9.eE+-]+)", output, re.MULTILINE)
    if not found:
        return f"{where}: no rmse in its output:\n{output}"
    with open(os.path.join(work, folder, "summary.json"), encoding="utf-8") as f:
        ours = json.load(f)["ate"]["rmse_m"]
    evo_rmse = float(found.group(1))
    if abs(evo_rmse - ours) > EVO_TOLERANCE_M:
        return (f"{where}: evo's rmse {evo_rmse:.5f} m differs from uwbsar's ATE {ours:.5f} m "
                f"({folder}/summary.json) by more than {EVO_TOLERANCE_M * 1000:.0f} mm")
    print(f"ok {took:6.1f} s  {where}: rmse {evo_rmse:.5f} m, uwbsar {ours:.5f} m")
    return None


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
            where = f"README.md:{line_no}: `{text}`"
            if argv[0] == "evo_ape":
                failure = check_evo(argv, where, root, binary, work, env)
                if failure:
                    print(f"FAILED {failure}")
                    return 1
                continue
            argv[0] = binary
            ok, took, output = run(argv, work, env)
            if not ok:
                print(f"FAILED {where} {output}")
                return 1
            print(f"ok {took:6.1f} s  {where}")
    print(f"{len(commands)} README commands ran in {time.monotonic() - total_start:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
