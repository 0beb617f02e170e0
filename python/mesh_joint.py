"""The bolted-joint kinds of boltrom_mesh: the reference single-lap joint (joint) and two of it
side by side (joint2). The contract and the level rule: boltrom_mesh.py."""

import numpy as np

from mesh_blocks import (QUANTUM, TOL, HexMesh, round_half_up, band, blend, circle, extrude, faces,
                         find_node, grid, match_pair, scale_count, square)

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


def level_counts(level, n_theta=None):
    """Division counts of the joint mesh at a (possibly fractional) level."""
    if level <= 0:
        raise ValueError("level must be positive")
    c = {key: scale_count(val, level) for key, val in JOINT_BASE.items()}
    c["n_theta"] = 8 * max(1, round_half_up(level * JOINT_BASE["n8"]))
    if n_theta is not None:
        if n_theta < 8 or n_theta % 8:
            raise ValueError("n_theta must be a positive multiple of 8")
        c["n_theta"] = int(n_theta)
    del c["n8"]
    c["nzp"] = max(2, c["nzp"])        # bending: at least 2 elements through a plate
    c["n_mid"] = 2 * c.pop("nmid") + 1
    return c




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
