"""Running boltrom from the scripts: the environment every run gets (mpiexec as root in the
sandbox and CI, one OpenBLAS thread per rank, so that two ranks use the two cores and no more),
and one call that echoes the command and stops the script with the run's last output if it fails."""
import os
import subprocess

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")

# The trained frictional ROM of docs/reduction.md ("ROMs trained on a FOM run"): a wider interface
# reduction, POD modes of the training run's snapshots (that run needs -fom true -snapshot_every 1)
# and the normal shapes of the pairs the preload leaves on the cone, compressed to the training
# run's leading patterns there. Its size does not grow with the mesh.
TRAINED_ROM = ["-rom_n_ccm", "300", "-rom_n_jim", "300", "-rom_snapshot_modes", "100", "-rom_cone_shapes", "0.999",
               "-rom_cone_traction", "false", "-rom_cone_modes", "150"]


class RunFailed(SystemExit):
    """A boltrom run that exited non-zero: it ends a script unless the script catches it."""


def call(cmd, cwd=None, tail=1500):
    """Runs cmd (a list; its items are turned into strings) and returns the finished process; a
    failure ends the script with the command and the last tail characters of both streams."""
    cmd = [str(c) for c in cmd]
    print("+", " ".join(cmd), flush=True)
    proc = subprocess.run(cmd, capture_output=True, text=True, env=ENV, cwd=cwd, stdin=subprocess.DEVNULL)
    if proc.returncode != 0:
        raise RunFailed(f"failed (exit {proc.returncode}): {' '.join(cmd)}\n{proc.stdout[-tail:]}\n{proc.stderr[-tail:]}")
    return proc
