#!/usr/bin/python3
"""Reads the engine's VTU files back with meshio (a reader the engine has no part in) and checks them
against the CSV files of the same frame, value by value.

  check_vtu.py frame <dir> <time>       every <kind>_<variant>.vtu in dir against <kind>.csv
  check_vtu.py series <pvd> <t0> <t1>.. the .pvd lists one frame per time, in order, each a file whose
                                        TimeValue is that time
  check_vtu.py complete <vtu> <n> <t>.. the file reads as a whole frame of n points written at one of
                                        the times

Every value printed as the CSV prints it (%.9g) must give the CSV's text, integers must be equal, and
every array must have its documented type (Float64 points and overlap, Float32 other reals, Int32
ids, UInt8 family, material and contact type). Exit
status 0 when every check passes; each failure is printed.
"""
import csv
import glob
import os
import sys
import xml.etree.ElementTree as ET

import meshio
import numpy as np

# Array name -> its CSV columns, for the arrays with several components.
VECTORS = {"v": ["v_x", "v_y", "v_z"], "w": ["w_x", "w_y", "w_z"], "f": ["f_x", "f_y", "f_z"],
           "n": ["n_x", "n_y", "n_z"], "Q": ["Qw", "Qx", "Qy", "Qz"]}
INTS = {"owner": np.int32, "geomA": np.int32, "geomB": np.int32, "ownerA": np.int32, "ownerB": np.int32,
        "family": np.uint8, "material": np.uint8, "type": np.uint8}
FLOAT64 = {"overlap"}
CONTACT_TYPES = {"SS": 0, "SA": 1, "SM": 2}

failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL:", msg)


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def column(header, rows, name):
    i = header.index(name)
    return [r[i] for r in rows]


def expected_arrays(header):
    """The point-data arrays a CSV header implies: name -> CSV columns."""
    arrays, used = {}, {"X", "Y", "Z"}
    for name, cols in VECTORS.items():
        if all(c in header for c in cols):
            arrays[name] = cols
            used.update(cols)
    for h in header:
        if h not in used:
            arrays[h] = [h]
    return arrays


def compare(label, name, got, texts):
    """got: values read from the VTU (n x k); texts: the CSV's strings (n x k)."""
    if name in INTS:
        if got.dtype != INTS[name]:
            fail(f"{label}: {name} is {got.dtype}, expected {np.dtype(INTS[name])}")
        if name == "type":
            want = np.array([[CONTACT_TYPES[t] for t in row] for row in texts], dtype=np.int64)
        else:
            want = np.array(texts, dtype=np.int64)
        if not np.array_equal(got.astype(np.int64), want):
            fail(f"{label}: {name} differs from the CSV")
        return
    want_type = np.float64 if name in FLOAT64 else np.float32
    if got.dtype != want_type:
        fail(f"{label}: {name} is {got.dtype}, expected {np.dtype(want_type)}")
    # The CSV prints each value with %.9g: the VTU's value printed so must give the same text (9
    # digits pin a float exactly, and a double to the CSV's precision).
    printed = [["%.9g" % float(x) for x in row] for row in got]
    if printed != texts:
        bad = next((i, a, b) for i, (a, b) in enumerate(zip(printed, texts)) if a != b)
        fail(f"{label}: {name} differs from the CSV (row {bad[0]}: {bad[1]} vs {bad[2]})")


def check_points_file(vtu_path, csv_path, time):
    label = os.path.basename(vtu_path)
    mesh = meshio.read(vtu_path)
    header, rows = read_csv(csv_path)
    n = len(rows)
    if len(mesh.points) != n:
        fail(f"{label}: {len(mesh.points)} points, the CSV has {n} rows")
        return
    if mesh.points.dtype != np.float64:
        fail(f"{label}: points are {mesh.points.dtype}, expected float64")
    printed = [["%.9g" % x for x in p] for p in mesh.points.tolist()]
    if printed != [[r[header.index(c)] for c in "XYZ"] for r in rows]:
        fail(f"{label}: point coordinates differ from the CSV's X,Y,Z")
    vertices = sum(len(c.data) for c in mesh.cells if c.type == "vertex")
    if vertices != n or any(c.type != "vertex" for c in mesh.cells):
        fail(f"{label}: expected {n} vertex cells, got {[(c.type, len(c.data)) for c in mesh.cells]}")
    want = expected_arrays(header)
    if set(mesh.point_data) != set(want):
        fail(f"{label}: arrays {sorted(mesh.point_data)}, the CSV implies {sorted(want)}")
    for name, cols in want.items():
        if name not in mesh.point_data:
            continue
        got = np.asarray(mesh.point_data[name]).reshape(n, len(cols))
        texts = [[r[header.index(c)] for c in cols] for r in rows]
        compare(label, name, got, texts)
    check_time(label, mesh, time)


def read_legacy_polydata(path):
    """Points, triangles and the cell scalar 'owner' of a legacy ASCII POLYDATA file (meshio 5 reads
    no POLYDATA), by the format's keywords."""
    words = open(path).read().split()
    i = words.index("POINTS")
    n = int(words[i + 1])
    points = np.array(words[i + 3:i + 3 + 3 * n], dtype=np.float64).reshape(n, 3)
    i = words.index("POLYGONS")
    m = int(words[i + 1])
    polys = np.array(words[i + 3:i + 3 + 4 * m], dtype=np.int64).reshape(m, 4)
    i = words.index("LOOKUP_TABLE")
    owner = np.array(words[i + 2:i + 2 + m], dtype=np.int64)
    return points, polys[:, 1:], owner


def check_mesh_file(vtu_path, vtk_path, time):
    """Triangles against the legacy VTK file of the same frame."""
    label = os.path.basename(vtu_path)
    got = meshio.read(vtu_path)
    ref_points, ref_tri, ref_owner = read_legacy_polydata(vtk_path)
    tri = [c.data for c in got.cells if c.type == "triangle"]
    if len(tri) != 1 or len(tri[0]) != len(ref_tri) or len(ref_tri) == 0:
        fail(f"{label}: triangles {[len(t) for t in tri]} vs the VTK file's {len(ref_tri)}")
        return
    # The legacy file holds floats as text that reads back as the float.
    if not np.array_equal(got.points[tri[0]].astype(np.float32), ref_points[ref_tri].astype(np.float32)):
        fail(f"{label}: triangle corners differ from the VTK file's")
    owner = np.asarray(got.cell_data["owner"][0]).ravel()
    if owner.dtype != np.int32 or not np.array_equal(owner.astype(np.int64), ref_owner):
        fail(f"{label}: cell data owner ({owner.dtype}) differs from the VTK file's")
    check_time(label, got, time)


def check_time(label, mesh, time):
    tv = mesh.field_data.get("TimeValue")
    if tv is None or float(np.asarray(tv).ravel()[0]) != time:
        fail(f"{label}: TimeValue {tv}, expected {time!r}")


def check_frame(directory, time):
    files = sorted(glob.glob(os.path.join(directory, "*_*.vtu")))
    kinds = set()
    for vtu in files:
        kind = os.path.basename(vtu).split("_")[0]
        kinds.add(kind)
        if kind == "mesh":
            check_mesh_file(vtu, os.path.join(directory, "mesh.vtk"), time)
        else:
            check_points_file(vtu, os.path.join(directory, kind + ".csv"), time)
    print(f"checked {len(files)} VTU files ({', '.join(sorted(kinds))})")
    if not files:
        fail("no VTU files found")


def check_series(pvd, times):
    root = ET.parse(pvd).getroot()
    sets = root.findall("./Collection/DataSet")
    if root.get("type") != "Collection" or len(sets) != len(times):
        fail(f"{pvd}: {len(sets)} data sets, expected {len(times)}")
        return
    for ds, t in zip(sets, times):
        if float(ds.get("timestep")) != t:
            fail(f"{pvd}: timestep {ds.get('timestep')}, expected {t!r}")
        path = os.path.join(os.path.dirname(pvd), ds.get("file"))
        if not os.path.isfile(path):
            fail(f"{pvd}: lists {ds.get('file')}, which does not exist")
            continue
        check_time(os.path.basename(path), meshio.read(path), t)
    print(f"checked {len(sets)} frames of {os.path.basename(pvd)}")


def check_complete(path, n, times):
    """A whole frame: it reads, has n points, and is one of the frames written (by its time)."""
    try:
        mesh = meshio.read(path)
    except Exception as e:  # a truncated or corrupt file
        fail(f"{path}: unreadable: {e}")
        return
    if len(mesh.points) != n:
        fail(f"{path}: {len(mesh.points)} points, expected {n}")
    t = float(np.asarray(mesh.field_data["TimeValue"]).ravel()[0])
    if t not in times:
        fail(f"{path}: TimeValue {t!r} is none of the frames written")
    print(f"{os.path.basename(path)}: a whole frame of {n} points at t = {t!r}")


if __name__ == "__main__":
    if sys.argv[1] == "frame":
        check_frame(sys.argv[2], float(sys.argv[3]))
    elif sys.argv[1] == "complete":
        check_complete(sys.argv[2], int(sys.argv[3]), [float(t) for t in sys.argv[4:]])
    else:
        check_series(sys.argv[2], [float(t) for t in sys.argv[3:]])
    sys.exit(1 if failures else 0)
