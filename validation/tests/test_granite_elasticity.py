"""The granite specimen's affine elasticity (validation/granite_model.py), without a simulation: a
block of spheres on a simple cubic lattice, bonded to its six nearest neighbours only, has under
uniaxial stress along z the modulus k_n / a of its columns of springs (a = 2R the spacing; the shear
springs along the axes carry no normal stress), whatever its size, with the section and height the
compression test measures."""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import granite_model as gm  # noqa: E402


def simple_cubic(nx, ny, nz):
    a = 2.0 * gm.RADIUS
    i, j, k = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
    return a * np.c_[i.ravel(), j.ravel(), k.ravel()].astype(np.float64)


def test_simple_cubic_block_has_its_columns_modulus():
    for n in ((3, 3, 5), (6, 4, 9)):
        pts = simple_cubic(*n)
        # gamma_int 0.2: the six at a = 2R are bonded, the next ones (at sqrt(2) a) are not
        e = gm.specimen_modulus(pts, [0.0, 0.0, 0.0], 0.2)
        # per unit E_micro: k_n = E_micro R for equal spheres, so k_n / a = 1/2
        assert math.isclose(e, 0.5, rel_tol=1e-9), (n, e)


def test_infinite_lattice_is_stiffer_than_a_block_of_it():
    # The 12-neighbour HCP lattice per unit E_micro, and a block's bonds are a subset of the lattice's.
    inf = gm.affine_modulus(1, gm.RADIUS)[0]
    a = 2.0 * gm.RADIUS
    pts = []
    for k in range(8):
        for j in range(4):
            for i in range(4):
                off = (0.5 * a, a * math.sqrt(3) / 6) if k % 2 else (0.0, 0.0)
                pts.append((a * (i + 0.5 * (j % 2)) + off[0], a * math.sqrt(3) / 2 * j + off[1],
                            k * a * math.sqrt(2 / 3)))
    e = gm.specimen_modulus(np.array(pts), [0.0, 0.0, 0.0], 0.1)
    assert 0.3 * inf < e < inf


def test_paper_block_is_the_papers_26754_spheres():
    # The paper's specimen: 21 spheres to a row, 26 rows, 49 layers of the HCP lattice of touching
    # spheres (26,754; paper s. 6.4), 5.16 x 5.51 x 9.65 cm with the radii (the offset rows and layers).
    import deme

    pts = gm.lattice(deme, gm.PAPER_BLOCK_HALF)
    assert len(pts) == 21 * 26 * 49 == 26754
    layers = np.unique(np.round(pts[:, 2] / gm.RADIUS, 6))
    assert len(layers) == 49
    layer = pts[np.isclose(pts[:, 2], pts[:, 2].min())]
    rows = np.unique(np.round(layer[:, 1] / gm.RADIUS, 6))
    assert len(rows) == 26 and len(layer) == 21 * 26
    extent = pts.max(axis=0) - pts.min(axis=0) + 2 * gm.RADIUS
    assert np.allclose(extent, [0.0516, 0.05505, 0.09646], atol=5e-5), extent
