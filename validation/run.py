#!/usr/bin/env python3
"""Runs the validation cases and gathers their verdicts.

    /usr/bin/python3 validation/run.py [--quick] [--backend cpu|cuda] [case ...]

Each case (validation/cases/<case>.py) runs in its own process, writes out/<case>.png and
out/<case>.json; this script writes out/summary.json (the list of every case's verdicts:
case, quantity, reference, source, measured, tolerance, pass), prints them as a table and exits with
status 1 when any verdict failed or any case did not finish.
"""
import argparse
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
CASES_DIR = os.path.join(HERE, "cases")


def all_cases(folder=CASES_DIR):
    return sorted(f[:-3] for f in os.listdir(folder) if f.endswith(".py") and not f.startswith("_"))


def script(case):
    """A case's script: cases/<case>.py, or pending/<name>.py for a case named pending/<name> (a case
    not yet in the suite, run only when named)."""
    return os.path.join(HERE, case + ".py") if case.startswith("pending/") else os.path.join(CASES_DIR, case + ".py")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("cases", nargs="*", help=f"cases to run (default: all of {', '.join(all_cases())}; "
                        "pending/<name> runs a case of pending/)")
    parser.add_argument("--quick", action="store_true", help="the reduced version of each case (CI)")
    parser.add_argument("--backend", choices=["cpu", "cuda", "auto"], default=os.environ.get("DEME_BACKEND") or "cpu")
    parser.add_argument("--out", default=os.path.join(HERE, "out"))
    parser.add_argument("--timeout", type=float, default=None, help="seconds per case (default: 900 quick, none full)")
    args = parser.parse_args()
    known = all_cases()
    pending = ["pending/" + c for c in all_cases(os.path.join(HERE, "pending"))]
    chosen = args.cases or known
    for c in chosen:
        if c not in known + pending:
            parser.error(f"no case '{c}' (cases: {', '.join(known)}; pending: {', '.join(pending)})")
    os.makedirs(args.out, exist_ok=True)
    timeout = args.timeout or (900 if args.quick else None)

    summary, failures, times, skipped = [], [], {}, {}
    for c in chosen:
        cmd = [sys.executable, script(c), "--backend", args.backend, "--out", args.out]
        if args.quick:
            cmd.append("--quick")
        record = os.path.join(args.out, os.path.basename(c) + ".json")
        if os.path.exists(record):
            os.remove(record)
        print(f"== {c}", flush=True)
        t0 = time.time()
        try:
            rc = subprocess.run(cmd, timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            rc = "timeout"
        times[c] = time.time() - t0
        if not os.path.exists(record):
            failures.append(f"{c}: no verdicts (exit {rc})")
            summary.append({"case": c, "quantity": "case finished", "reference": "exit 0", "source": "run.py",
                            "measured": f"exit {rc}", "tolerance": "none", "pass": False})
            continue
        with open(record) as f:
            rec = json.load(f)
        if rec.get("skipped"):
            skipped[c] = rec["skipped"]
            continue
        verdicts = rec["verdicts"]
        summary.extend(verdicts)
        failures.extend(f"{c}: {v['quantity']}" for v in verdicts if not v["pass"])

    path = os.path.join(args.out, "summary.json")
    with open(path + ".tmp", "w") as f:
        json.dump(summary, f, indent=1)
    os.replace(path + ".tmp", path)

    print(f"\n{'case':<16} {'quantity':<58} {'measured':>14} {'reference':>14}  verdict")
    for v in summary:
        print(f"{v['case']:<16} {v['quantity'][:58]:<58} {str(v['measured'])[:14]:>14} {str(v['reference'])[:14]:>14}  "
              f"{'pass' if v['pass'] else 'FAIL'}")
    print("\n" + ", ".join(f"{c} {t:.0f} s" for c, t in times.items()) + f"; total {sum(times.values()):.0f} s")
    for c, why in skipped.items():
        print(f"skipped {c}: {why}")
    print(f"wrote {path}")
    if failures:
        print("failed: " + "; ".join(failures))
        sys.exit(1)


if __name__ == "__main__":
    main()
