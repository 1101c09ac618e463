# Memory by array group from Python (GetMemoryStats, ShowMemoryStats; docs/memory.md): the groups
# add up to the totals, the state's groups hold at least their arrays, and a call before
# Initialize is a deme.Error naming it; Initialize's estimate of the run's memory, and a scene larger
# than the memory there (DEME_MEMORY_LIMIT) failing at Initialize.
import pytest

import deme
from conftest import pouring_block

GROUPS = ["owner_state", "geometry", "contacts_and_history", "wildcards", "detection_scratch", "output_staging",
          "step_scratch"]


def settled_block():
    sim, n = pouring_block()
    with pytest.raises(deme.Error, match="GetMemoryStats"):
        sim.GetMemoryStats()
    sim.Initialize()
    sim.DoDynamics(0.02)
    return sim, n


def test_groups_add_up_and_hold_the_state(capfd):
    sim, n = settled_block()
    m = sim.GetMemoryStats()
    assert m["spheres"] == n
    assert sorted(m["host"]) == sorted(GROUPS) and sorted(m["device"]) == sorted(GROUPS)
    assert m["host_total"] == sum(m["host"].values())
    assert m["device_total"] == sum(m["device"].values())
    # Every sphere is an owner here: at least its position, velocities and loads (over 60 bytes).
    assert m["host"]["owner_state"] >= 60 * n
    # At least each sphere's radius and material (an owner's position is decoded where it is read,
    # not cached: docs/memory.md).
    assert m["host"]["geometry"] >= 5 * n
    # The contact sets live where the backend steps: on the GPU the host keeps no copy of them.
    side = "device" if sim.GetBackend() == "cuda" else "host"
    assert m[side]["contacts_and_history"] > 0
    if side == "device":
        assert m["host"]["contacts_and_history"] == 0
    assert sorted(m["device_peak"]) == sorted(GROUPS)
    assert m["device_peak_total"] == sum(m["device_peak"].values())
    if sim.GetBackend() == "cuda":
        assert m["device_total"] == sim.GetDeviceMemUsage()
        assert m["device_peak_total"] >= m["device_total"]
    else:
        assert m["device_total"] == 0
        assert m["device_peak_total"] == 0
    sim.ShowMemoryStats()
    out = capfd.readouterr().out
    assert "contacts and history" in out and "total" in out


def test_initialize_estimates_the_memory_and_refuses_a_scene_too_large(monkeypatch):
    sim, n = pouring_block()
    sim.Initialize()
    m = sim.GetMemoryStats()
    assert sorted(m["estimate"]) == sorted(GROUPS)
    assert m["estimate_total"] == sum(m["estimate"].values()) > 0
    assert m["estimated_pairs"] == 6 * n
    monkeypatch.setenv("DEME_MEMORY_LIMIT", str(m["estimate_total"] // 2))
    small, _ = pouring_block()
    with pytest.raises(deme.Error, match=r"Initialize.*needs about %d bytes" % m["estimate_total"]):
        small.Initialize()
