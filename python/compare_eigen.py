#!/usr/bin/python3
"""First eigenfrequencies of the tied joint, full model against ROM, from the matrices that
`boltrom -export_matrices DIR` writes (PETSc binary): the full pair (K_tied, M) by SLEPc
(shift-and-invert about 0, MUMPS), the reduced pair (rom_K_tied, rom_M) densely with LAPACK.
Prints a markdown table and writes it to DIR/eigen.md.
Usage: python/compare_eigen.py DIR [NEV]   (serial or under mpiexec)"""
import sys
from pathlib import Path

import numpy as np
import scipy.linalg
import slepc4py

slepc4py.init(sys.argv[:1])
from petsc4py import PETSc  # noqa: E402
from slepc4py import SLEPc  # noqa: E402


def load(path, comm, dense=False):
    viewer = PETSc.Viewer().createBinary(str(path), "r", comm=comm)
    A = PETSc.Mat().create(comm)
    if dense:
        A.setType(PETSc.Mat.Type.SEQDENSE)
    A.load(viewer)
    viewer.destroy()
    return A


def full_frequencies(d, nev):
    comm = PETSc.COMM_WORLD
    K, M = load(d / "K_tied.petsc", comm), load(d / "M.petsc", comm)
    eps = SLEPc.EPS().create(comm)
    eps.setOperators(K, M)
    eps.setProblemType(SLEPc.EPS.ProblemType.GHEP)
    eps.setDimensions(nev)
    eps.setTarget(0.0)
    eps.setWhichEigenpairs(SLEPc.EPS.Which.TARGET_MAGNITUDE)
    st = eps.getST()
    st.setType(SLEPc.ST.Type.SINVERT)
    ksp = st.getKSP()
    ksp.setType("preonly")
    ksp.getPC().setType("cholesky")
    ksp.getPC().setFactorSolverType("mumps")
    eps.setTolerances(1e-10)
    eps.solve()
    lam = sorted(eps.getEigenvalue(i).real for i in range(eps.getConverged()))
    return np.sqrt(np.maximum(lam[:nev], 0)) / (2 * np.pi)


def reduced_frequencies(d, nev):
    K, M = load(d / "rom_K_tied.petsc", PETSc.COMM_SELF, True), load(d / "rom_M.petsc", PETSc.COMM_SELF, True)
    Kd, Md = K.getDenseArray().copy(), M.getDenseArray().copy()
    Kd, Md = 0.5 * (Kd + Kd.T), 0.5 * (Md + Md.T)  # symmetric up to rounding of the projection
    lam = scipy.linalg.eigh(Kd, Md, eigvals_only=True)
    return np.sqrt(np.maximum(lam[:nev], 0)) / (2 * np.pi)


def main(d, nev=10):
    d, nev = Path(d), int(nev)
    f_full = full_frequencies(d, nev)
    f_rom = reduced_frequencies(d, nev)
    lines = ["| mode | FOM [Hz] | ROM [Hz] | difference |", "|---|---|---|---|"]
    for i, (a, b) in enumerate(zip(f_full, f_rom)):
        lines.append(f"| {i + 1} | {a:.3f} | {b:.3f} | {(b - a) / a:+.2e} |")
    text = "\n".join(lines) + "\n"
    if PETSc.COMM_WORLD.getRank() == 0:
        print(text, end="")
        (d / "eigen.md").write_text(text)


if __name__ == "__main__":
    main(*sys.argv[1:])
