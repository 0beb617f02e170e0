"""The verification kinds of boltrom_mesh: a cantilever plate (beam), a patch-test block (block),
two stacked blocks (blocks) and an eccentric flat punch (punch). The contract: boltrom_mesh.py."""

import numpy as np

from mesh_blocks import TOL, HexMesh, extrude, faces, find_node, grid, match_pair, round_half_up

# ---------------------------------------------------------------------------
# kind = beam, block, blocks
# ---------------------------------------------------------------------------
BEAM = dict(length=0.300, width=0.040, t=0.008, elements=(60, 8, 2))


def beam_elements(level):
    nx, ny, nz = BEAM["elements"]
    return (max(1, round_half_up(nx * level)), 2 * max(1, round_half_up(ny / 2 * level)),
            max(1, round_half_up(nz * level)))


def build_beam(level=1.0, length=None, elements=None):
    L = BEAM["length"] if length is None else float(length)
    nx, ny, nz = beam_elements(level) if elements is None else map(int, elements)
    if min(nx, ny, nz) < 1 or ny % 2 or L <= 0:
        raise ValueError("beam needs positive length, counts >= 1 and even NY")
    W, t = BEAM["width"], BEAM["t"]
    mesh = HexMesh("beam", level)
    P = grid(np.linspace(0.0, L, nx + 1), W / 2 * (2.0 * np.arange(ny + 1) - ny) / ny)
    mesh.add_merge_group([("plate",) + extrude(P, np.linspace(0.0, t, nz + 1))])
    mesh.finish()
    mesh.surfaces["clamp"] = faces(mesh, "plate", lambda x, y, z: np.abs(x) < TOL)
    mesh.surfaces["tip"] = faces(mesh, "plate", lambda x, y, z: np.abs(x - L) < TOL)
    mesh.points["load_point"] = find_node(mesh, "plate", (L, 0.0, t))
    mesh.info = dict(length=L, elements=[nx, ny, nz])
    return mesh


def build_block(level=1.0, n=3, size=0.01, seed=20240601, amplitude=0.2):
    mesh = HexMesh("block", level)
    xs = np.linspace(0.0, size, n + 1)
    X, H = extrude(grid(xs, xs), xs)
    rng = np.random.default_rng(seed)
    inner = np.all((X > TOL) & (X < size - TOL), axis=1)
    X = X.copy()
    X[inner] += rng.uniform(-amplitude, amplitude, (inner.sum(), 3)) * (size / n)
    mesh.add_merge_group([("block", X, H)])
    mesh.finish()
    on = [lambda x, y, z, a=a, v=v: np.abs((x, y, z)[a] - v) < TOL
          for a in range(3) for v in (0.0, size)]
    mesh.surfaces["boundary"] = np.concatenate([faces(mesh, "block", p) for p in on])
    mesh.surfaces["clamp"] = faces(mesh, "block", on[0])
    mesh.info = dict(elements=[n, n, n], seed=seed, perturbation=amplitude)
    return mesh


def build_blocks(level=1.0, n=None, size=0.01):
    n = max(1, round_half_up(2 * level)) if n is None else int(n)
    mesh = HexMesh("blocks", level)
    xs = np.linspace(0.0, size, n + 1)
    P = grid(xs, xs)
    mesh.add_merge_group([("lower",) + extrude(P, xs)])
    mesh.add_merge_group([("upper",) + extrude(P, size + xs)])
    mesh.finish()
    add_flat_pair(mesh, "upper", "lower", size)
    mesh.surfaces["clamp"] = faces(mesh, "lower", lambda x, y, z: np.abs(z) < TOL)
    mesh.surfaces["top"] = faces(mesh, "upper", lambda x, y, z: np.abs(z - 2 * size) < TOL)
    mesh.info = dict(elements=[n, n, n])
    return mesh


def add_flat_pair(mesh, part_a, part_b, z0):
    """The contact pair part_a_part_b between part_a's faces at z = z0 (side a) and part_b's."""
    Fa = faces(mesh, part_a, lambda x, y, z: np.abs(z - z0) < TOL, which=[0])
    Fb = faces(mesh, part_b, lambda x, y, z: np.abs(z - z0) < TOL, which=[1])
    Fa, Fb = match_pair(mesh.coords, Fa, Fb)
    name = f"{part_a}_{part_b}"
    mesh.surfaces[f"contact_{name}_a"] = Fa
    mesh.surfaces[f"contact_{name}_b"] = Fb
    mesh.pairs.append(name)


# The eccentric flat punch: x across the width (centre x = 0), y along the depth, z up.
PUNCH = dict(width=0.040, depth=0.004, layer_t=0.001, height=0.020, eccentricity=0.0125,
             elements=(40, 2, 2, 4))  # nx, ny, layer nz, punch nz at level 1


def build_punch(level=1.0, eccentricity=None, layer_t=None):
    """A punch (width b, depth d, height H) on a layer of the same footprint and thickness t,
    clamped at z = 0, meshed node to node at z = t; the load strip on the punch's top is
    centred on x = eccentricity, which must lie on a node or half-way between two."""
    nx, ny, nzl, nzp = (max(1, round_half_up(n * level)) for n in PUNCH["elements"])
    nx += nx % 2  # a node at x = 0, so that e lies on the node grid or half-way
    b, d, H = PUNCH["width"], PUNCH["depth"], PUNCH["height"]
    t = PUNCH["layer_t"] if layer_t is None else float(layer_t)
    e = PUNCH["eccentricity"] if eccentricity is None else float(eccentricity)
    h = b / nx
    if not (0 < t and abs(e) < b / 2) or abs(2 * e / h - round(2 * e / h)) > 1e-6:
        raise ValueError("punch: need t > 0 and |eccentricity| < %g on a node or half-way "
                         "between two (element %g m)" % (b / 2, h))
    mesh = HexMesh("punch", level)
    P = grid(b / 2 * (2.0 * np.arange(nx + 1) - nx) / nx, d / 2 * (2.0 * np.arange(ny + 1) - ny) / ny)
    mesh.add_merge_group([("layer",) + extrude(P, np.linspace(0.0, t, nzl + 1))])
    mesh.add_merge_group([("punch",) + extrude(P, np.linspace(t, t + H, nzp + 1))])
    mesh.finish()
    add_flat_pair(mesh, "punch", "layer", t)
    mesh.surfaces["clamp"] = faces(mesh, "layer", lambda x, y, z: np.abs(z) < TOL)
    top = faces(mesh, "punch", lambda x, y, z: np.abs(z - t - H) < TOL, which=[1])
    mesh.surfaces["top"] = top
    xc = mesh.coords[top][..., 0].mean(axis=1)
    mesh.surfaces["load_strip"] = top[np.abs(xc - e) < h - TOL]
    mesh.info = dict(elements=[nx, ny, nzl, nzp], width=b, depth=d, layer_thickness=t,
                     height=H, eccentricity=e)
    return mesh

