"""Element kernels (hex8 full and incompatible, mass, quad penalty): tests/c/test_elements.c."""
import subprocess

from conftest import ENV, ROOT


def test_element_kernels():
    proc = subprocess.run([str(ROOT / "bin" / "test_elements")], capture_output=True, text=True, env=ENV, timeout=300)
    lines = [l for l in proc.stdout.splitlines() if l.startswith(("PASS", "FAIL"))]
    failed = [l for l in lines if l.startswith("FAIL")]
    assert proc.returncode == 0 and not failed, proc.stdout + proc.stderr
    names = {l.split()[1] for l in lines}
    # the checks the issue names must all be there
    for needed in ("patch_stress_full", "patch_stress_incompatible", "rigid_modes_Ke_full",
                   "rigid_modes_Ke_incompatible", "cantilever_tip_deflection_incompatible_relerr"):
        assert needed in names
