"""Reference values for the cantilever verification: Timoshenko beam theory.

A cantilever of length L, rectangular section b x h, clamped at x = 0, loaded at the tip.
"""
import numpy as np
import scipy.linalg


def shear_coefficient(nu):
    """Cowper's shear coefficient of a rectangular section."""
    return 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu)


def tip_deflection(P, L, b, h, E, nu):
    """Timoshenko tip deflection under a tip force P: bending plus shear."""
    I = b * h**3 / 12.0
    G = E / (2.0 * (1.0 + nu))
    return P * L**3 / (3.0 * E * I) + P * L / (shear_coefficient(nu) * G * b * h)


def first_frequency(L, b, h, E, nu, rho, nel=400):
    """First bending eigenfrequency [Hz] of the Timoshenko cantilever (shear and rotary inertia),
    from a converged 1D finite element model (linear elements, reduced-integration shear)."""
    K, M = _timoshenko_matrices(L, b, h, E, nu, rho, nel)
    free = np.arange(2, len(K))            # the clamped node's w and theta removed
    w2 = scipy.linalg.eigh(K[np.ix_(free, free)], M[np.ix_(free, free)], eigvals_only=True, subset_by_index=[0, 0])
    return float(np.sqrt(w2[0]) / (2 * np.pi))


def euler_bernoulli_first_frequency(L, b, h, E, rho):
    I, A = b * h**3 / 12.0, b * h
    return 1.87510407**2 / (2 * np.pi) * np.sqrt(E * I / (rho * A * L**4))


def _timoshenko_matrices(L, b, h, E, nu, rho, nel):
    """K and M of the 1D Timoshenko beam above, (w, theta) per node, no DOF held."""
    I, A = b * h**3 / 12.0, b * h
    G, k = E / (2.0 * (1.0 + nu)), shear_coefficient(nu)
    le = L / nel
    n = 2 * (nel + 1)
    K = np.zeros((n, n)); M = np.zeros((n, n))
    kb = E * I / le * np.array([[0, 0, 0, 0], [0, 1, 0, -1], [0, 0, 0, 0], [0, -1, 0, 1]])
    B = np.array([-1 / le, -0.5, 1 / le, -0.5])
    ks = k * G * A * le * np.outer(B, B)
    Nl = np.array([[2, 1], [1, 2]]) * le / 6.0
    for e in range(nel):
        idx = [2 * e, 2 * e + 1, 2 * e + 2, 2 * e + 3]
        K[np.ix_(idx, idx)] += kb + ks
        M[np.ix_([idx[0], idx[2]], [idx[0], idx[2]])] += rho * A * Nl
        M[np.ix_([idx[1], idx[3]], [idx[1], idx[3]])] += rho * I * Nl
    return K, M


def free_free(L, b, h, E, nu, rho, P, nel=400):
    """The free-free Timoshenko beam: its first elastic bending eigenfrequency [Hz], and the tip
    deflection under a tip force P balanced by the beam's rigid-body inertia (inertia relief),
    the deflection taken mass-orthogonal to the rigid motions (translation and rotation)."""
    K, M = _timoshenko_matrices(L, b, h, E, nu, rho, nel)
    x = np.linspace(0.0, L, nel + 1)
    R = np.zeros((len(K), 2))
    R[0::2, 0] = 1.0                     # translation
    R[0::2, 1], R[1::2, 1] = x - L / 2, 1.0  # rotation: w = x - L/2, theta = w'
    w2 = scipy.linalg.eigh(K, M, eigvals_only=True, subset_by_index=[0, 2])
    f = np.zeros(len(K))
    f[-2] = P
    MR = M @ R
    fr = f - MR @ np.linalg.solve(R.T @ MR, R.T @ f)
    kkt = np.block([[K, MR], [MR.T, np.zeros((2, 2))]])
    w = np.linalg.solve(kkt, np.concatenate([fr, np.zeros(2)]))[:len(K)]
    return float(np.sqrt(w2[2]) / (2 * np.pi)), float(w[-2])
