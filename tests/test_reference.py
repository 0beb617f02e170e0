"""The paper-step scene's FOM and ROM probe histories against stored ones
(tests/data/reference-L0.5.json, written by scripts/reference-histories --write): a change of
the code's shape must leave every history bit-identical on one rank. Eleven histories: four
cases under the paper's stick law (written from the code before its objects were reshaped), the
default strict law (strict-step: 50 steps, FOM and ROM) and Coulomb friction (coulomb-step,
mu 0.1: 30 steps, FOM and ROM, about 150 of 704 contact points sliding by the end). A history
is rewritten (--write --cases ...) only by a change meant to move its arithmetic, and the commit
that does it says by how much.

The bits hold for OpenBLAS's Haswell kernels (the script sets OPENBLAS_CORETYPE=Haswell), the
compiler and the MUMPS/PETSc/OpenBLAS builds they were made with (each new case stores them
under "made_with"; the first four were checked against the same on an AMD EPYC). On another
toolchain the histories move by rounding; how to tell and to rewrite them: docs/verification.md
section 7 and the script's help."""
import subprocess

from conftest import ENV, PYTHON, ROOT


def test_histories_match_the_stored_reference():
    proc = subprocess.run([PYTHON, str(ROOT / "scripts" / "reference-histories"), "--level", "0.5", "--rtol", "0"],
                          capture_output=True, text=True, env=ENV, timeout=900)
    lines = proc.stdout.splitlines()
    assert proc.returncode == 0, proc.stdout + proc.stderr
    # every stored history was compared and each one kept its bits
    assert sum("bit-identical" in l for l in lines) == 11, proc.stdout
    for case in ("strict-step", "coulomb-step"):
        assert sum(l.startswith(case) and "bit-identical" in l for l in lines) == 2, proc.stdout
