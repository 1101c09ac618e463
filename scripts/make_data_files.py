#!/usr/bin/python3
"""Writes the engine's shipped data files (data/): the paper's listings load them through
GetDEMEDataFile. Run with /usr/bin/python3 from anywhere; it rewrites

  data/mesh/internal_mixer.obj  a bladed mixer: a hub and four pitched blades (the geometry of
                                demos/MixerGeometry.h), in a unit frame: z is the shaft, the mesh
                                spans z in [-0.45, 0.45] and reaches radius 0.96, so the listing's
                                Scale([0.5, 0.5, 1/3]) makes it 0.3 m tall and 0.48 m in radius
                                inside the 0.5 m cylinder and 1/3 m chamber;
  data/clumps/3_clump.csv       three spheres of radius 0.8 in their principal frame, whose union
                                has the volume and principal moments per unit density that the
                                paper's listing uses (5.5886717; 2.928, 2.6029, 3.9908);

  scripts/make_data_files.py [--check-mass]   (--check-mass integrates the clump's mass properties)
The pytest suite (python/tests/test_data_files.py) checks that the files equal this script's
output and that the clump's mass properties match the listing's numbers.
"""
import math
import os
import sys

# The mixer in its unit frame (see the docstring); the same construction as MixerGeometry.h.
MIXER = dict(hub_radius=0.12, height=0.9, tip_radius=0.96, blade_thickness=0.04, pitch_deg=15.0,
             num_blades=4, hub_segments=32)

# Component spheres (x, y, z, r): centres chosen so that the union's centre of mass is the origin.
CLUMP_3 = [(0.5, 0.341729, 0.0, 0.8), (0.0, -0.658271, 0.0, 0.8), (-0.5, 0.341729, 0.0, 0.8)]


def mixer_mesh(hub_radius, height, tip_radius, blade_thickness, pitch_deg, num_blades, hub_segments):
    """Vertices and 0-based counter-clockwise (outward) triangles of the hub and the blades."""
    verts, faces = [], []
    h, t = 0.5 * height, 0.5 * blade_thickness
    # Hub: a closed cylinder about z (side quads and two fans).
    b = len(verts)
    for i in range(hub_segments):
        a = 2.0 * math.pi * i / hub_segments
        x, y = hub_radius * math.cos(a), hub_radius * math.sin(a)
        verts += [(x, y, -h), (x, y, h)]
    bottom, top = len(verts), len(verts) + 1
    verts += [(0.0, 0.0, -h), (0.0, 0.0, h)]
    for i in range(hub_segments):
        j = (i + 1) % hub_segments
        lo_i, lo_j = b + 2 * i, b + 2 * j
        faces += [(lo_i, lo_j, lo_j + 1), (lo_i, lo_j + 1, lo_i + 1), (bottom, lo_j, lo_i), (top, lo_i + 1, lo_j + 1)]
    # Blades: boxes from inside the hub to the tip, pitched about their radial axis; the outer end
    # is placed so that the farthest corner lies at tip_radius.
    pitch = math.radians(pitch_deg)
    cp, sp = math.cos(pitch), math.sin(pitch)
    y_far = t * cp + h * abs(sp)
    x_out, x_in = math.sqrt(max(tip_radius ** 2 - y_far ** 2, 0.0)), 0.5 * hub_radius
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    for k in range(num_blades):
        a = 2.0 * math.pi * k / num_blades
        ca, sa = math.cos(a), math.sin(a)
        b = len(verts)
        for i in range(8):  # corner bits: 1 -> outer end, 2 -> +y side, 4 -> top
            x = x_out if i & 1 else x_in
            y = t if i & 2 else -t
            z = h if i & 4 else -h
            yp, zp = y * cp - z * sp, y * sp + z * cp
            verts.append((x * ca - yp * sa, x * sa + yp * ca, zp))
        for q in quads:
            faces += [(b + q[0], b + q[1], b + q[2]), (b + q[0], b + q[2], b + q[3])]
    return verts, faces


def mixer_obj_text():
    verts, faces = mixer_mesh(**MIXER)
    lines = ["# Bladed mixer: hub and %d blades pitched %g deg; z is the shaft axis, origin the centre."
             % (MIXER["num_blades"], MIXER["pitch_deg"]),
             "# Unit frame: radius %g, height %g. Made by scripts/make_data_files.py." % (MIXER["tip_radius"],
                                                                                       MIXER["height"]),
             "# %d vertices, %d triangles" % (len(verts), len(faces))]
    lines += ["v %.9g %.9g %.9g" % v for v in verts]
    lines += ["f %d %d %d" % (f[0] + 1, f[1] + 1, f[2] + 1) for f in faces]
    return "\n".join(lines) + "\n"


def union_mass_properties(spheres, n=400):
    """Volume, centre and principal moments (about the centre, per unit density) of the union of
    the spheres, by midpoint integration on an n-cell grid along the longest axis."""
    import numpy as np
    lo = np.min([[x - r, y - r, z - r] for x, y, z, r in spheres], axis=0)
    hi = np.max([[x + r, y + r, z + r] for x, y, z, r in spheres], axis=0)
    d = (hi - lo).max() / n
    axes = [lo[k] + d * (np.arange(int(math.ceil((hi[k] - lo[k]) / d))) + 0.5) for k in range(3)]
    X, Y = np.meshgrid(axes[0], axes[1], indexing="ij")
    vol, first, second = 0.0, np.zeros(3), np.zeros(3)  # second: sums of x^2, y^2, z^2
    for z in axes[2]:
        inside = np.zeros(X.shape, bool)
        for x0, y0, z0, r in spheres:
            inside |= (X - x0) ** 2 + (Y - y0) ** 2 + (z - z0) ** 2 <= r * r
        xs, ys, cnt = X[inside], Y[inside], inside.sum()
        vol += cnt
        first += [xs.sum(), ys.sum(), z * cnt]
        second += [(xs ** 2).sum(), (ys ** 2).sum(), z * z * cnt]
    dv = d ** 3
    com = first / vol
    sq = second / vol - com ** 2  # per unit volume, about the centre
    vol *= dv
    moi = vol * np.array([sq[1] + sq[2], sq[0] + sq[2], sq[0] + sq[1]])
    return vol, com, moi


def clump_csv_text():
    lines = ["# Three spheres of radius 0.8 in the clump's principal frame (centre of mass at the origin).",
             "# Union's volume 5.5886717 and principal moments per unit density (2.928, 2.6029, 3.9908):",
             "# mass = density * 5.5886717, MOI = density * (2.928, 2.6029, 3.9908), as in the paper's listing.",
             "# Made by scripts/make_data_files.py (--check-mass integrates them).",
             "x,y,z,r"]
    lines += ["%g,%g,%g,%g" % s for s in CLUMP_3]
    return "\n".join(lines) + "\n"


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)  # never a half-written file


if __name__ == "__main__":
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data")
    write(os.path.join(root, "mesh", "internal_mixer.obj"), mixer_obj_text())
    write(os.path.join(root, "clumps", "3_clump.csv"), clump_csv_text())
    if "--check-mass" in sys.argv:
        vol, com, moi = union_mass_properties(CLUMP_3)
        print("3_clump: volume %.6f, centre (%.2e, %.2e, %.2e), MOI (%.5f, %.5f, %.5f)" % (vol, *com, *moi))
