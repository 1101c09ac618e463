"""The crater case's parts (CRATER_BED_CKPT, CRATER_DROPS, CRATER_FROM): drops run by separate commands
on one settled bed, judged and drawn together from their crater-data.json, without a simulation. The
drops here are made up (depths on the law's line, or off it), so that each verdict's outcome is known:
the test checks the bookkeeping (parts joined, mismatched beds and repeated drops refused), not the
physics, which the case's own runs check (its quick form split in parts gives the same depths bit for
bit as in one run: validation/README.md).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import replay as rp  # noqa: E402


def write_part(folder, drops, rho_g=1490.0, c=0.14, grains=5815):
    """crater-data.json of a part: each drop's depth d = c x, x made up from the drop."""
    record = {"grains": grains, "grain_scale": 1.0, "bed_cm": [3.0, 4.0], "rho_g": rho_g, "surface_m": 0.0423,
              "backend": "cuda", "commit": "test", "drops": []}
    for rho_b, h in drops:
        x = 0.05 * (rho_b / rho_g) ** 0.5 * (1.0 + h)
        record["drops"].append({"rho_b": rho_b, "h": h, "d": c * x, "x": x, "rest": True,
                                "t": [0.0, 0.05, 0.1], "path": [0.0, -0.5 * c * x, -c * x]})
    rp.write_data(folder, "crater-data.json", record)


def join(tmp_path, *folders):
    r, summary, out = rp.replay(tmp_path, "pending/crater", "CRATER_FROM", folders)
    return r, {v["quantity"].split(" (")[0]: v for v in summary}, out


def test_two_parts_are_judged_as_one_fit(tmp_path):
    write_part(tmp_path / "a", [(2200.0, 0.05), (2200.0, 0.2)])
    write_part(tmp_path / "b", [(7800.0, 0.1), (15000.0, 0.2)])
    r, verdicts, out = join(tmp_path, tmp_path / "a", tmp_path / "b")
    assert r.returncode == 0, r.stdout + r.stderr
    fit = verdicts["C of d = C x fitted to 4 drops"]
    assert fit["pass"] and abs(fit["measured"] - 0.14) < 1e-4
    assert verdicts["balls at rest when measured"]["measured"] == 4
    assert (out / "crater.png").exists()


def test_depths_off_the_law_fail(tmp_path):
    write_part(tmp_path / "a", [(2200.0, 0.05), (3800.0, 0.2)], c=0.10)
    r, verdicts, _ = join(tmp_path, tmp_path / "a")
    assert r.returncode == 1
    assert not verdicts["C of d = C x fitted to 2 drops"]["pass"]


def test_parts_of_different_beds_are_refused(tmp_path):
    write_part(tmp_path / "a", [(2200.0, 0.05)])
    write_part(tmp_path / "b", [(3800.0, 0.2)], rho_g=1500.0)
    r, verdicts, _ = join(tmp_path, tmp_path / "a", tmp_path / "b")
    assert r.returncode != 0 and list(verdicts) == ["case finished"] and not verdicts["case finished"]["pass"]
    assert "not the same bed" in r.stdout + r.stderr


def test_a_drop_in_two_parts_is_refused(tmp_path):
    write_part(tmp_path / "a", [(2200.0, 0.05)])
    write_part(tmp_path / "b", [(2200.0, 0.05), (3800.0, 0.2)])
    r, verdicts, _ = join(tmp_path, tmp_path / "a", tmp_path / "b")
    assert r.returncode != 0 and list(verdicts) == ["case finished"] and not verdicts["case finished"]["pass"]
    assert "more than one part" in r.stdout + r.stderr
