"""The errors of a ROM probe history against the FOM's, as boltrom's summary computes them
(docs/reduction.md, "Errors and speedup"): e_L2 = ||u - ref|| / ||ref|| over all steps, and the
mean pointwise relative error over the steps where |ref| exceeds 1 % of its maximum."""
import numpy as np


def errors(u, ref):
    """Returns (e_L2, e_mean) of history u against the reference history ref."""
    eL2 = np.linalg.norm(u - ref) / np.linalg.norm(ref)
    mask = np.abs(ref) > 0.01 * np.abs(ref).max()
    return eL2, np.mean(np.abs(u[mask] - ref[mask]) / np.abs(ref[mask]))
