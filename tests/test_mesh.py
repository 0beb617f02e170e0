"""Facts about the all-hex meshes of python/boltrom_mesh.py (scripts/mesh-joint).

The joint meshes are written to .msh, read back with gmsh and checked from the
file.  Run: /usr/bin/python3 -m pytest -q tests/test_mesh.py
"""
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
import boltrom_mesh as bm  # noqa: E402

MM = 1e-3
CTR = np.array([0.130, 0.0])
PARTS = ["plate1", "plate2", "bolt", "washer_head", "washer_nut", "nut"]
PAIRS = {  # pair: (z, rmin, rmax) of the shared annulus (None: overlap square)
    "head_washer": (0.018, 5.25 * MM, 8.5 * MM),
    "washer_plate2": (0.016, 5.5 * MM, 10 * MM),
    "plate2_plate1": (0.008, None, None),
    "plate1_washer": (0.0, 5.5 * MM, 10 * MM),
    "washer_nut": (-0.002, 5.25 * MM, 8.5 * MM),
}
SURFACES = (["contact_%s_%s" % (p, s) for p in PAIRS for s in "ab"]
            + ["clamp", "preload_lower", "preload_upper"])
POINTS = {"load_point": (0.260, 0.0, 0.016), "corner_point": (0.260, 0.020, 0.016)}


class Msh:
    """A .msh read back with gmsh: xyz[tag] and groups[name] = node tags."""

    def __init__(self, path):
        d = bm.read_msh(path)
        self.tags = d["tags"]
        self.xyz = np.full((self.tags.max() + 1, 3), np.nan)
        self.xyz[self.tags] = d["coords"]
        self.types = {name: (dim, t) for (dim, name), (t, _, _) in d["groups"].items()}
        self.conn = {name: c for (dim, name), (_, c, _) in d["groups"].items()}

    def nodes(self, name):
        return np.unique(self.conn[name])


def write_joint(tmp, level, ascii=False):
    mesh = bm.build_joint(level)
    rep = bm.report(mesh)
    path = str(tmp / ("joint_%g.msh" % level))
    bm.write_msh(mesh, path, ascii=ascii)
    return path, rep, Msh(path)


@pytest.fixture(scope="module", params=[0.5, 1.0], ids=["L0.5", "L1"])
def joint(request, tmp_path_factory):
    return write_joint(tmp_path_factory.mktemp("joint"), request.param)


def radius(X):
    return np.hypot(X[..., 0] - CTR[0], X[..., 1] - CTR[1])


# DOFs and contact DOFs per level as docs/model.md tables them; level 1 is the paper's mesh
# (16,065 DOFs and 3,888 contact DOFs in the paper: within 3 % and exact)
SIZES = {0.5: (3954, 1536), 1.0: (16266, 3888)}


def test_mesh_size(joint):
    path, rep, m = joint
    dofs = 3 * len(m.tags)
    contact = np.unique(np.concatenate([m.nodes("contact_%s_%s" % (p, s))
                                        for p in PAIRS for s in "ab"]))
    assert (dofs, 3 * len(contact)) == SIZES[rep["level"]], (dofs, 3 * len(contact))
    if rep["level"] == 1.0:
        assert abs(dofs - 16065) <= 0.03 * 16065, dofs
    assert rep["dofs"] == dofs and rep["contact_dofs"] == 3 * len(contact)


def test_level4_has_a_million_dofs():
    mesh = bm.build_joint(4.0)
    assert 3 * len(mesh.coords) >= 1_000_000


def test_physical_groups(joint):
    _, _, m = joint
    for p in PARTS:
        assert m.types[p] == (3, [bm.GMSH_HEX])
    for s in SURFACES:
        assert m.types[s] == (2, [bm.GMSH_QUAD])
    for p in POINTS:
        assert m.types[p] == (0, [bm.GMSH_POINT])
    assert set(m.types) == set(PARTS) | set(SURFACES) | set(POINTS)


def test_hexes_valid(joint):
    _, rep, m = joint
    for p in PARTS:
        sj = bm.scaled_jacobian(m.xyz, m.conn[p])
        assert sj.min() > 0.3, (p, sj.min())
    assert rep["min_scaled_jacobian"] > 0.3
    # every node of the file is used by a hexahedron
    used = np.unique(np.concatenate([m.conn[p].ravel() for p in PARTS]))
    assert np.array_equal(used, np.sort(m.tags))


def test_contact_pairs_match_node_to_node(joint):
    _, rep, m = joint
    for pair, (z0, rmin, rmax) in PAIRS.items():
        Fa, Fb = m.conn["contact_%s_a" % pair], m.conn["contact_%s_b" % pair]
        assert Fa.shape == Fb.shape and len(Fa) > 0
        Xa, Xb = m.xyz[Fa], m.xyz[Fb]
        assert np.abs(Xa - Xb).max() < 1e-12, pair
        assert len(np.intersect1d(Fa, Fb)) == 0, pair
        assert np.abs(Xa[..., 2] - z0).max() < 1e-12
        if rmin is not None:
            r = radius(Xa)
            assert r.min() > rmin - 1e-9 and r.max() < rmax + 1e-9
            assert abs(r.min() - rmin) < 1e-9 and abs(r.max() - rmax) < 1e-9
        else:   # overlap square x in [0.110, 0.150], minus the hole
            assert abs(Xa[..., 0].min() - 0.110) < 1e-12 and abs(Xa[..., 0].max() - 0.150) < 1e-12
            assert abs(np.abs(Xa[..., 1]).max() - 0.020) < 1e-12
            assert abs(radius(Xa).min() - 5.5 * MM) < 1e-9
        # right-hand-rule normal of side a points down, out of the upper body a
        n = np.cross(Xa[:, 2] - Xa[:, 0], Xa[:, 3] - Xa[:, 1])
        assert np.all(n[:, 2] < 0) and np.abs(n[:, :2]).max() < 1e-12 * np.abs(n[:, 2]).min()
        assert rep["contact_dofs_per_pair"][pair] == 3 * (len(np.unique(Fa)) + len(np.unique(Fb)))
    # each side belongs to the right part
    owner = {"head_washer": ("bolt", "washer_head"), "washer_plate2": ("washer_head", "plate2"),
             "plate2_plate1": ("plate2", "plate1"), "plate1_washer": ("plate1", "washer_nut"),
             "washer_nut": ("washer_nut", "nut")}
    for pair, (pa, pb) in owner.items():
        assert np.isin(m.nodes("contact_%s_a" % pair), m.nodes(pa)).all()
        assert np.isin(m.nodes("contact_%s_b" % pair), m.nodes(pb)).all()


@pytest.mark.parametrize("level", [0.6, 0.7, 0.8, 1.3, 1.5])
def test_contact_pairs_match_at_other_levels(tmp_path, level):
    """Between the published levels too (0.7: the stress sweep's refused level), the two
    sides of every pair have the same nodes, coincident and distinct, face by face."""
    _, rep, m = write_joint(tmp_path, level)
    for pair in PAIRS:
        Fa, Fb = m.conn["contact_%s_a" % pair], m.conn["contact_%s_b" % pair]
        na, nb = m.nodes("contact_%s_a" % pair), m.nodes("contact_%s_b" % pair)
        assert len(na) == len(nb) > 0, (level, pair, len(na), len(nb))
        assert Fa.shape == Fb.shape, (level, pair)
        assert np.abs(m.xyz[Fa] - m.xyz[Fb]).max() < 1e-12, (level, pair)
        assert len(np.intersect1d(na, nb)) == 0, (level, pair)
        Xa, Xb = m.xyz[na], m.xyz[nb]
        Xa, Xb = Xa[np.lexsort(Xa.T)], Xb[np.lexsort(Xb.T)]
        assert np.abs(Xa - Xb).max() < 1e-12, (level, pair)
        assert rep["contact_dofs_per_pair"][pair] == 6 * len(na)


def test_contact_areas(joint):
    _, rep, m = joint
    N = rep["divisions"]["n_theta"]
    poly = lambda r: 0.5 * N * r * r * math.sin(2 * math.pi / N)  # noqa: E731
    for pair, (_, rmin, rmax) in PAIRS.items():
        X = m.xyz[m.conn["contact_%s_a" % pair]]
        x, y = X[..., 0], X[..., 1]
        area = -0.5 * np.sum(x * np.roll(y, -1, 1) - np.roll(x, -1, 1) * y)  # side a is clockwise
        exact = (0.040 * 0.040 - poly(5.5 * MM)) if rmin is None else poly(rmax) - poly(rmin)
        assert abs(area - exact) < 1e-9 * exact, pair


def test_node_sharing(joint):
    _, rep, m = joint
    nodes = {p: m.nodes(p) for p in PARTS}
    for i, p in enumerate(PARTS):
        for q in PARTS[i + 1:]:
            common = np.intersect1d(nodes[p], nodes[q])
            if {p, q} != {"bolt", "nut"}:
                assert len(common) == 0, (p, q)
    common = np.intersect1d(nodes["bolt"], nodes["nut"])
    X = m.xyz[common]
    assert np.abs(radius(X) - 5 * MM).max() < 1e-9
    assert X[:, 2].min() > -0.010 - 1e-12 and X[:, 2].max() < -0.002 + 1e-12
    # all bolt nodes on r = 5 mm within the nut height are shared
    Xb = m.xyz[nodes["bolt"]]
    on = (np.abs(radius(Xb) - 5 * MM) < 1e-9) & (Xb[:, 2] < -0.002 + 1e-12)
    assert on.sum() == len(common)
    d = rep["divisions"]
    assert len(common) == d["n_theta"] * (d["nzn"] + 1)


def test_points(joint):
    _, _, m = joint
    for name, xyz in POINTS.items():
        tags = m.nodes(name)
        assert len(tags) == 1
        assert np.abs(m.xyz[tags[0]] - xyz).max() < 1e-12
        assert tags[0] in m.nodes("plate2")


def test_clamp_and_preload(joint):
    _, rep, m = joint
    X = m.xyz[m.conn["clamp"]]
    assert np.abs(X[..., 0]).max() < 1e-12
    assert np.isin(m.nodes("clamp"), m.nodes("plate1")).all()
    d = rep["divisions"]
    assert len(m.conn["clamp"]) == d["n_theta"] // 4 * d["nzp"]
    h = rep["preload_h"]
    zs = []
    for name, sign in (("preload_lower", -1), ("preload_upper", 1)):
        X = m.xyz[m.conn[name]]
        z = 0.008 + sign * h / 2
        assert np.abs(X[..., 2] - z).max() < 1e-12
        assert radius(X).max() < 5 * MM + 1e-9
        assert np.isin(m.nodes(name), m.nodes("bolt")).all()
        assert len(m.nodes(name)) == len(np.unique(m.nodes(name)))
        zs.append(z)
    # exactly one element layer of the shank between the two sections
    zb = np.unique(np.round(m.xyz[m.nodes("bolt")][:, 2], 12))
    assert np.sum((zb > zs[0] + 1e-12) & (zb < zs[1] - 1e-12)) == 0
    assert len(m.nodes("preload_lower")) == len(m.nodes("preload_upper"))


def test_volumes(joint):
    _, rep, m = joint
    N = rep["divisions"]["n_theta"]
    f = math.sin(2 * math.pi / N) / (2 * math.pi / N)    # polygon area / circle area
    circ = lambda r: math.pi * r * r                       # noqa: E731
    poly = lambda r: f * circ(r)                           # noqa: E731
    plate = lambda a: (0.150 * 0.040 - a(5.5 * MM)) * 0.008  # noqa: E731
    analytic = {"plate1": plate(circ), "plate2": plate(circ),
                "bolt": circ(5 * MM) * 0.028 + circ(8.5 * MM) * 0.0064,
                "washer_head": (circ(10 * MM) - circ(5.25 * MM)) * 0.002,
                "washer_nut": (circ(10 * MM) - circ(5.25 * MM)) * 0.002,
                "nut": (circ(8.5 * MM) - circ(5 * MM)) * 0.008}
    exact = {"plate1": plate(poly), "plate2": plate(poly),
             "bolt": poly(5 * MM) * 0.028 + poly(8.5 * MM) * 0.0064,
             "washer_head": (poly(10 * MM) - poly(5.25 * MM)) * 0.002,
             "washer_nut": (poly(10 * MM) - poly(5.25 * MM)) * 0.002,
             "nut": (poly(8.5 * MM) - poly(5 * MM)) * 0.008}
    for p in PARTS:
        v = bm.hex_volumes(m.xyz, m.conn[p])
        assert v.min() > 0
        v2 = bm.extruded_volumes(m.xyz, m.conn[p])
        assert np.allclose(v, v2, rtol=1e-9, atol=0)
        V = v.sum()
        assert abs(V - rep["volume_per_part"][p]) < 1e-12 * V
        assert abs(V - exact[p]) < 1e-9 * exact[p], p
        tol = 0.01 if p.startswith("plate") else (1 - f) + 1e-9
        assert abs(V - analytic[p]) <= tol * analytic[p], p


def test_cli_json_binary_ascii_and_atomic_output(tmp_path):
    out, js = tmp_path / "j.msh", tmp_path / "j.json"
    script = os.path.join(ROOT, "scripts", "mesh-joint")
    r = subprocess.run([script, "--level", "0.5", "--output", str(out), "--json", str(js)],
                       capture_output=True, text=True, check=True)
    assert "DOFs" in r.stdout and "min scaled Jacobian" in r.stdout
    rep = json.load(open(js))
    for key in ("nodes", "dofs", "contact_dofs", "contact_dofs_per_pair", "elements_per_part",
                "volume_per_part", "min_scaled_jacobian", "level"):
        assert key in rep
    assert rep["dofs"] == 3 * rep["nodes"] and rep["level"] == 0.5
    assert set(rep["contact_dofs_per_pair"]) == set(PAIRS)
    assert set(rep["elements_per_part"]) == set(PARTS)
    assert sum(rep["contact_dofs_per_pair"].values()) == rep["contact_dofs"]
    with open(out, "rb") as f:
        head = f.read(40)
    assert head.startswith(b"$MeshFormat\n4.1 1 8")          # binary by default
    out2 = tmp_path / "a.msh"
    subprocess.run([script, "-q", "--level", "0.5", "--ascii", "--output", str(out2)], check=True)
    with open(out2, "rb") as f:
        assert f.read(40).startswith(b"$MeshFormat\n4.1 0 8")
    assert len(Msh(str(out2)).tags) == rep["nodes"]
    assert sorted(os.listdir(tmp_path)) == ["a.msh", "j.json", "j.msh"]   # no temp leftovers


def test_beam(tmp_path):
    mesh = bm.build_beam(1.0)
    path = str(tmp_path / "beam.msh")
    bm.write_msh(mesh, path)
    m = Msh(path)
    assert len(m.conn["plate"]) == 60 * 8 * 2
    assert m.types["clamp"] == (2, [bm.GMSH_QUAD]) and len(m.conn["clamp"]) == 16
    assert np.abs(m.xyz[m.conn["tip"]][..., 0] - 0.300).max() < 1e-12
    assert np.abs(m.xyz[m.nodes("load_point")[0]] - (0.300, 0, 0.008)).max() < 1e-12
    v = bm.hex_volumes(m.xyz, m.conn["plate"]).sum()
    assert abs(v - 0.300 * 0.040 * 0.008) < 1e-12
    small = bm.build_beam(0.5, length=0.1, elements=(4, 2, 1))
    assert len(small.parts["plate"]) == 8
    with pytest.raises(ValueError):
        bm.build_beam(1.0, elements=(4, 3, 1))


def test_block(tmp_path):
    mesh = bm.build_block()
    path = str(tmp_path / "block.msh")
    bm.write_msh(mesh, path)
    m = Msh(path)
    H = m.conn["block"]
    assert len(H) == 27 and len(m.tags) == 64
    sj = bm.scaled_jacobian(m.xyz, H)
    assert 0.3 < sj.min() < 0.999              # distorted but valid
    assert len(m.conn["boundary"]) == 54 and len(m.conn["clamp"]) == 9
    assert np.abs(m.xyz[m.conn["clamp"]][..., 0]).max() < 1e-12
    assert abs(bm.hex_volumes(m.xyz, H).sum() - 1e-6) < 1e-18
    again = bm.build_block()
    assert np.array_equal(again.coords, mesh.coords)          # deterministic


def test_blocks(tmp_path):
    mesh = bm.build_blocks(1.0)
    path = str(tmp_path / "blocks.msh")
    bm.write_msh(mesh, path)
    m = Msh(path)
    assert len(m.conn["lower"]) == len(m.conn["upper"]) == 8
    Fa, Fb = m.conn["contact_upper_lower_a"], m.conn["contact_upper_lower_b"]
    assert np.abs(m.xyz[Fa] - m.xyz[Fb]).max() < 1e-12 and len(np.intersect1d(Fa, Fb)) == 0
    assert np.isin(Fa, m.nodes("upper")).all() and np.isin(Fb, m.nodes("lower")).all()
    assert len(np.intersect1d(m.nodes("lower"), m.nodes("upper"))) == 0
    assert np.abs(m.xyz[m.conn["clamp"]][..., 2]).max() < 1e-12
    assert np.abs(m.xyz[m.conn["top"]][..., 2] - 0.02).max() < 1e-12


def test_punch(tmp_path):
    e = 0.0125
    mesh = bm.build_punch(1.0, eccentricity=e)
    path = str(tmp_path / "punch.msh")
    bm.write_msh(mesh, path)
    m = Msh(path)
    b, d, t, H = 0.040, 0.004, 0.001, 0.020
    assert len(m.conn["layer"]) == 40 * 2 * 2 and len(m.conn["punch"]) == 40 * 2 * 4
    assert abs(bm.hex_volumes(m.xyz, m.conn["layer"]).sum() - b * d * t) < 1e-18
    assert abs(bm.hex_volumes(m.xyz, m.conn["punch"]).sum() - b * d * H) < 1e-15
    Fa, Fb = m.conn["contact_punch_layer_a"], m.conn["contact_punch_layer_b"]
    assert len(Fa) == 80 and np.abs(m.xyz[Fa] - m.xyz[Fb]).max() < 1e-12
    assert np.isin(Fa, m.nodes("punch")).all() and np.isin(Fb, m.nodes("layer")).all()
    assert np.abs(m.xyz[Fa][..., 2] - t).max() < 1e-12
    assert len(np.intersect1d(m.nodes("layer"), m.nodes("punch"))) == 0
    assert np.abs(m.xyz[m.conn["clamp"]][..., 2]).max() < 1e-12
    assert np.abs(m.xyz[m.conn["top"]][..., 2] - t - H).max() < 1e-12
    # the load strip: top faces whose area centre is x = e (one column of faces here)
    strip = m.xyz[m.conn["load_strip"]]
    assert len(strip) == 2 and np.abs(strip[..., 2] - t - H).max() < 1e-12
    assert abs(strip[..., 0].mean() - e) < 1e-12
    other = bm.build_punch(1.0, eccentricity=-0.005)  # on a node: two columns of faces
    on_node = other.coords[other.surfaces["load_strip"]]
    assert len(on_node) == 4 and abs(on_node[..., 0].mean() + 0.005) < 1e-12
    for bad in (0.0123, 0.021):
        with pytest.raises(ValueError):
            bm.build_punch(1.0, eccentricity=bad)


def test_petsc_reads_labels(tmp_path):
    PETSc = pytest.importorskip("petsc4py.PETSc")
    path, rep, _ = write_joint(tmp_path, 0.5)
    opts = PETSc.Options()
    opts.setValue("dm_plex_gmsh_use_regions", True)
    opts.setValue("dm_plex_gmsh_mark_vertices", True)
    try:
        dm = PETSc.DMPlex().createFromFile(path, interpolate=True)
    finally:
        opts.delValue("dm_plex_gmsh_use_regions")
        opts.delValue("dm_plex_gmsh_mark_vertices")
    cs, ce = dm.getHeightStratum(0)
    assert ce - cs == sum(rep["elements_per_part"].values())
    names = {dm.getLabelName(i) for i in range(dm.getNumLabels())}
    assert set(PARTS) | set(SURFACES) | set(POINTS) <= names

    def stratum(name):
        lab = dm.getLabel(name)
        vals = lab.getValueIS().getIndices()
        assert len(vals) == 1
        return lab.getStratumIS(vals[0]).getIndices()

    depth = dm.getLabel("depth")
    for p, n in rep["elements_per_part"].items():
        pts = stratum(p)
        assert len(pts) == n and all(depth.getValue(int(q)) == 3 for q in pts)
    for s, n in rep["faces_per_surface"].items():
        pts = stratum(s)
        assert len(pts) == n and all(depth.getValue(int(q)) == 2 for q in pts)
    vs, _ = dm.getDepthStratum(0)
    xyz = dm.getCoordinatesLocal().getArray().reshape(-1, 3)
    for p, x in POINTS.items():
        pts = stratum(p)
        assert len(pts) == 1 and np.abs(xyz[pts[0] - vs] - x).max() < 1e-12
