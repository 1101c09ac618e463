"""What the tests of a case's replay share (a case run again from its earlier runs' data files,
without a simulation: the drum's DRUM_FROM, the crater's CRATER_FROM): writing a made-up data file,
and running the case on folders of them."""
import json
import os
import subprocess
import sys

RUN = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "run.py")


def write_data(folder, name, record):
    """<folder>/<name>: the record as JSON (the folder made if needed)."""
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "w") as f:
        json.dump(record, f)


def run_case(tmp_path, case, env):
    """Runs `case` through run.py with the environment `env`, its output in <tmp_path>/out."""
    return subprocess.run([sys.executable, RUN, case, "--out", str(tmp_path / "out")], env=env, capture_output=True,
                          text=True, timeout=300)


def replay(tmp_path, case, variable, folders):
    """Runs `case` with `variable` naming the folders; returns the process, its verdicts (the
    summary's list) and its output folder."""
    out = tmp_path / "out"
    r = run_case(tmp_path, case, dict(os.environ, **{variable: ",".join(str(f) for f in folders)}))
    summary = json.loads((out / "summary.json").read_text()) if (out / "summary.json").exists() else []
    return r, summary, out
