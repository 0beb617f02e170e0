"""All-hexahedral meshes for boltrom, built with numpy and written with the gmsh API.

The hexahedra are made by the kinds' modules (mesh_joint.py, mesh_brb.py,
mesh_test_kinds.py) from the building blocks of mesh_blocks.py (structured
blocks and O-grids of planar quads extruded in z), then handed to gmsh as discrete entities and written as an
MSH 4.1 file (binary unless ``ascii=True``).  SI units: metres.

Kinds
-----
``joint``   the reference single-lap bolted joint (two plates, bolt, two
            washers, nut tied to the shank), five node-to-node contact pairs.
``joint2``  two of it side by side, plates merged (mesh_joint.py).
``brb``     the Brake-Reuss beam: two half-beams lapped, three bolts, free-free
            (its geometry and groups: mesh_brb.py).
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
import os
import sys
import time

import numpy as np

from mesh_blocks import (GMSH_HEX, GMSH_POINT, GMSH_QUAD, NODE_ENTITY,  # noqa: F401 (scripts and tests use them)
                         extruded_volumes, hex_volumes, scaled_jacobian)
from mesh_brb import build_brb
from mesh_joint import build_joint, build_joint2  # noqa: F401
from mesh_test_kinds import build_beam, build_block, build_blocks, build_punch  # noqa: F401


def build(kind="joint", level=1.0, **kw):
    builders = dict(joint=build_joint, joint2=build_joint2, brb=build_brb, beam=build_beam, block=build_block,
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
    ap.add_argument("--kind", choices=("joint", "joint2", "brb", "beam", "block", "blocks", "punch"), default="joint")
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
    if a.kind in ("joint", "joint2", "brb"):
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
