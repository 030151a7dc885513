#!/usr/bin/env python3
"""Do two uwbsar binaries give the same results? The check for a change that must not change
behaviour (a restructuring, a refactor): both binaries run the same three jobs, and every output
must be byte-identical except what records time or the run's own paths.

Jobs: `demo` (seed_hall), `demo --map` on the paper's LiDAR map (seed_lab, from ../shared/data;
skipped with one line when it is missing), and the office ring (`simulate` with the first binary,
then `map` of that one bag with each binary).

Compared: every file of each output folder byte for byte; except
  - summary.json: equal after removing timings, memory and real-time factor;
  - report.html: equal after removing numbers (it prints those timings);
  - session.uwbsar: every table's rows equal, except the config and paths a session stores;
  - .uwbsar.lock: holds the writer's pid.

Usage: compare_runs.py BIN_A BIN_B [WORK_DIR]   (WORK_DIR defaults to a fresh temporary folder)
Exit 0 when everything matches, 1 listing what differs. Standard library only.
"""
import json
import os
import re
import sqlite3
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SEED_LAB = os.path.join(ROOT, "..", "shared", "data", "maps", "seed_lab", "my_map.yaml")
VOLATILE_SUMMARY_KEYS = {"peak_memory_mib", "processing_s", "real_time_factor", "time_s", "input",
                         "wall_s"}


def run(binary, args, log):
    with open(log, "w") as out:
        rc = subprocess.call([binary, *args], cwd=ROOT, stdout=out, stderr=subprocess.STDOUT)
    if rc != 0:
        sys.exit(f"{binary} {' '.join(args)} failed with exit {rc} (log: {log})")


def strip_summary(value):
    if isinstance(value, dict):
        return {k: strip_summary(v) for k, v in value.items() if k not in VOLATILE_SUMMARY_KEYS}
    if isinstance(value, list):
        return [strip_summary(v) for v in value]
    return value


def session_rows(path):
    db = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    tables = [r[0] for r in db.execute("SELECT name FROM sqlite_master WHERE type='table'")]
    rows = {}
    for table in sorted(tables):
        cols = [r[1] for r in db.execute(f"PRAGMA table_info({table})")]
        keep = [c for c in cols if c not in ("input",)]
        data = db.execute(f"SELECT {', '.join(keep)} FROM {table}").fetchall()
        if table == "meta":
            data = [r for r in data if r[0] not in ("config_yaml",)]
        rows[table] = sorted(data, key=repr)
    return rows


def same(a, b, name):
    if name == ".uwbsar.lock":
        return True
    if name == "summary.json":
        with open(a) as fa, open(b) as fb:
            return strip_summary(json.load(fa)) == strip_summary(json.load(fb))
    if name == "report.html":
        with open(a, errors="replace") as fa, open(b, errors="replace") as fb:
            number = re.compile(r"\d+(\.\d+)?")
            return number.sub("#", fa.read()) == number.sub("#", fb.read())
    if name.endswith(".uwbsar"):
        return session_rows(a) == session_rows(b)
    with open(a, "rb") as fa, open(b, "rb") as fb:
        return fa.read() == fb.read()


def compare_folders(a, b):
    differ = []
    names_a = sorted(os.listdir(a))
    if names_a != sorted(os.listdir(b)):
        differ.append(f"{a} and {b} hold different files")
    for name in names_a:
        pa, pb = os.path.join(a, name), os.path.join(b, name)
        if os.path.isfile(pa) and os.path.isfile(pb) and not same(pa, pb, name):
            differ.append(f"{name} differs ({pa} vs {pb})")
    return differ


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    bins = [os.path.abspath(b) for b in sys.argv[1:3]]
    work = sys.argv[3] if len(sys.argv) > 3 else tempfile.mkdtemp(prefix="uwbsar_compare_")
    os.makedirs(work, exist_ok=True)
    bag = os.path.join(work, "office_bag")
    run(bins[0], ["simulate", "--map", "config/maps/office/office.yaml", "--route",
                  "config/maps/office/route_loops.txt", "--out", bag], os.path.join(work, "sim.log"))
    jobs = {"demo": ["demo", "--seed", "1"], "office": ["map", bag]}
    if os.path.exists(SEED_LAB):
        jobs["seed_lab"] = ["demo", "--map", SEED_LAB]
    else:
        print(f"seed_lab skipped: {SEED_LAB} is missing")
    differ = []
    for job, args in jobs.items():
        outs = []
        for i, binary in enumerate(bins):
            out = os.path.join(work, f"{job}_{i}")
            run(binary, [*args, "--out", out], out + ".log")
            outs.append(out)
        found = compare_folders(*outs)
        print(f"{job}: {'identical' if not found else 'DIFFERENT'} "
              f"({len(os.listdir(outs[0]))} files)")
        differ += [f"{job}: {d}" for d in found]
    for d in differ:
        print(d)
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
