"""What every validation case shares: finding the engine, its command line, its verdicts, its plot.

A case is a script in validation/cases/ that builds its set-up, measures, compares each measured
quantity with a published or analytical reference and draws the comparison. It calls `Case.check`
once per quantity and `Case.finish()` at the end, which writes out/<case>.json (its verdicts) and
exits with status 1 when a verdict fails. `validation/run.py` runs the cases and gathers their
verdicts into out/summary.json.
"""
import argparse
import json
import os
import platform
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
BUILD = os.environ.get("DEME_BUILD_DIR", os.path.join(ROOT, "build"))


def import_deme():
    """The engine's Python module: from PYTHONPATH if set, else from the build tree."""
    try:
        import deme  # noqa: F401
    except ImportError:
        sys.path.insert(0, os.path.join(BUILD, "python"))
    import deme
    return deme


def demo_path(name):
    path = os.path.join(BUILD, "demos", name)
    if not os.path.exists(path):
        raise SystemExit(f"{path} is missing: build the engine first (bash scripts/setup.sh)")
    return path


def run_demo(name, *args, timeout=3600):
    """Runs a C++ demo of the build on the chosen backend (DEME_BACKEND) and returns its stdout."""
    out = subprocess.run([demo_path(name), *args], capture_output=True, text=True, timeout=timeout)
    if out.returncode not in (0, 1):
        sys.stderr.write(out.stdout[-4000:] + out.stderr[-4000:])
        raise SystemExit(f"{name} failed with status {out.returncode}")
    return out.stdout


def json_lines(text):
    """The JSON objects a demo printed, one per line."""
    found = []
    for line in text.splitlines():
        line = line.strip()
        if line.startswith("{") and line.endswith("}"):
            found.append(json.loads(line))
    return found


def commit():
    # DEME_COMMIT names it where the checkout's git does not know it (a copy of a working tree whose
    # .git is older than its files, as on a remote GPU machine).
    if os.environ.get("DEME_COMMIT"):
        return os.environ["DEME_COMMIT"]
    try:
        return subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                              timeout=10).stdout.strip() or "unknown"
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def device(backend):
    if backend == "cuda":
        try:
            name = subprocess.run(["nvidia-smi", "--query-gpu=name", "--format=csv,noheader"], capture_output=True,
                                  text=True, timeout=20).stdout.strip().splitlines()
            if name:
                return name[0]
        except (OSError, subprocess.SubprocessError):
            pass
        return "GPU"
    return f"CPU ({os.cpu_count()} cores, {platform.machine()})"


def write_json(path, record):
    """Writes `record` to `path` through a temporary name, so that a crash never leaves half a file."""
    with open(path + ".tmp", "w") as f:
        json.dump(record, f, indent=1)
    os.replace(path + ".tmp", path)


def read_parts(variable, folders, name, same_keys, reason):
    """The data files `name` of an earlier run's parts (a case's DRUM_FROM, CRATER_FROM: the folders
    that `variable` names), as dicts, refused unless every one agrees with the first on `same_keys`
    (`reason` says why they must)."""
    parts = []
    for folder in folders:
        with open(os.path.join(folder, name)) as f:
            parts.append(json.load(f))
    for key in same_keys:
        if any(p.get(key) != parts[0].get(key) for p in parts):
            raise ValueError(f"{variable}: the runs differ in {key} ({reason}): {[p.get(key) for p in parts]}")
    return parts


class Case:
    """One case's command line (--quick, --backend, --out), verdicts and plot."""

    def __init__(self, name, description):
        parser = argparse.ArgumentParser(description=description)
        parser.add_argument("--quick", action="store_true", help="the reduced version (CI)")
        parser.add_argument("--backend", choices=["cpu", "cuda", "auto"],
                            default=os.environ.get("DEME_BACKEND") or "cpu")
        parser.add_argument("--out", default=os.path.join(HERE, "out"))
        self.args = parser.parse_args()
        self.name = name
        self.quick = self.args.quick
        self.backend = self.args.backend
        os.environ["DEME_BACKEND"] = self.backend  # the engine's solvers and the demos read it
        os.makedirs(self.args.out, exist_ok=True)
        self.verdicts = []
        self.started = time.time()

    def require_liggghts(self):
        """A case that runs LIGGGHTS beside the engine calls this first. LIGGGHTS is a CPU program: where
        it is missing, a CPU run fails (scripts/setup.sh installs it), and a GPU run (whose machine may
        have no LIGGGHTS) records the case as skipped, which run.py lists apart and never counts as a
        pass."""
        if shutil.which("liggghts"):
            return
        if self.backend == "cpu":
            self.check("LIGGGHTS 3.8 installed (apt-get install liggghts; scripts/setup.sh does)", "found",
                       "Debian package liggghts", "missing", "needed", False)
            self.finish()
        self.finish(skipped="LIGGGHTS is not installed on this machine (run the case with --backend cpu)")

    def check(self, quantity, reference, source, measured, tolerance, passed):
        """One verdict: `measured` against `reference` (from `source`) within `tolerance` (words)."""
        v = {"case": self.name, "quantity": quantity, "reference": reference, "source": source,
             "measured": measured, "tolerance": tolerance, "pass": bool(passed)}
        self.verdicts.append(v)
        print(f"{'PASS' if passed else 'FAIL'}  {quantity}: measured {measured}, reference {reference} ({tolerance})")
        return passed

    def figure(self, *args, **kwargs):
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        return plt.subplots(*args, **kwargs)

    def save(self, fig, origin=None, name=None):
        """Writes the case's plot to <out>/<name>.png (name: the case's by default; through a temporary
        name). origin: where the data came from when it is not this run (e.g. "cuda, 9ac9233", a GPU
        run drawn here)."""
        made = f"{self.backend}, {commit()}" if origin is None else f"{origin} (drawn on {self.backend}, {commit()})"
        fig.suptitle(f"{self.name}{' (quick)' if self.quick else ''}: {made}", fontsize=8, y=0.995)
        fig.tight_layout()
        path = os.path.join(self.args.out, (name or self.name) + ".png")
        tmp = path + ".tmp.png"
        fig.savefig(tmp, dpi=110)
        os.replace(tmp, path)

    def finish(self, skipped=None):
        """Writes the verdicts (or, with `skipped`, why the case did not run here) and exits: 0 when
        every verdict passed or the case was skipped, 1 otherwise."""
        record = {"case": self.name, "quick": self.quick, "backend": self.backend, "device": device(self.backend),
                  "commit": commit(), "seconds": round(time.time() - self.started, 1), "verdicts": self.verdicts}
        if skipped:
            record["skipped"] = skipped
            print(f"SKIPPED  {self.name}: {skipped}")
        write_json(os.path.join(self.args.out, self.name + ".json"), record)
        ok = bool(skipped) or (bool(self.verdicts) and all(v["pass"] for v in self.verdicts))
        sys.exit(0 if ok else 1)
