#!/usr/bin/env python3
"""Property test (issue 13): mutates every example scene and runs `sinew run` on each mutation.

Each mutation changes one thing in one example scene: a value's type (string, bool, null,
array, object), a value (0, -1, huge, tiny, fractional, past INT_MAX), a key (deleted, renamed,
an unknown one added, duplicated), or the text (cut short). The run must
  - exit 0, 2 (an error) or 3 (did not converge) - never a signal, never anything else;
  - finish within --timeout seconds (a hang past the bound is a failure);
  - on exit 2, print error lines that each name a file and where in it (a JSON path such as
    "/mesh/cells" or a "file:line").
The mutations come from a seeded generator, so a failure is reproducible with the printed seed
and index (--only INDEX reruns one).

  mutate_scenes.py SINEW EXAMPLES [--count N] [--seed S] [--frames F] [--timeout T] [--jobs J]
"""
import argparse
import concurrent.futures
import copy
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile

VALUES = [0, -1, 1, 0.5, -0.5, 1e308, -1e308, 1e-300, 2147483647, 2147483648, -2147483649,
          9007199254740993, "", "x", True, False, None, [], {}, [1, 2], [0, 0, 0], {"a": 1}]


def paths(node, prefix=()):
    """Every (path, value) in the JSON tree, the root excluded."""
    if isinstance(node, dict):
        for k, v in node.items():
            yield prefix + (k,), v
            yield from paths(v, prefix + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield prefix + (i,), v
            yield from paths(v, prefix + (i,))


def parent_of(doc, path):
    node = doc
    for p in path[:-1]:
        node = node[p]
    return node


def mutate(doc, text, rng):
    """(new text, description) for one random mutation of the scene `doc` (its text `text`)."""
    all_paths = list(paths(doc))
    kind = rng.choice(["value", "value", "value", "delete", "rename", "add", "duplicate", "truncate"])
    if kind == "truncate":
        cut = rng.randrange(len(text))
        return text[:cut], f"text cut at byte {cut}"
    if kind == "duplicate":
        # The first key of the top-level object written twice (JSON readers must refuse it).
        m = re.search(r'\{\s*("[^"]+"\s*:)', text)
        return text[:m.start(1)] + m.group(1) + " 1, " + text[m.start(1):], "a duplicated key"
    doc = copy.deepcopy(doc)
    path, _ = rng.choice(all_paths)
    parent = parent_of(doc, path)
    key = path[-1]
    where = "/" + "/".join(str(p) for p in path)
    if kind == "value":
        v = rng.choice(VALUES)
        parent[key] = v
        desc = f"{where} = {json.dumps(v)}"
    elif kind == "delete":
        del parent[key]
        desc = f"{where} deleted"
    elif kind == "rename" and isinstance(parent, dict):
        parent[str(key) + "_x"] = parent.pop(key)
        desc = f"{where} renamed"
    else:
        target = parent if isinstance(parent, dict) else doc
        target["unknown_key"] = 1
        desc = "an unknown key added"
    return json.dumps(doc, indent=1), desc


LOCATION = re.compile(r"(: /|\.json: |:\d+|--[a-z])")


def check(sinew, scene, out, frames, timeout, threads):
    """(exit code, None) when the run behaved, else (exit code, the reason it did not)."""
    rc, reason = run_one(sinew, scene, out, frames, timeout, threads)
    return rc, reason


def run_one(sinew, scene, out, frames, timeout, threads):
    cmd = [sinew, "run", scene, "--out", out, "--frames", str(frames), "--threads", str(threads), "--quiet"]
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout,
                           env=dict(os.environ, OMP_NUM_THREADS="1"))
    except subprocess.TimeoutExpired:
        return "hang", f"still running after {timeout} s (a hang)"
    rc = r.returncode
    if rc < 0:
        return rc, f"killed by signal {signal.Signals(-rc).name}: {r.stderr[-2000:]}"
    if rc not in (0, 2, 3):
        return rc, f"exit code {rc}: {r.stderr[-2000:]}"
    if rc == 2:
        lines = [l for l in r.stderr.splitlines() if l.strip()]
        if not lines:
            return rc, "exit 2 with no error message"
        for line in lines:
            if "internal error" in line:
                return rc, f"an internal error: {line}"
            names_file = os.path.basename(scene) in line or re.search(r"\.(json|obj|off|ply|stl|vtk|vtu|mesh|msh|node|ele)\b", line)
            if line.startswith("sinew: error:") and not (names_file and LOCATION.search(line)):
                return rc, f"an error line naming no file and location: {line}"
    return rc, None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("sinew")
    ap.add_argument("examples")
    ap.add_argument("--count", type=int, default=200)
    ap.add_argument("--seed", type=int, default=13)
    ap.add_argument("--frames", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=120.0)
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--only", type=int, default=None, help="run only this mutation index")
    args = ap.parse_args()

    examples = os.path.abspath(args.examples)
    scenes = sorted(os.path.relpath(os.path.join(d, f), examples)
                    for d, _, files in os.walk(examples) for f in files
                    if f.endswith(".json") and "rigs" not in d.split(os.sep))
    if not scenes:
        sys.exit(f"no example scenes under {examples}")
    work = tempfile.mkdtemp(prefix="sinew-mutate-")
    try:
        # A copy of the examples tree (links to its files), so relative mesh and rig paths in a
        # mutated scene resolve as in the original.
        for d, _, files in os.walk(examples):
            rel = os.path.relpath(d, examples)
            os.makedirs(os.path.join(work, "ex", rel), exist_ok=True)
            for f in files:
                os.symlink(os.path.join(d, f), os.path.join(work, "ex", rel, f))
        rng = random.Random(args.seed)
        jobs = []
        for i in range(args.count):
            name = scenes[i % len(scenes)]  # every example in turn
            with open(os.path.join(examples, name)) as f:
                text = f.read()
            new_text, desc = mutate(json.loads(text), text, rng)
            if args.only is not None and i != args.only:
                continue
            target = os.path.join(work, "ex", os.path.dirname(name), f"m{i}_{os.path.basename(name)}")
            with open(target, "w") as f:
                f.write(new_text)
            jobs.append((i, name, desc, target))
        failures = []
        codes = {}
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            futures = {pool.submit(check, args.sinew, t, os.path.join(work, f"out{i}"), args.frames, args.timeout, 1):
                       (i, n, d) for i, n, d, t in jobs}
            for fut in concurrent.futures.as_completed(futures):
                i, n, d = futures[fut]
                rc, reason = fut.result()
                codes[rc] = codes.get(rc, 0) + 1
                shutil.rmtree(os.path.join(work, f"out{i}"), ignore_errors=True)
                if reason:
                    failures.append(f"mutation {i} of {n} ({d}): {reason}")
        print(f"{len(jobs)} mutations of {len(scenes)} example scenes (seed {args.seed}, {args.frames} frame(s)): "
              f"{len(failures)} failed; exit codes {dict(sorted(codes.items(), key=str))}")
        for f in sorted(failures):
            print("FAIL:", f)
        sys.exit(1 if failures else 0)
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
