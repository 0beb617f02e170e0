"""Building blocks of boltrom's hexahedral meshes: structured patches extruded in z, node merging,
faces of a part, node-to-node matching of a contact pair's sides, element quality."""

import math

import numpy as np

HEX_FACES = np.array([[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4],
                      [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]])
# corner c, then its three neighbours in right-handed order
HEX_CORNERS = np.array([[0, 1, 3, 4], [1, 2, 0, 5], [2, 3, 1, 6], [3, 0, 2, 7],
                        [4, 7, 5, 0], [5, 4, 6, 1], [6, 5, 7, 2], [7, 6, 4, 3]])
GMSH_HEX, GMSH_QUAD, GMSH_POINT = 5, 3, 15
NODE_ENTITY = 1000  # discrete volume entity that carries all nodes (no physical group)
TOL = 1e-9          # geometric tolerance (m) for selecting nodes/faces
QUANTUM = 1e-9      # rounding quantum (m) for merging nodes


def round_half_up(x):
    return int(math.floor(x + 0.5))


def scale_count(n, level):
    """Division count at `level` for the count n at level 1.

    max(1, round(L n + (L - 1) / 2)): half-way between scaling the elements
    (L n) and the node layers (L (n + 1) - 1) by L, so that the DOF count of
    the joint grows like L^3 although many counts are small at level 1.
    """
    return max(1, round_half_up(level * n + 0.5 * (level - 1.0)))

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


def find_node(mesh, part, xyz):
    nodes = np.unique(mesh.parts[part])
    d = np.abs(mesh.coords[nodes] - np.asarray(xyz)).max(axis=1)
    i = np.argmin(d)
    if d[i] > TOL:
        raise RuntimeError("no node of %s at %s" % (part, xyz))
    return int(nodes[i])

