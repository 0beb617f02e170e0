"""scripts/check-mesh: a mesh that follows the contract passes; each planted fault is named.

Run: /usr/bin/python3 -m pytest -q tests/test_check_mesh.py"""
import os
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
import boltrom_mesh as bm  # noqa: E402

PYTHON = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable


def run(path, *args):
    proc = subprocess.run([PYTHON, os.path.join(ROOT, "scripts", "check-mesh"), str(path), *args],
                          capture_output=True, text=True)
    return proc.returncode, proc.stdout


def problems(out):
    return [l.strip()[len("problem: "):] for l in out.splitlines() if l.strip().startswith("problem: ")]


@pytest.fixture(scope="module")
def joint():
    return bm.build_joint(0.5)


def test_the_reference_joint_passes(joint, tmp_path):
    path = tmp_path / "joint.msh"
    bm.write_msh(joint, str(path))
    rc, out = run(path)
    assert rc == 0 and problems(out) == [], out
    assert "6 parts" in out and "5 contact pairs" in out and "no problems found" in out, out


def test_each_planted_fault_is_named(joint, tmp_path):
    """One inverted hexahedron, one contact side removed, one side-b node moved off its partner, and
    one preload layer removed: four problems, each naming its group; without the clamp, a note."""
    m = bm.build_joint(0.5)
    m.parts["plate1"][7] = m.parts["plate1"][7][[4, 5, 6, 7, 0, 1, 2, 3]]  # mirrored: inside out
    del m.surfaces["contact_washer_nut_b"]
    moved = m.surfaces["contact_plate2_plate1_b"][0, 0]
    m.coords = m.coords.copy()
    m.coords[moved, 0] += 1e-4
    del m.surfaces["preload_upper"]
    del m.surfaces["clamp"]
    path = tmp_path / "faulty.msh"
    bm.write_msh(m, str(path))
    rc, out = run(path)
    found = problems(out)
    assert rc == 1, out
    assert len(found) == 4, out
    assert any(p.startswith("part plate1: 1 inverted or degenerate hexahedra") for p in found), out
    assert any("contact pair washer_nut has side contact_washer_nut_a but no contact_washer_nut_b" in p
               for p in found), out
    assert any(p.startswith("contact pair plate2_plate1: 1 of its") for p in found), out
    assert any("preload layer 'preload_upper' is missing" in p for p in found), out
    assert "the model is free-free; run it with -clamp false" in out, out


def test_non_hexahedral_part_and_unreadable_file(tmp_path):
    bad = tmp_path / "text.msh"
    bad.write_text("not a mesh\n")
    rc, out = run(bad)
    assert rc == 1 and "cannot read" in out, out
    rc, out = run(tmp_path / "absent.msh")
    assert rc == 2 and "no file" in out, out
    # a tetrahedral part
    import gmsh
    gmsh.initialize([], False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
        gmsh.model.occ.synchronize()
        gmsh.model.setPhysicalName(3, gmsh.model.addPhysicalGroup(3, [1]), "block")
        gmsh.model.mesh.generate(3)
        path = str(tmp_path / "tets.msh")
        gmsh.write(path)
    finally:
        gmsh.finalize()
    rc, out = run(path)
    assert rc == 1 and any(p.startswith("part block holds tetrahedra") for p in problems(out)), out


def test_two_bolt_joint_and_a_bolt_without_its_upper_layer(tmp_path):
    m = bm.build_joint2(0.5)
    path = tmp_path / "joint2.msh"
    bm.write_msh(m, str(path))
    rc, out = run(path)
    assert rc == 0 and "run with -preload_bolts 1,2" in out, out
    del m.surfaces["preload_2_upper"]
    bm.write_msh(m, str(path))
    rc, out = run(path)
    assert rc == 1 and problems(out) == ["preload layer 'preload_2_upper' is missing (its partner 'preload_2_lower' is there): add it"], out
