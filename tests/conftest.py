"""Shared fixtures: the built binaries, meshes made once per test run, and a runner.

The mesh fixtures have package scope: tests/ has no __init__.py, so pytest keeps one instance
for the whole run (the meshes are made once, the first time a test asks for them)."""
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))
PYTHON = "/usr/bin/python3"
BOLTROM = ROOT / "bin" / "boltrom"

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OPENBLAS_NUM_THREADS="1", OMPI_MCA_rmaps_base_oversubscribe="1")


def run_boltrom(args, ranks=1, check=True, cwd=None, timeout=900):
    """Runs bin/boltrom on `ranks` MPI ranks; returns the CompletedProcess."""
    # one rank runs as an MPI singleton: no launcher, so stderr holds only boltrom's own lines
    launcher = ["mpiexec", "-n", str(ranks)] if ranks > 1 else []
    cmd = launcher + [str(BOLTROM)] + [str(a) for a in args]
    proc = subprocess.run(cmd, capture_output=True, text=True, env=ENV, cwd=cwd or ROOT, timeout=timeout)
    if check and proc.returncode != 0:
        raise AssertionError(f"{' '.join(cmd)} failed ({proc.returncode}):\n{proc.stdout}\n{proc.stderr}")
    return proc


def run_summary(args, tmp, ranks=1, name="summary"):
    """Runs boltrom with -summary and returns the parsed JSON."""
    path = Path(tmp) / f"{name}.json"
    run_boltrom(list(args) + ["-summary", path], ranks=ranks)
    return json.loads(path.read_text())


def load_petsc_matrix(path):
    """A matrix boltrom wrote with -export_matrices (PETSc binary), as a scipy CSR matrix."""
    import petsc4py
    petsc4py.init([])
    from petsc4py import PETSc
    import scipy.sparse as sp
    viewer = PETSc.Viewer().createBinary(str(path), "r", comm=PETSc.COMM_SELF)
    A = PETSc.Mat().create(PETSc.COMM_SELF)
    A.load(viewer)
    ai, aj, av = A.getValuesCSR()
    return sp.csr_matrix((av, aj, ai), shape=A.getSize())


def make_mesh(kind, path, level=1.0, extra=()):
    json_path = Path(str(path) + ".json")
    subprocess.run([PYTHON, str(ROOT / "scripts" / "mesh-joint"), "--kind", kind, "--level", str(level),
                    "--output", str(path), "--json", str(json_path)] + list(extra),
                   check=True, capture_output=True, text=True)
    return path, json.loads(json_path.read_text())


@pytest.fixture(scope="package")
def meshdir(tmp_path_factory):
    return tmp_path_factory.mktemp("meshes")


@pytest.fixture(scope="package")
def joint_small(meshdir):
    """A coarse joint (level 0.5): every feature of the reference joint, few DOFs."""
    return make_mesh("joint", meshdir / "joint-L0.5.msh", 0.5)


@pytest.fixture(scope="package")
def joint_paper(meshdir):
    """The paper-level joint (level 1)."""
    return make_mesh("joint", meshdir / "joint-L1.msh", 1)


@pytest.fixture(scope="package")
def block_mesh(meshdir):
    return make_mesh("block", meshdir / "block.msh", 1)


def assert_uniform_contact(pre, p, penetration_max, pair="upper_lower", points=16):
    """The contact patch test's facts: every point closed and carrying the traction p (to 1e-8),
    no tangential traction, penetration below penetration_max [m], the pair's force p x area."""
    assert pre["active_points"] == points
    assert abs(pre["traction_normal_min"] / -p - 1) < 1e-8
    assert abs(pre["traction_normal_max"] / -p - 1) < 1e-8
    assert pre["traction_tangential_max"] < 1e-8 * p
    assert pre["penetration_max"] < penetration_max
    force = -pre["normal_force_per_pair"][pair]
    assert abs(force / (p * 1e-4) - 1) < 1e-8
