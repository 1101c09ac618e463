"""The drum case's replay of earlier runs (DRUM_FROM, DRUM_SHARD's parts): judged and drawn from their
drum-data.json alone, without a simulation. The maps here are made up, with angles chosen so that each
verdict's outcome is known: the test checks the bookkeeping (parts joined, verdicts present or left out,
mismatched parts refused), not the physics, which the case's own runs check.
"""
import json
import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import replay as rp  # noqa: E402
MUS, CRRS = [0.0, 0.45, 0.9], [0.0, 0.08]


def angle(mu, crr):
    """A made-up map: flat at mu = 0, rising with mu and with Crr."""
    return 0.0 if mu == 0.0 else 20.0 + 10.0 * mu + 40.0 * crr


def write_part(folder, mus, measure=3.0, shift=0.0):
    """drum-data.json of a PS map over the given mu columns (30 samples a point, +-0.2 deg of noise)."""
    points = []
    for c in CRRS:
        for m in mus:
            base = angle(m, c) + shift
            samples = [round(base + 0.2 * ((-1) ** k), 3) for k in range(30)]
            points.append({"mu": m, "Crr": c, "angle_deg": base, "se_deg": 0.05, "samples_deg": samples})
    data = {"settle_s": 0.3, "steady_s": 2.0, "measure_s": measure, "samples": 30, "mu": MUS, "Crr": CRRS,
            "walls": {}, "rolling": "relative", "peer_run": None, "peer_points": [[0.3, 0.0]],
            "backend": "cuda", "commit": "test", "runs": {"PS": {
                "depth_m": 0.2, "E_Pa": 1e7, "dt_s": 2e-5, "steady_s": 6.0, "grains_per_drum": 13024,
                "spheres": 13024 * len(points), "steps": 465000, "wall_s": 100.0, "points": points}}}
    rp.write_data(folder, "drum-data.json", data)


def replay(tmp_path, *folders):
    r, summary, out = rp.replay(tmp_path, "drum", "DRUM_FROM", folders)
    return r, {v["quantity"]: v for v in summary}, out


def test_two_parts_are_judged_as_one_map(tmp_path):
    write_part(tmp_path / "a", [0.0, 0.9])
    write_part(tmp_path / "b", [0.45])
    r, verdicts, out = replay(tmp_path, tmp_path / "a", tmp_path / "b")
    assert r.returncode == 0, r.stdout + r.stderr
    assert verdicts["spheres at mu = 0: largest angle over Crr (deg)"]["pass"]
    rise_mu = verdicts["PS: angle rises with mu (every Crr)"]
    assert rise_mu["pass"]
    assert verdicts["PS: angle rises with Crr (every mu > 0)"]["pass"]
    assert (out / "drum.png").exists()
    data = json.loads((out / "drum-data.json").read_text())
    assert len(data["runs"]["PS"]["points"]) == len(MUS) * len(CRRS)


def test_a_part_without_mu_zero_has_no_such_verdict(tmp_path):
    write_part(tmp_path / "b", [0.45])
    r, verdicts, _ = replay(tmp_path, tmp_path / "b")
    assert r.returncode == 0, r.stdout + r.stderr
    # one column: no line along mu, no mu = 0 point; only the line along Crr is judged
    assert list(verdicts) == ["PS: angle rises with Crr (every mu > 0)"]


def test_a_falling_line_fails(tmp_path):
    # part b's column 20 degrees higher: the line along mu falls from mu = 0.45 to 0.9
    write_part(tmp_path / "a", [0.0, 0.9])
    write_part(tmp_path / "b", [0.45], shift=20.0)
    r, verdicts, _ = replay(tmp_path, tmp_path / "a", tmp_path / "b")
    assert r.returncode == 1
    assert not verdicts["PS: angle rises with mu (every Crr)"]["pass"]


def test_parts_measured_differently_are_refused(tmp_path):
    write_part(tmp_path / "a", [0.0, 0.9])
    write_part(tmp_path / "b", [0.45], measure=7.0)
    r, verdicts, _ = replay(tmp_path, tmp_path / "a", tmp_path / "b")
    assert r.returncode == 1 and not verdicts.get("PS: angle rises with mu (every Crr)")
    assert "the runs differ in measure_s" in r.stdout + r.stderr


def test_pc_crr_values_off_the_grid_are_refused(tmp_path):
    # DRUM_PC_CRR picks the PC map's Crr values among the grid's (so that parts join on one grid):
    # 0.03 is not on the 13 x 5 grid's 0, 0.02, ..., 0.08, and the case stops before any drum is set up
    env = dict(os.environ, DRUM_GRID="13x5", DRUM_RUNS="PC", DRUM_PC_CRR="0.02,0.03")
    r = rp.run_case(tmp_path, "drum", env)
    assert r.returncode != 0
    assert "DRUM_PC_CRR='0.02,0.03': Crr values of the grid [0.0, 0.02, 0.04, 0.06, 0.08] only" in r.stdout + r.stderr


if __name__ == "__main__":
    sys.exit(pytest.main([__file__, "-q"]))
