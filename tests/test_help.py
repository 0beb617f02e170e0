"""bin/boltrom -help as a user reads it: boltrom's own options first, grouped by object, each
help string short enough to read, with its default as a value; PETSc's and SLEPc's solver
options after them. And the source's shape (scripts/check-layout) as far as it is settled."""
import re
import subprocess

from conftest import PYTHON, ROOT, run_boltrom

# section titles PETSc and SLEPc print for their objects' options
FOREIGN = re.compile(r"^(Preconditioner|Krylov Method|Viewer|Eigenvalue|Basis Vectors|Region|Direct Solver|"
                     r"Spectral Transformation|Options for all PETSc|PetscDevice|Root PetscDeviceContext|"
                     r"Petsc Release|SLEPc Release|Matrix|Vector|Index set|MUMPS)")
OPTION = re.compile(r"^  (-\w+)[: ].*?(?:<(.*?)>)?:? ?(.*?)(?: \((?:None|BoltDual|[A-Za-z]+)\))?$")


def boltrom_block(lines):
    """The lines before the first section of PETSc's or SLEPc's own options."""
    for i, line in enumerate(lines):
        if FOREIGN.match(line):
            return lines[:i]
    return lines


def test_boltrom_options_come_first():
    lines = run_boltrom(["-help"]).stdout.splitlines()
    first = boltrom_block(lines)
    # the first 60 lines are boltrom's; its own sections, in the order a run configures them
    assert len(first) >= 60, first[-5:]
    titles = [l[:-1] for l in first if l.endswith(":") and not l.startswith(" ")]
    for t in ("Run", "Mesh and model", "Materials", "Contact", "Loads", "Reduction", "Time integration", "Contact loop"):
        assert t in titles, (t, titles)
    # and the solvers' options do come after them
    rest = lines[len(first):]
    assert any("-static_ksp_type" in l for l in rest) and any("-modal_eps_nev" in l for l in rest)
    assert not any("-static_ksp_type" in l for l in first)


def test_help_strings_are_short_and_show_their_default():
    first = boltrom_block(run_boltrom(["-help"]).stdout.splitlines())
    options = [l for l in first if l.startswith("  -")]
    assert len(options) > 80, len(options)
    too_long = []
    for line in options:
        # '  -name <now x : formerly y>: text (manual)' or '  -name: <x : y> text (manual)'
        text = re.sub(r"^  -\S+?:? ?<[^>]*>:? ?", "", line)
        text = re.sub(r" \([A-Za-z]*\)$", "", text)
        text = re.sub(r" \((?:choose )?one of\) .*$", "", text)  # the choices PETSc appends to a list option
        if len(text) > 160:
            too_long.append((len(text), line[:60]))
    assert not too_long, too_long
    # a vector option shows its whole default, not its first component
    direction = next(l for l in options if l.startswith("  -load_direction"))
    assert "0,0,-1" in direction.replace(" ", "").replace(".", ""), direction


def test_source_layout_sizes_and_layers():
    """Files <= 500 lines, functions <= 150, no call from a lower module to a higher one, no cycle
    between files, no struct body in a public header, no private header outside its module
    (scripts/check-layout)."""
    proc = subprocess.run([PYTHON, str(ROOT / "scripts" / "check-layout")], capture_output=True, text=True)
    breaches = [l for l in proc.stdout.splitlines() if not l.startswith("check-layout:")]
    assert not breaches, "\n".join(breaches)
    assert proc.returncode == 0 and "check-layout:" in proc.stdout


def test_source_layout_check_finds_planted_faults(tmp_path):
    """The layout check is not blind: a copy of the sources with a struct body in a public header,
    a private header read from another module, a call from the model up into the ROM and a
    function of 153 lines gives one breach for each."""
    import shutil
    for d in ("src", "include"):
        shutil.copytree(ROOT / d, tmp_path / d)
    (tmp_path / "include" / "boltrom" / "model.h").write_text(
        (ROOT / "include" / "boltrom" / "model.h").read_text().replace(
            "#endif", "typedef struct {\n  int planted;\n} BoltPlanted;\n#endif"))
    run = tmp_path / "src" / "app" / "run.c"
    run.write_text('#include "private/model.h"\n' + run.read_text())
    (tmp_path / "src" / "model" / "planted.c").write_text(
        "void BoltPlanted(void)\n{\n" + "  BoltROMSetUp(0);\n" * 150 + "}\n")
    proc = subprocess.run([PYTHON, str(ROOT / "scripts" / "check-layout"), "--root", str(tmp_path)],
                          capture_output=True, text=True)
    out = proc.stdout
    assert proc.returncode == 1, out
    assert "a struct body in the public header" in out, out
    assert "src/app/run.c includes private/model.h" in out, out
    assert "a lower module (model) calls a higher one (rom)" in out, out
    assert "BoltPlanted has 153 lines" in out, out
    assert out.strip().splitlines()[-1].endswith("4 breaches"), out


def test_log_lines_are_short_and_counts_are_integers(joint_small, tmp_path):
    """A run of both models with a ROM that has opening shapes and closed-contact Krylov vectors (the
    steps that used to print a value per shape) prints no line over 200 characters, and its
    iteration counts as integers."""
    mesh, _ = joint_small
    proc = run_boltrom(["-mesh", mesh, "-static", "false", "-modal_nev", "0", "-fom", "-rom",
                        "-load_force", "300", "-ts_dt", "1e-4", "-ts_end", "2e-3", "-output_dir", tmp_path], ranks=2)
    lines = proc.stdout.splitlines()
    assert any(l.startswith("ROM:") for l in lines) and any("outer" in l for l in lines)
    long = [(len(l), l[:80]) for l in lines if len(l) > 200]
    assert not long, long
    assert not re.search(r"\d\. (outer|inner)", proc.stdout), re.findall(r".{40}\d\. (?:outer|inner).{20}", proc.stdout)
