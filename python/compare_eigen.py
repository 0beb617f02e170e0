#!/usr/bin/python3
"""First eigenfrequencies of the tied joint, full model against ROM, from the matrices that
`boltrom -export_matrices DIR` writes (PETSc binary): the full pair (K_tied, M) by SLEPc
(shift-and-invert about 0, MUMPS), the reduced pair (rom_K_tied, rom_M) densely with LAPACK.
Prints a markdown table and writes it to DIR/eigen.md. Runs serial or under mpiexec."""
import argparse
import functools
import sys
from pathlib import Path

import numpy as np


@functools.lru_cache(maxsize=None)
def petsc():
    """petsc4py and slepc4py, initialised once without this script's command line (imported only
    to compute, so that --help needs neither)."""
    import slepc4py
    slepc4py.init(sys.argv[:1])
    from petsc4py import PETSc
    from slepc4py import SLEPc
    return PETSc, SLEPc


def load(path, comm, dense=False):
    PETSc, _ = petsc()
    viewer = PETSc.Viewer().createBinary(str(path), "r", comm=comm)
    A = PETSc.Mat().create(comm)
    if dense:
        A.setType(PETSc.Mat.Type.SEQDENSE)
    A.load(viewer)
    viewer.destroy()
    return A


def full_frequencies(d, nev):
    PETSc, SLEPc = petsc()
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
    import scipy.linalg
    PETSc, _ = petsc()
    K, M = load(d / "rom_K_tied.petsc", PETSc.COMM_SELF, True), load(d / "rom_M.petsc", PETSc.COMM_SELF, True)
    Kd, Md = K.getDenseArray().copy(), M.getDenseArray().copy()
    Kd, Md = 0.5 * (Kd + Kd.T), 0.5 * (Md + Md.T)  # symmetric up to rounding of the projection
    lam = scipy.linalg.eigh(Kd, Md, eigvals_only=True)
    return np.sqrt(np.maximum(lam[:nev], 0)) / (2 * np.pi)


def main(d, nev=10):
    PETSc, _ = petsc()
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


def parse_args(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("dir", metavar="DIR", help="the folder of boltrom -export_matrices DIR (run with -rom)")
    parser.add_argument("nev", metavar="NEV", nargs="?", type=int, default=10, help="how many frequencies (default: %(default)s)")
    return parser.parse_args(argv)


if __name__ == "__main__":
    args = parse_args()
    main(args.dir, args.nev)
