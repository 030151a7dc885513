"""What the repository checks (check_layering.py, check_paths.py) share: run one over a root
given on the command line (default: the repository holding this file), print its findings, and
exit 0 when there are none, 1 otherwise. Standard library only."""
import os
import sys


def run_check(check, failed, passed):
    """check(root) -> list of lines; `failed` is formatted with the count, `passed` printed as is."""
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(
        os.path.dirname(os.path.abspath(__file__)))
    if not os.path.isdir(root):
        print(f"{root}: not a folder (give the repository root)")
        return 2
    errors = check(root)
    for e in errors:
        print(e)
    if errors:
        print(failed.format(len(errors)))
        return 1
    print(passed)
    return 0
