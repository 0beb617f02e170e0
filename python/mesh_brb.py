"""The Brake-Reuss beam (kind brb): two half-beams of square section lapped over 120 mm and held
by three bolts, tested free-free; the jointed-structures community's benchmark.

Geometry (metres), from the public descriptions of the BRB: section 25.4 x 25.4 mm; each half-beam
420 mm long, 12.7 mm thick over its 120 mm lap; assembled length 720 mm; 5/16-inch bolts
(shank 7.94 mm) through 8.5 mm holes at -30, 0 and +30 mm from the lap's centre, washers of
17.5 mm outer diameter and 1.65 mm thickness, hexagonal heads and nuts (12.7 mm across flats)
taken as cylinders of the same area, 5.16 and 6.75 mm high.

Axes: x along the beam, the lap's centre at x = 0; y across (the section is |y| <= 12.7 mm); z up,
0 <= z <= 25.4 mm. beam1 (x from -360 to 60 mm) is the lower half in the lap (z <= 12.7 mm),
beam2 (x from -60 to 360 mm) the upper half; heads and head washers on top (z = 25.4 mm), nuts
below (z = 0). The lap's ends face the other beam's step across a zero gap but carry no contact.

Groups (the joint's, per bolt where a bolt has its own):
  volumes  beam1, beam2, bolt, washer_head, washer_nut, nut (bolt, washers and nut hold all
           three bolts; each nut is tied to its shank as in the joint)
  pairs    head_washer, washer_beam2, beam2_beam1 (the lap), beam1_washer, washer_nut
  preload  preload_B_lower / preload_B_upper, B = 1, 2, 3 from -x to +x: one shank element layer
           half-way between the washers, as the joint's
  ends     the two end faces (x = -360 and 360 mm): a load spread on them by area bends the beam
           in its symmetric modes (with the rigid motion that balances it)
  points   load_point (beam2's end: x = 360 mm, y = 0, z = 25.4 mm), end_point (beam1's end at
           x = -360 mm, same y and z)
No clamp: the beam is free-free (-clamp false).

Level: the joint's division counts (mesh_joint.level_counts) for the bolt, washers and lap
thicknesses; the lap between and beyond the bolts and the full-section beams get divisions of
about the lap's element size, the latter stretched 3:1 along x (bending of a slender beam).
"""

import numpy as np

from mesh_blocks import (TOL, HexMesh, band, blend, circle, extrude, faces, find_node, grid,
                         match_pair, scale_count, square)
from mesh_joint import level_counts

BRB = dict(
    bolt_x=(-0.030, 0.0, 0.030), width=0.0254, t=0.0127,
    lap=(-0.060, 0.060), beam1_x=(-0.360, 0.060), beam2_x=(-0.060, 0.360),
    r_shank=0.0039688, r_washer_in=0.0041, r_hole=0.00425, r_head=0.0067, r_washer_out=0.00875,
    washer_t=0.00165, head_h=0.00516, nut_h=0.00675,
    core_frac=0.55,
)
BRB_PARTS = ("beam1", "beam2", "bolt", "washer_head", "washer_nut", "nut")
BRB_PAIRS = ("head_washer", "washer_beam2", "beam2_beam1", "beam1_washer", "washer_nut")
# divisions at level 1 beyond the joint's: the 4.6 mm between two bolts' squares, the 17.3 mm
# from the outer squares to the lap's ends, and the 300 mm of each full-section beam
BRB_BASE = dict(n_gap=1, n_end=3, n_beam=24)


def brb_counts(level, n_theta=None):
    c = level_counts(level, n_theta)
    c.update({k: scale_count(v, level) for k, v in BRB_BASE.items()})
    return c


def _ring_radii(G, c):
    """The radii shared by bolt, washers and lap: shank | washer bore | hole | head | washer."""
    segs = [(G["r_shank"], G["r_washer_in"], c["g"]), (G["r_washer_in"], G["r_hole"], c["g"]),
            (G["r_hole"], G["r_head"], c["m1"]), (G["r_head"], G["r_washer_out"], c["m2"])]
    rr = np.concatenate([[G["r_shank"]]] + [np.linspace(a, b, n + 1)[1:] for a, b, n in segs])
    i = np.cumsum([0, c["g"], c["g"], c["m1"], c["m2"]])
    return rr, dict(zip(("i5", "i525", "i55", "i85", "i10"), i))


def _z_levels(G, c):
    t, tw = G["t"], G["washer_t"]
    z = dict(p1=np.linspace(0.0, t, c["nzp"] + 1), p2=np.linspace(t, 2 * t, c["nzp"] + 1),
             wh=np.linspace(2 * t, 2 * t + tw, c["nzw"] + 1), wn=np.linspace(-tw, 0.0, c["nzw"] + 1),
             nut=np.linspace(-tw - G["nut_h"], -tw, c["nzn"] + 1),
             mid=np.linspace(-tw, 2 * t + tw, c["n_mid"] + 1),
             head=np.linspace(2 * t + tw, 2 * t + tw + G["head_h"], c["nzh"] + 1))
    z["full"] = np.concatenate([z["p1"], z["p2"][1:]])
    z["bolt"] = np.concatenate([z["nut"], z["mid"][1:], z["head"][1:]])
    iz = (c["n_mid"] - 1) // 2
    z["pre"] = (z["mid"][iz], z["mid"][iz + 1])
    return z


def _plate_blocks(G, c, z_lap, z_full, ctrs, rings, ri, x_ends, name):
    """One half-beam's lap (an O-grid around each bolt, boxes between and beyond) and its
    full-section part, as blocks to merge."""
    N, S = c["n_theta"], G["width"] / 2
    blocks, xs_cut = [], [G["lap"][0]]
    for ctr, rg in zip(ctrs, rings):
        sq, uS = square(ctr, S, N)
        ov = band(rg[ri["i55"]:ri["i10"] + 1]
                  + [blend(rg[ri["i10"]], sq, tt) for tt in np.arange(1, c["m3"] + 1) / c["m3"]])
        blocks.append((name,) + extrude(ov, z_lap))
        xs_cut += [ctr[0] - S, ctr[0] + S]
    xs_cut.append(G["lap"][1])
    ys = uS
    for k in range(0, len(xs_cut), 2):
        n = c["n_end"] if k in (0, len(xs_cut) - 2) else c["n_gap"]
        blocks.append((name,) + extrude(grid(np.linspace(xs_cut[k], xs_cut[k + 1], n + 1), ys), z_lap))
    blocks.append((name,) + extrude(grid(np.linspace(x_ends[0], x_ends[1], c["n_beam"] + 1), ys),
                                    z_full))
    return blocks


def _merge(mesh, blocks):
    """Merge a group's blocks and append its parts to those of earlier groups. Coordinates are
    rounded to 1e-12 m first: the O-grids' squares and the boxes between them reach their shared
    nodes by different sums, which can differ in the last bit across a merge quantum."""
    parts = dict(mesh.parts)
    mesh.parts = {}
    mesh.add_merge_group([(name, np.round(X, 12), H) for name, X, H in blocks])
    for name, H in mesh.parts.items():
        parts[name] = np.concatenate([parts[name], H]) if name in parts else H
    mesh.parts = parts


def build_brb(level=1.0, n_theta=None):
    G = BRB
    c = brb_counts(level, n_theta)
    N = c["n_theta"]
    th = 2.0 * np.pi * np.arange(N) / N
    cs = (np.cos(th), np.sin(th))
    rr, ri = _ring_radii(G, c)
    z = _z_levels(G, c)
    ctrs = [(x, 0.0) for x in G["bolt_x"]]
    rings = [[circle(ctr, r, cs) for r in rr] for ctr in ctrs]
    mesh = HexMesh("brb", level)
    lap0, lap1 = G["lap"]
    _merge(mesh, _plate_blocks(G, c, z["p1"], z["full"], ctrs, rings, ri, (G["beam1_x"][0], lap0), "beam1"))
    _merge(mesh, _plate_blocks(G, c, z["p2"], z["full"], ctrs, rings, ri, (lap1, G["beam2_x"][1]), "beam2"))
    s = G["core_frac"] * G["r_shank"]
    for ctr, rg in zip(ctrs, rings):
        sqc, uc = square(ctr, s, N)
        core = grid(ctr[0] + uc, ctr[1] + uc)
        shank = band([blend(sqc, rg[ri["i5"]], tt) for tt in np.arange(c["k"] + 1) / c["k"]])
        outer = band(rg[ri["i5"]:ri["i85"] + 1])
        _merge(mesh, [("bolt",) + extrude(core, z["bolt"]), ("bolt",) + extrude(shank, z["bolt"]),
                              ("bolt",) + extrude(outer, z["head"]), ("nut",) + extrude(outer, z["nut"])])
        wb = band(rg[ri["i525"]:ri["i10"] + 1])
        _merge(mesh, [("washer_head",) + extrude(wb, z["wh"])])
        _merge(mesh, [("washer_nut",) + extrude(wb, z["wn"])])
    mesh.parts = {p: mesh.parts[p] for p in BRB_PARTS}
    mesh.finish()
    _add_pairs(mesh, G, z, ctrs)
    for b, ctr in enumerate(ctrs, start=1):
        F = mesh.parts["bolt"][:, :4]                      # bottom faces, normal +z
        X = mesh.coords[F]
        near = np.all(np.hypot(X[..., 0] - ctr[0], X[..., 1] - ctr[1]) < G["r_shank"] + TOL, axis=1)
        for side, z0 in zip(("lower", "upper"), z["pre"]):
            mesh.surfaces["preload_%d_%s" % (b, side)] = F[near & np.all(np.abs(X[..., 2] - z0) < TOL, axis=1)]
    xe = (G["beam1_x"][0], G["beam2_x"][1])
    mesh.surfaces["ends"] = np.concatenate([faces(mesh, "beam1", lambda x, y, zz: np.abs(x - xe[0]) < TOL),
                                            faces(mesh, "beam2", lambda x, y, zz: np.abs(x - xe[1]) < TOL)])
    mesh.points["load_point"] = find_node(mesh, "beam2", (G["beam2_x"][1], 0.0, 2 * G["t"]))
    mesh.points["end_point"] = find_node(mesh, "beam1", (G["beam1_x"][0], 0.0, 2 * G["t"]))
    mesh.info = dict(divisions=c, bolts=len(ctrs), bolt_x=list(G["bolt_x"]), preload_z=list(z["pre"]),
                     preload_h=float(z["pre"][1] - z["pre"][0]), ring_radii=rr.tolist())
    return mesh


def _add_pairs(mesh, G, z, ctrs):
    """The five pairs over all bolts, side a the upper body, faces matched node to node."""
    t, tw = G["t"], G["washer_t"]

    def rad(x, y):
        return np.min([np.hypot(x - cx, y - cy) for cx, cy in ctrs], axis=0)

    def ring(z0, rmin, rmax):
        return lambda x, y, zz: (np.abs(zz - z0) < TOL) & (rad(x, y) > rmin - TOL) & (rad(x, y) < rmax + TOL)

    def lap(z0):
        return lambda x, y, zz: (np.abs(zz - z0) < TOL) & (x > G["lap"][0] - TOL) & (x < G["lap"][1] + TOL)

    r525, r55, r85, r10 = G["r_washer_in"], G["r_hole"], G["r_head"], G["r_washer_out"]
    sides = {
        "head_washer": (("bolt", ring(2 * t + tw, r525, r85)), ("washer_head", ring(2 * t + tw, r525, r85))),
        "washer_beam2": (("washer_head", ring(2 * t, r55, r10)), ("beam2", ring(2 * t, r55, r10))),
        "beam2_beam1": (("beam2", lap(t)), ("beam1", lap(t))),
        "beam1_washer": (("beam1", ring(0.0, r55, r10)), ("washer_nut", ring(0.0, r55, r10))),
        "washer_nut": (("washer_nut", ring(-tw, r525, r85)), ("nut", ring(-tw, r525, r85))),
    }
    for pair in BRB_PAIRS:
        (pa, preda), (pb, predb) = sides[pair]
        Fa, Fb = match_pair(mesh.coords, faces(mesh, pa, preda, which=[0]), faces(mesh, pb, predb, which=[1]))
        mesh.surfaces["contact_%s_a" % pair] = Fa
        mesh.surfaces["contact_%s_b" % pair] = Fb
        mesh.pairs.append(pair)
