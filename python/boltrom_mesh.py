"""All-hexahedral meshes for boltrom, built with numpy and written with the gmsh API.

The hexahedra are made here (structured blocks and O-grids of planar quads
extruded in z), then handed to gmsh as discrete entities and written as an
MSH 4.1 file (binary unless ``ascii=True``).  SI units: metres.

Kinds
-----
``joint``   the reference single-lap bolted joint (two plates, bolt, two
            washers, nut tied to the shank), five node-to-node contact pairs.
``beam``    a monolithic cantilever plate (verification against beam theory).
``block``   a 3 x 3 x 3 patch-test block with distorted interior nodes.
``blocks``  two stacked blocks with one node-to-node contact pair.
``punch``   a stiff block on a thin layer clamped at its bottom, one contact
            pair between them and a load strip off-centre on the block's top
            (eccentric flat punch: the strict law's test with a known contact
            length, tests/test_punch.py).

Contract with the C code (physical groups)
-----------------------------------------
Every physical group has a name; select groups by NAME where possible.  The
numeric physical tags are fixed (volumes 1, 2, ..., surfaces 101, ..., points
201, ...):
    joint : 1 plate1, 2 plate2, 3 bolt, 4 washer_head, 5 washer_nut, 6 nut,
            101/102 contact_head_washer_a/_b, 103/104 contact_washer_plate2_a/_b,
            105/106 contact_plate2_plate1_a/_b, 107/108 contact_plate1_washer_a/_b,
            109/110 contact_washer_nut_a/_b, 111 clamp, 112 preload_lower,
            113 preload_upper, 201 load_point, 202 corner_point
    beam  : 1 plate, 101 clamp, 102 tip, 201 load_point
    block : 1 block, 101 boundary, 102 clamp
    blocks: 1 lower, 2 upper, 101/102 contact_upper_lower_a/_b, 103 clamp, 104 top
    punch : 1 layer, 2 punch, 101/102 contact_punch_layer_a/_b, 103 clamp, 104 top,
            105 load_strip

How PETSc 3.18 (DMPlexCreateFromFile, interpolate) labels them:
    default: "Cell Sets" (value = volume tag) and "Face Sets" (value = surface
        tag); no vertex label.
    -dm_plex_gmsh_mark_vertices: adds "Vertex Sets" with values 201, 202
        (only the dim-0 groups, because no node sits on an entity that has a
        physical group).
    -dm_plex_gmsh_use_regions: one label per physical NAME instead (e.g. label
        "bolt", stratum 3 = its cells; "clamp", stratum 111 = its faces); the
        generic "Cell Sets"/"Face Sets" are then NOT created.  The dim-0 groups
        ("load_point", "corner_point") appear only with
        -dm_plex_gmsh_mark_vertices as well.

dim 3 (hexahedra, gmsh type 5), one group per part, named after the part:
    joint : plate1, plate2, bolt, washer_head, washer_nut, nut
    beam  : plate          block : block          blocks: lower, upper
    punch : layer, punch
dim 2 (quadrangles, gmsh type 3):
    contact_<pair>_a, contact_<pair>_b   the two sides of a contact pair.
        Side a is the upper body (larger z).  Both sides list their faces in
        the same order with the same node order: face i of side a and face i
        of side b have coincident (but distinct) nodes, node by node.  The
        right-hand-rule normal of the face points OUT of body a (towards b),
        i.e. downwards (-z); for side b the same order points into body b.
        joint pairs (a over b):
            head_washer    bolt head underside  / washer_head top, r 5.25..8.5 mm, z 0.018
            washer_plate2  washer_head bottom   / plate2 top,      r 5.5..10 mm,   z 0.016
            plate2_plate1  plate2 bottom        / plate1 top,      overlap square minus hole, z 0.008
            plate1_washer  plate1 bottom        / washer_nut top,  r 5.5..10 mm,   z 0
            washer_nut     washer_nut bottom    / nut top,         r 5.25..8.5 mm, z -0.002
        blocks pair: upper_lower (upper block bottom / lower block top, z 0.01)
        punch pair: punch_layer (punch bottom / layer top, z = layer thickness)
    clamp          joint: plate1 face x = 0; beam, block: face x = 0;
                   blocks: the lower block's face z = 0; punch: the layer's
                   face z = 0.  Outward normals.
    preload_lower, preload_upper   (joint) the shank cross-sections at
                   z = 0.008 - h/2 and 0.008 + h/2 that bound exactly one
                   element layer of height h; face normals point +z.
    tip            (beam) face x = L, outward normal.
    boundary       (block) all six outer faces, outward normals.
    top            (blocks) the upper block's face z = 0.02, (punch) the punch's
                   top face; outward normal.
    load_strip     (punch) the punch's top faces whose centres lie within one
                   element of x = eccentricity (one or two columns of faces,
                   symmetric about it: the resultant of a force spread on them
                   by area acts at x = eccentricity).
dim 0 (points, gmsh type 15), on existing nodes:
    load_point     joint: (0.260, 0, 0.016) on plate2; beam: (L, 0, 0.008).
    corner_point   joint: (0.260, 0.020, 0.016) on plate2.

Node sharing: every part has its own nodes, except that the nut is tied to
the bolt shank: the nut's inner nodes at r = 5 mm are the shank's nodes.
All nodes are classified on one discrete volume entity (tag 1000) that has no
physical group and no elements; each group's elements sit on their own
discrete entity (tag = physical tag).  Hexahedra use gmsh's node order
(0-3 bottom face counter-clockwise seen from +z, 4-7 the top face above them).

Mesh density (kind=joint)
-------------------------
Level L scales every division count by about L: a count n at level 1 becomes
max(1, round(L n + (L - 1) / 2)) (half-way between L n elements and L (n + 1)
node layers; rounding half up), the angular division is
N_theta = 8 max(1, round(3 L)).  The DOF count grows like L^3: level 0.5:
3954 (plates keep 2 layers), 1: 16266 (3888 on contact), 2: 148410, 3: 426180, 4: 1087842.
"""

import json
import math
import os
import sys
import time

import numpy as np

# ---------------------------------------------------------------------------
# Geometry of the reference joint (metres)
# ---------------------------------------------------------------------------
JOINT = dict(
    bolt_x=0.130, bolt_y=0.0,
    plate_width=0.040, plate_t=0.008,
    plate1_x=(0.0, 0.150), plate2_x=(0.110, 0.260),
    r_hole=0.0055,
    r_shank=0.005, shank_z=(-0.010, 0.018),
    r_head=0.0085, head_z=(0.018, 0.0244),
    r_washer_in=0.00525, r_washer_out=0.010,
    washer_head_z=(0.016, 0.018), washer_nut_z=(-0.002, 0.0),
    r_nut_in=0.005, r_nut_out=0.0085, nut_z=(-0.010, -0.002),
    core_frac=0.55,      # half side of the shank core square / shank radius
)
JOINT_PARTS = ("plate1", "plate2", "bolt", "washer_head", "washer_nut", "nut")
JOINT_PAIRS = ("head_washer", "washer_plate2", "plate2_plate1",
               "plate1_washer", "washer_nut")

# Division counts at level 1 (see level_counts)
JOINT_BASE = dict(
    n8=3,      # N_theta = 8 * n8 angular divisions
    k=2,       # shank core square -> r = 5 mm
    g=1,       # 5 -> 5.25 mm and 5.25 -> 5.5 mm
    m1=3,      # 5.5 -> 8.5 mm
    m2=1,      # 8.5 -> 10 mm
    m3=2,      # 10 mm circle -> 40 x 40 mm overlap square
    nx=16,     # x divisions of each plate outside the overlap square
    nzp=3,     # plate thickness
    nzw=2,     # washer thickness
    nzn=3,     # nut height (= shank below the nut's top)
    nzh=3,     # head height
    nmid=3,    # shank z in [-0.002, 0.018] has 2 nmid + 1 element layers
)

HEX_FACES = np.array([[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4],
                      [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]])
# corner c, then its three neighbours in right-handed order
HEX_CORNERS = np.array([[0, 1, 3, 4], [1, 2, 0, 5], [2, 3, 1, 6], [3, 0, 2, 7],
                        [4, 7, 5, 0], [5, 4, 6, 1], [6, 5, 7, 2], [7, 6, 4, 3]])
GMSH_HEX, GMSH_QUAD, GMSH_POINT = 5, 3, 15
NODE_ENTITY = 1000  # discrete volume entity that carries all nodes (no physical group)
TOL = 1e-9          # geometric tolerance (m) for selecting nodes/faces
QUANTUM = 1e-9      # rounding quantum (m) for merging nodes


def _round_half_up(x):
    return int(math.floor(x + 0.5))


def scale_count(n, level):
    """Division count at `level` for the count n at level 1.

    max(1, round(L n + (L - 1) / 2)): half-way between scaling the elements
    (L n) and the node layers (L (n + 1) - 1) by L, so that the DOF count of
    the joint grows like L^3 although many counts are small at level 1.
    """
    return max(1, _round_half_up(level * n + 0.5 * (level - 1.0)))


def level_counts(level, n_theta=None):
    """Division counts of the joint mesh at a (possibly fractional) level."""
    if level <= 0:
        raise ValueError("level must be positive")
    c = {key: scale_count(val, level) for key, val in JOINT_BASE.items()}
    c["n_theta"] = 8 * max(1, _round_half_up(level * JOINT_BASE["n8"]))
    if n_theta is not None:
        if n_theta < 8 or n_theta % 8:
            raise ValueError("n_theta must be a positive multiple of 8")
        c["n_theta"] = int(n_theta)
    del c["n8"]
    c["nzp"] = max(2, c["nzp"])        # bending: at least 2 elements through a plate
    c["n_mid"] = 2 * c.pop("nmid") + 1
    return c


# ---------------------------------------------------------------------------
# Building blocks
# ---------------------------------------------------------------------------
def extrude(P, z):
    """Hexahedra of a structured quad patch P (na+1, nb+1, 2) extruded over z.

    Quad (i,j),(i+1,j),(i+1,j+1),(i,j+1) must be counter-clockwise seen from
    +z; z increasing.  Returns (coords (n,3), hexes (E,8)) with local indices.
    """
    z = np.asarray(z, float)
    na1, nb1 = P.shape[:2]
    nz1 = len(z)
    X = np.empty((nz1, na1, nb1, 3))
    X[..., 0] = P[None, :, :, 0]
    X[..., 1] = P[None, :, :, 1]
    X[..., 2] = z[:, None, None]
    idx = np.arange(nz1 * na1 * nb1).reshape(nz1, na1, nb1)
    corners = []
    for dk in (0, 1):
        k = slice(dk, nz1 - 1 + dk)
        corners += [idx[k, :-1, :-1], idx[k, 1:, :-1], idx[k, 1:, 1:], idx[k, :-1, 1:]]
    H = np.stack(corners, axis=-1).reshape(-1, 8)
    return X.reshape(-1, 3), H


def merge_nodes(blocks):
    """Merge coincident nodes of a list of (name, coords, hexes) blocks.

    Keys are coordinates rounded to QUANTUM; merged nodes keep the order of
    first occurrence.  Returns coords (n,3) and {name: hexes} (names may
    repeat: their hexes are concatenated in order).
    """
    offs = np.cumsum([0] + [len(b[1]) for b in blocks])
    X = np.concatenate([b[1] for b in blocks])
    keys = np.round(X / QUANTUM).astype(np.int64)
    _, first, inv = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    inv = inv.reshape(-1)
    # guard against a pair of equal points split by a rounding boundary
    n_shift = len(np.unique(np.round(X / QUANTUM + 0.5).astype(np.int64), axis=0))
    if n_shift != len(first):
        raise RuntimeError("node merge is ambiguous (points closer than %g m)" % QUANTUM)
    order = np.argsort(first, kind="stable")
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    new = rank[inv]
    parts = {}
    for (name, _, H), o in zip(blocks, offs[:-1]):
        h = new[H + o]
        parts[name] = np.concatenate([parts[name], h]) if name in parts else h
    return X[first[order]], parts


def circle(center, r, cs):
    """Points of a circle of radius r at the angles whose (cos, sin) are cs."""
    return np.stack([center[0] + r * cs[0], center[1] + r * cs[1]], axis=-1)


def square(center, s, n_theta):
    """Perimeter points of the square of half side s, matched to the angles
    2 pi j / n_theta (j = 0 at (s, 0), counter-clockwise, corners at 45 deg),
    equally spaced along each side; also returns the side's node offsets u."""
    q = n_theta // 8
    n = 2 * q
    u = s * (2.0 * np.arange(n + 1) - n) / n          # exactly symmetric, u[q] = 0
    jj = (np.arange(n_theta) + q) % n_theta            # 0 at the corner (s, -s)
    side, p = jj // n, jj % n
    sx = np.select([side == 0, side == 1, side == 2, side == 3],
                   [np.full(n_theta, s), u[n - p], np.full(n_theta, -s), u[p]])
    sy = np.select([side == 0, side == 1, side == 2, side == 3],
                   [u[p], np.full(n_theta, s), u[n - p], np.full(n_theta, -s)])
    return np.stack([center[0] + sx, center[1] + sy], axis=-1), u


def band(curves):
    """Structured patch (len(curves), N+1, 2) from closed curves of N points,
    innermost first; the angular index wraps (column N is column 0)."""
    C = np.stack(curves)
    return np.concatenate([C, C[:, :1]], axis=1)


def blend(c0, c1, t):
    return (1.0 - t) * c0 + t * c1


def grid(xs, ys):
    """Structured patch of a rectangle (x along the first index)."""
    P = np.empty((len(xs), len(ys), 2))
    P[..., 0] = np.asarray(xs)[:, None]
    P[..., 1] = np.asarray(ys)[None, :]
    return P


# ---------------------------------------------------------------------------
# Mesh container, faces, quality
# ---------------------------------------------------------------------------
class HexMesh:
    """coords (n,3); parts {name: hexes (E,8)}; surfaces {name: quads (F,4)};
    points {name: node index}; pairs [pair names]; info: dict of parameters."""

    def __init__(self, kind, level):
        self.kind, self.level = kind, level
        self.coords = np.zeros((0, 3))
        self.parts, self.surfaces, self.points = {}, {}, {}
        self.pairs, self.info = [], {}

    def add_merge_group(self, blocks):
        X, parts = merge_nodes(blocks)
        off = len(self.coords)
        self.coords = np.concatenate([self.coords, X])
        for name, H in parts.items():
            self.parts[name] = H + off

    def finish(self):
        used = np.zeros(len(self.coords), bool)
        for H in self.parts.values():
            used[H.reshape(-1)] = True
        if not used.all():
            raise RuntimeError("mesh has nodes not used by any hexahedron")


def faces(mesh, part, pred, which=range(6)):
    """Outward faces (F,4) of `part`'s hexes whose 4 nodes all satisfy
    pred(x, y, z) (vectorised, returns bool arrays)."""
    H = mesh.parts[part]
    out = []
    for f in which:
        F = H[:, HEX_FACES[f]]
        X = mesh.coords[F]
        ok = np.all(pred(X[..., 0], X[..., 1], X[..., 2]), axis=1)
        out.append(F[ok])
    return np.concatenate(out)


def match_pair(coords, Fa, Fb):
    """Sort side a's faces and give side b the same order and node order."""
    if len(Fa) != len(Fb) or len(Fa) == 0:
        raise RuntimeError("contact sides have %d and %d faces" % (len(Fa), len(Fb)))

    def order(F):
        k = np.round(coords[F].mean(axis=1) / QUANTUM).astype(np.int64)
        return np.lexsort(k.T[::-1])

    Fa, Fb = Fa[order(Fa)], Fb[order(Fb)]
    perms = np.array([[0, 1, 2, 3], [1, 2, 3, 0], [2, 3, 0, 1], [3, 0, 1, 2],
                      [0, 3, 2, 1], [3, 2, 1, 0], [2, 1, 0, 3], [1, 0, 3, 2]])
    Xa = coords[Fa]
    best = np.full(len(Fa), -1)
    for p in range(len(perms)):
        d = np.abs(coords[Fb[:, perms[p]]] - Xa).max(axis=(1, 2))
        best = np.where((best < 0) & (d < TOL), p, best)
    if np.any(best < 0):
        raise RuntimeError("contact sides do not match node to node")
    Fb = np.take_along_axis(Fb, perms[best], axis=1)
    return Fa, Fb


def scaled_jacobian(coords, H, chunk=200000):
    """Minimum over the 8 corners of the normalised edge triple product, per hex."""
    out = np.empty(len(H))
    for a in range(0, len(H), chunk):
        X = coords[H[a:a + chunk]]
        sj = np.full(len(X), np.inf)
        for c, i, j, k in HEX_CORNERS:
            e1, e2, e3 = X[:, i] - X[:, c], X[:, j] - X[:, c], X[:, k] - X[:, c]
            det = np.einsum("ij,ij->i", np.cross(e1, e2), e3)
            nrm = (np.linalg.norm(e1, axis=1) * np.linalg.norm(e2, axis=1)
                   * np.linalg.norm(e3, axis=1))
            sj = np.minimum(sj, det / nrm)
        out[a:a + chunk] = sj
    return out


def hex_volumes(coords, H, chunk=100000):
    """Exact volumes of trilinear hexes (2x2x2 Gauss integration of det J)."""
    ref = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                    [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], float)
    g = 1.0 / math.sqrt(3.0)
    gp = ref * g
    # dN[q, a, d]: derivative of shape function a w.r.t. reference coord d at gp q
    dN = np.empty((8, 8, 3))
    for q in range(8):
        for a in range(8):
            f = 1.0 + ref[a] * gp[q]
            dN[q, a] = 0.125 * ref[a] * np.array([f[1] * f[2], f[0] * f[2], f[0] * f[1]])
    out = np.empty(len(H))
    for s in range(0, len(H), chunk):
        X = coords[H[s:s + chunk]]
        vol = np.zeros(len(X))
        for q in range(8):
            J = np.einsum("ead,ai->eid", X, dN[q])      # J[e, i, d] = dx_i/dxi_d
            vol += np.linalg.det(J)
        out[s:s + chunk] = vol
    return out


def extruded_volumes(coords, H):
    """Volumes as shoelace area of the bottom quad x height (planar extrusions)."""
    X = coords[H]
    x, y = X[:, :4, 0], X[:, :4, 1]
    area = 0.5 * np.sum(x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y, axis=1)
    return area * (X[:, 4, 2] - X[:, 0, 2])


# ---------------------------------------------------------------------------
# kind = joint
# ---------------------------------------------------------------------------
def build_joint(level=1.0, n_theta=None):
    G = JOINT
    c = level_counts(level, n_theta)
    N = c["n_theta"]
    ctr = (G["bolt_x"], G["bolt_y"])
    th = 2.0 * np.pi * np.arange(N) / N
    cs = (np.cos(th), np.sin(th))

    # common ring radii: 5 | 5.25 | 5.5 | 8.5 | 10 mm with g, g, m1, m2 divisions
    segs = [(G["r_shank"], G["r_washer_in"], c["g"]), (G["r_washer_in"], G["r_hole"], c["g"]),
            (G["r_hole"], G["r_head"], c["m1"]), (G["r_head"], G["r_washer_out"], c["m2"])]
    rr = [np.array([G["r_shank"]])] + [np.linspace(a, b, n + 1)[1:] for a, b, n in segs]
    rr = np.concatenate(rr)
    i5 = 0
    i525 = i5 + c["g"]
    i55 = i525 + c["g"]
    i85 = i55 + c["m1"]
    i10 = i85 + c["m2"]
    rings = [circle(ctr, r, cs) for r in rr]

    # z levels
    tp = G["plate_t"]
    z_p1 = np.linspace(0.0, tp, c["nzp"] + 1)
    z_p2 = np.linspace(tp, 2 * tp, c["nzp"] + 1)
    z_wh = np.linspace(*G["washer_head_z"], c["nzw"] + 1)
    z_wn = np.linspace(*G["washer_nut_z"], c["nzw"] + 1)
    z_nut = np.linspace(*G["nut_z"], c["nzn"] + 1)
    z_mid = np.linspace(G["nut_z"][1], G["head_z"][0], c["n_mid"] + 1)
    z_head = np.linspace(*G["head_z"], c["nzh"] + 1)
    z_bolt = np.concatenate([z_nut, z_mid[1:], z_head[1:]])
    h = (G["head_z"][0] - G["nut_z"][1]) / c["n_mid"]
    iz = (c["n_mid"] - 1) // 2
    z_pre = (z_mid[iz], z_mid[iz + 1])

    mesh = HexMesh("joint", level)

    # plates: rings 5.5 -> 10 mm, O-grid to the overlap square, boxes
    S = G["plate_width"] / 2
    sq, uS = square(ctr, S, N)
    ov = band(rings[i55:i10 + 1]
              + [blend(rings[i10], sq, t) for t in np.arange(1, c["m3"] + 1) / c["m3"]])
    ys = ctr[1] + uS
    x_lo, x_hi = ctr[0] - S, ctr[0] + S
    nx1 = nx2 = c["nx"]
    box1 = grid(np.linspace(G["plate1_x"][0], x_lo, nx1 + 1), ys)
    box2 = grid(np.linspace(x_hi, G["plate2_x"][1], nx2 + 1), ys)
    mesh.add_merge_group([("plate1",) + extrude(ov, z_p1), ("plate1",) + extrude(box1, z_p1)])
    mesh.add_merge_group([("plate2",) + extrude(ov, z_p2), ("plate2",) + extrude(box2, z_p2)])

    # bolt (core square + O-grid to r = 5, head rings to 8.5) and nut, merged
    s = G["core_frac"] * G["r_shank"]
    sqc, uc = square(ctr, s, N)
    core = grid(ctr[0] + uc, ctr[1] + uc)
    shank = band([blend(sqc, rings[i5], t) for t in np.arange(c["k"] + 1) / c["k"]])
    outer = band(rings[i5:i85 + 1])
    mesh.add_merge_group([("bolt",) + extrude(core, z_bolt),
                          ("bolt",) + extrude(shank, z_bolt),
                          ("bolt",) + extrude(outer, z_head),
                          ("nut",) + extrude(outer, z_nut)])
    # washers: rings 5.25 -> 10 mm
    wb = band(rings[i525:i10 + 1])
    mesh.add_merge_group([("washer_head",) + extrude(wb, z_wh)])
    mesh.add_merge_group([("washer_nut",) + extrude(wb, z_wn)])
    # part order of the contract
    mesh.parts = {p: mesh.parts[p] for p in JOINT_PARTS}
    mesh.finish()

    # surfaces
    def rad(x, y):
        return np.hypot(x - ctr[0], y - ctr[1])

    def at_z(z0, rmin=-1.0, rmax=1.0):
        return lambda x, y, z: ((np.abs(z - z0) < TOL) & (rad(x, y) > rmin - TOL)
                                & (rad(x, y) < rmax + TOL))

    r525, r55, r85, r10 = G["r_washer_in"], G["r_hole"], G["r_head"], G["r_washer_out"]
    zc = {"head_washer": G["head_z"][0], "washer_plate2": 2 * tp, "plate2_plate1": tp,
          "plate1_washer": 0.0, "washer_nut": G["nut_z"][1]}
    sides = {
        "head_washer": (("bolt", at_z(zc["head_washer"], r525, r85)),
                        ("washer_head", at_z(zc["head_washer"], r525, r85))),
        "washer_plate2": (("washer_head", at_z(zc["washer_plate2"], r55, r10)),
                          ("plate2", at_z(zc["washer_plate2"], r55, r10))),
        "plate2_plate1": (("plate2", lambda x, y, z: (np.abs(z - tp) < TOL) & (x < x_hi + TOL)),
                          ("plate1", lambda x, y, z: (np.abs(z - tp) < TOL) & (x > x_lo - TOL))),
        "plate1_washer": (("plate1", at_z(0.0, r55, r10)),
                          ("washer_nut", at_z(0.0, r55, r10))),
        "washer_nut": (("washer_nut", at_z(zc["washer_nut"], r525, r85)),
                       ("nut", at_z(zc["washer_nut"], r525, r85))),
    }
    for pair in JOINT_PAIRS:
        (pa, preda), (pb, predb) = sides[pair]
        Fa = faces(mesh, pa, preda, which=[0])      # bottom faces of the upper body
        Fb = faces(mesh, pb, predb, which=[1])      # top faces of the lower body
        Fa, Fb = match_pair(mesh.coords, Fa, Fb)
        mesh.surfaces["contact_%s_a" % pair] = Fa
        mesh.surfaces["contact_%s_b" % pair] = Fb
        mesh.pairs.append(pair)
    mesh.surfaces["clamp"] = faces(mesh, "plate1", lambda x, y, z: np.abs(x) < TOL)
    for name, z0 in zip(("preload_lower", "preload_upper"), z_pre):
        H = mesh.parts["bolt"]
        F = H[:, :4]                                 # bottom faces, normal +z
        mesh.surfaces[name] = F[np.all(np.abs(mesh.coords[F][..., 2] - z0) < TOL, axis=1)]
    xe, ze = G["plate2_x"][1], 2 * tp
    mesh.points["load_point"] = find_node(mesh, "plate2", (xe, ctr[1], ze))
    mesh.points["corner_point"] = find_node(mesh, "plate2", (xe, ctr[1] + S, ze))
    mesh.info = dict(divisions=c, preload_h=h, preload_z=list(z_pre),
                     ring_radii=rr.tolist(), core_half_side=s)
    return mesh


def build_joint2(level=1.0, n_theta=None):
    """Two bolts in one lap joint: the reference joint and a copy of it beside it (+y, one plate
    width over), the plates joined along their seam into plates twice as wide. Each bolt keeps
    its own head, washers, nut and preload layers (preload_1_*, preload_2_*); the contact pairs
    span both bolts; the clamp is the whole plate1 end; the load and corner points are the first
    joint's, the load point of the second is load_point_2."""
    one = build_joint(level, n_theta)
    pitch = JOINT["plate_width"]
    n0 = len(one.coords)
    X2 = one.coords + np.array([0.0, pitch, 0.0])
    new = np.arange(n0, 2 * n0)  # copy node i -> n0 + i, unless it joins a plate node
    for part in ("plate1", "plate2"):
        nodes = np.unique(one.parts[part])
        key = {tuple(k): i for k, i in zip(np.round(one.coords[nodes] / QUANTUM).astype(np.int64), nodes)}
        for i, k in zip(nodes, np.round(X2[nodes] / QUANTUM).astype(np.int64)):
            j = key.get(tuple(k))
            if j is not None:
                new[i] = j
    keep = new >= n0
    remap = np.full(2 * n0, -1, dtype=np.int64)
    remap[:n0] = np.arange(n0)
    remap[n0:][keep] = n0 + np.arange(keep.sum())
    remap[n0:][~keep] = new[~keep]
    mesh = HexMesh("joint2", level)
    mesh.coords = np.concatenate([one.coords, X2[keep]])
    second = lambda E: remap[n0 + E]  # noqa: E731
    for name, H in one.parts.items():
        mesh.parts[name] = np.concatenate([H, second(H)])
    for name, F in one.surfaces.items():
        if name.startswith("preload_"):
            mesh.surfaces[name.replace("preload_", "preload_1_")] = F
            mesh.surfaces[name.replace("preload_", "preload_2_")] = second(F)
        else:
            mesh.surfaces[name] = np.concatenate([F, second(F)])
    mesh.pairs = list(one.pairs)
    mesh.points = dict(one.points)
    mesh.points["load_point_2"] = int(second(np.array([one.points["load_point"]]))[0])
    mesh.info = dict(one.info, bolts=2, bolt_y=[JOINT["bolt_y"], JOINT["bolt_y"] + pitch],
                     seam_nodes=int((~keep).sum()))
    mesh.finish()
    return mesh


def find_node(mesh, part, xyz):
    nodes = np.unique(mesh.parts[part])
    d = np.abs(mesh.coords[nodes] - np.asarray(xyz)).max(axis=1)
    i = np.argmin(d)
    if d[i] > TOL:
        raise RuntimeError("no node of %s at %s" % (part, xyz))
    return int(nodes[i])


# ---------------------------------------------------------------------------
# kind = beam, block, blocks
# ---------------------------------------------------------------------------
BEAM = dict(length=0.300, width=0.040, t=0.008, elements=(60, 8, 2))


def beam_elements(level):
    nx, ny, nz = BEAM["elements"]
    return (max(1, _round_half_up(nx * level)), 2 * max(1, _round_half_up(ny / 2 * level)),
            max(1, _round_half_up(nz * level)))


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
    n = max(1, _round_half_up(2 * level)) if n is None else int(n)
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
    nx, ny, nzl, nzp = (max(1, _round_half_up(n * level)) for n in PUNCH["elements"])
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


def build(kind="joint", level=1.0, **kw):
    builders = dict(joint=build_joint, joint2=build_joint2, beam=build_beam, block=build_block,
                    blocks=build_blocks, punch=build_punch)
    if kind not in builders:
        raise ValueError("unknown kind %r" % kind)
    return builders[kind](level=level, **{k: v for k, v in kw.items() if v is not None})


# ---------------------------------------------------------------------------
# Report and output
# ---------------------------------------------------------------------------
def report(mesh):
    """Facts about the mesh (the JSON written by --json)."""
    nodes = len(mesh.coords)
    per_pair = {}
    contact_nodes = []
    for pair in mesh.pairs:
        a = np.unique(mesh.surfaces["contact_%s_a" % pair])
        b = np.unique(mesh.surfaces["contact_%s_b" % pair])
        per_pair[pair] = 3 * (len(a) + len(b))
        contact_nodes += [a, b]
    n_contact = len(np.unique(np.concatenate(contact_nodes))) if contact_nodes else 0
    sj = {p: float(scaled_jacobian(mesh.coords, H).min()) for p, H in mesh.parts.items()}
    rep = dict(
        kind=mesh.kind, level=mesh.level, nodes=nodes, dofs=3 * nodes,
        contact_dofs=3 * n_contact, contact_dofs_per_pair=per_pair,
        elements_per_part={p: int(len(H)) for p, H in mesh.parts.items()},
        volume_per_part={p: float(hex_volumes(mesh.coords, H).sum())
                         for p, H in mesh.parts.items()},
        min_scaled_jacobian=min(sj.values()),
        min_scaled_jacobian_per_part=sj,
        faces_per_surface={s: int(len(F)) for s, F in mesh.surfaces.items()},
        points={p: mesh.coords[i].tolist() for p, i in mesh.points.items()},
    )
    rep.update(mesh.info)
    return rep


def format_report(rep):
    lines = ["boltrom mesh: kind=%s level=%g" % (rep["kind"], rep["level"]),
             "  nodes %d, DOFs %d, contact DOFs %d" % (rep["nodes"], rep["dofs"],
                                                       rep["contact_dofs"])]
    for p, n in rep["elements_per_part"].items():
        lines.append("  part %-12s %8d hexes  volume %.6e m^3  min scaled Jacobian %.3f"
                     % (p, n, rep["volume_per_part"][p], rep["min_scaled_jacobian_per_part"][p]))
    for pair, n in rep["contact_dofs_per_pair"].items():
        lines.append("  pair %-14s %6d contact nodes (both sides)" % (pair, n // 3))
    lines.append("  min scaled Jacobian %.4f" % rep["min_scaled_jacobian"])
    if "divisions" in rep:
        lines.append("  divisions " + " ".join("%s=%d" % kv for kv in rep["divisions"].items()))
    return "\n".join(lines)


def _tmp_name(path, suffix):
    d, base = os.path.split(os.path.abspath(path))
    return os.path.join(d, ".%s.%d.tmp%s" % (base, os.getpid(), suffix))


def write_msh(mesh, path, ascii=False, verbose=False):
    """Write the mesh with the gmsh API as MSH 4.1 (atomically: temp + rename)."""
    import gmsh
    tmp = _tmp_name(path, ".msh")
    gmsh.initialize([], False)
    try:
        gmsh.option.setNumber("General.Terminal", 1 if verbose else 0)
        gmsh.model.add("boltrom_" + mesh.kind)
        tags = np.arange(1, len(mesh.coords) + 1, dtype=np.uint64)
        etag = 1
        # all nodes on one volume entity without physical group, so that PETSc's
        # -dm_plex_gmsh_mark_vertices marks only the dim-0 groups
        gmsh.model.addDiscreteEntity(3, NODE_ENTITY)
        gmsh.model.mesh.addNodes(3, NODE_ENTITY, tags, mesh.coords.reshape(-1))
        for i, (name, H) in enumerate(mesh.parts.items()):
            ent = i + 1
            gmsh.model.addDiscreteEntity(3, ent)
            gmsh.model.mesh.addElementsByType(
                ent, GMSH_HEX, np.arange(etag, etag + len(H), dtype=np.uint64),
                tags[H.reshape(-1)])
            etag += len(H)
            gmsh.model.addPhysicalGroup(3, [ent], ent)
            gmsh.model.setPhysicalName(3, ent, name)
        for i, (name, F) in enumerate(mesh.surfaces.items()):
            ent = 101 + i
            gmsh.model.addDiscreteEntity(2, ent)
            gmsh.model.mesh.addElementsByType(
                ent, GMSH_QUAD, np.arange(etag, etag + len(F), dtype=np.uint64),
                tags[F.reshape(-1)])
            etag += len(F)
            gmsh.model.addPhysicalGroup(2, [ent], ent)
            gmsh.model.setPhysicalName(2, ent, name)
        for i, (name, n) in enumerate(mesh.points.items()):
            ent = 201 + i
            gmsh.model.addDiscreteEntity(0, ent)
            gmsh.model.mesh.addElementsByType(ent, GMSH_POINT, [etag], [int(tags[n])])
            etag += 1
            gmsh.model.addPhysicalGroup(0, [ent], ent)
            gmsh.model.setPhysicalName(0, ent, name)
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.Binary", 0 if ascii else 1)
        # SaveAll = 1: gmsh 4.8 writes a wrong node count in the $Nodes header
        # with SaveAll = 0 when nodes sit on an entity without physical group
        gmsh.option.setNumber("Mesh.SaveAll", 1)
        gmsh.write(tmp)
        os.replace(tmp, path)
    finally:
        gmsh.finalize()
        if os.path.exists(tmp):
            os.remove(tmp)


def write_json(rep, path):
    tmp = _tmp_name(path, ".json")
    with open(tmp, "w") as f:
        json.dump(rep, f, indent=1)
        f.write("\n")
    os.replace(tmp, path)


def read_msh(path):
    """Read a .msh back with gmsh: coords {tag: xyz} as arrays and groups.

    Returns dict(tags (n,), coords (n,3), groups {(dim, name): (elem_type,
    node tags (E, nnodes))}).
    """
    import gmsh
    gmsh.initialize([], False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(path)
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        groups = {}
        for dim, ptag in gmsh.model.getPhysicalGroups():
            name = gmsh.model.getPhysicalName(dim, ptag)
            types, conn = [], []
            for ent in gmsh.model.getEntitiesForPhysicalGroup(dim, ptag):
                ets, _, ens = gmsh.model.mesh.getElements(dim, ent)
                for et, en in zip(ets, ens):
                    nn = gmsh.model.mesh.getElementProperties(et)[3]
                    types.append(int(et))
                    conn.append(np.asarray(en, dtype=np.int64).reshape(-1, nn))
            groups[(dim, name)] = (sorted(set(types)), np.concatenate(conn), ptag)
        return dict(tags=np.asarray(tags, dtype=np.int64),
                    coords=np.asarray(xyz).reshape(-1, 3), groups=groups)
    finally:
        gmsh.finalize()


# ---------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------
def main(argv=None):
    import argparse
    ap = argparse.ArgumentParser(
        prog="mesh-joint",
        description="All-hex meshes for boltrom (gmsh MSH 4.1). See python/boltrom_mesh.py "
                    "for the physical-group contract.")
    ap.add_argument("--kind", choices=("joint", "joint2", "beam", "block", "blocks", "punch"), default="joint")
    ap.add_argument("--level", type=float, default=1.0,
                    help="refinement level (float; node layers scale by about LEVEL)")
    ap.add_argument("--output", "-o", required=True, help="output .msh file")
    ap.add_argument("--json", help="also write the report as JSON to this file")
    ap.add_argument("--ascii", action="store_true", help="text MSH instead of binary")
    ap.add_argument("--quiet", "-q", action="store_true", help="no report on stdout")
    ap.add_argument("--n-theta", type=int, help="joint: angular divisions (multiple of 8)")
    ap.add_argument("--beam-length", type=float, help="beam: length L (m), default 0.300")
    ap.add_argument("--beam-elements", type=int, nargs=3, metavar=("NX", "NY", "NZ"),
                    help="beam: element counts (NY even); default 60 8 2 scaled by level")
    ap.add_argument("--block-elements", type=int,
                    help="blocks: elements per edge of each block (default round(2 level))")
    ap.add_argument("--seed", type=int, help="block: random seed of the perturbation")
    ap.add_argument("--punch-eccentricity", type=float,
                    help="punch: x of the load strip's centre (m), on a node or half-way "
                         "between two; default 0.0125")
    ap.add_argument("--punch-layer", type=float, help="punch: layer thickness (m), default 0.001")
    a = ap.parse_args(argv)
    if a.level <= 0:
        ap.error("--level must be positive")
    if not a.output.endswith(".msh"):
        ap.error("--output must end with .msh")
    t0 = time.time()
    kw = {}
    if a.kind == "joint":
        kw = dict(n_theta=a.n_theta)
    elif a.kind == "beam":
        kw = dict(length=a.beam_length, elements=a.beam_elements)
    elif a.kind == "block":
        kw = dict(seed=a.seed)
    elif a.kind == "blocks":
        kw = dict(n=a.block_elements)
    elif a.kind == "punch":
        kw = dict(eccentricity=a.punch_eccentricity, layer_t=a.punch_layer)
    try:
        mesh = build(a.kind, a.level, **kw)
    except ValueError as e:
        ap.error(str(e))
    rep = report(mesh)
    t1 = time.time()
    write_msh(mesh, a.output, ascii=a.ascii)
    t2 = time.time()
    rep["output"] = a.output
    rep["seconds"] = dict(build=round(t1 - t0, 3), write=round(t2 - t1, 3))
    if not a.quiet:
        print(format_report(rep))
        print("  wrote %s in %.2f s (build %.2f s, write %.2f s)"
              % (a.output, t2 - t0, t1 - t0, t2 - t1))
    if a.json:
        write_json(rep, a.json)
    return 0


if __name__ == "__main__":
    sys.exit(main())
