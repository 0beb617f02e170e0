"""The paper-step scene's FOM and ROM probe histories against stored ones
(tests/data/reference-L0.5.json, written by scripts/reference-histories --write from the code
before its objects were reshaped): a change of the code's shape must leave every history
bit-identical on one rank."""
import subprocess

from conftest import ENV, PYTHON, ROOT


def test_histories_match_the_stored_reference():
    proc = subprocess.run([PYTHON, str(ROOT / "scripts" / "reference-histories"), "--level", "0.5", "--rtol", "0"],
                          capture_output=True, text=True, env=ENV, timeout=900)
    lines = proc.stdout.splitlines()
    assert proc.returncode == 0, proc.stdout + proc.stderr
    # every stored history was compared and each one kept its bits
    assert sum("bit-identical" in l for l in lines) == 7, proc.stdout
