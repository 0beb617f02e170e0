"""Post-processing of frictional runs: the work of a load over a hysteresis loop, and the
backbone (amplitude, frequency, damping ratio) of a ring-down."""
import numpy as np


def loop_work(load, x):
    """The work of the load on its point over the path x (the hysteresis loop's area over a
    closed cycle), by the trapezoidal rule."""
    load, x = np.asarray(load), np.asarray(x)
    return float(np.sum(0.5 * (load[1:] + load[:-1]) * np.diff(x)))


def per_cycle(t, d, period, cycles):
    """The increase of a history d(t) over each of the first cycles of the period, between the
    samples nearest to the cycles' ends."""
    ends = [int(np.argmin(np.abs(t - k * period))) for k in range(cycles + 1)]
    return [float(d[j] - d[i]) for i, j in zip(ends[:-1], ends[1:])]


def fit_decay(t, x, omega):
    """Least squares of c + exp(-sigma s) (A cos(omega s) + B sin(omega s)), s = t - mid: c, A, B
    linear, (omega, sigma) by Gauss-Newton from (omega, 0). Returns omega, sigma and the amplitude
    at mid, sqrt(A^2 + B^2)."""
    s = t - 0.5 * (t[0] + t[-1])

    def solve(w, sg):
        basis = np.column_stack([np.ones_like(s), np.exp(-sg * s) * np.cos(w * s), np.exp(-sg * s) * np.sin(w * s)])
        coef, *_ = np.linalg.lstsq(basis, x, rcond=None)
        return x - basis @ coef, coef

    p = np.array([omega, 0.0])
    for _ in range(30):
        r, coef = solve(*p)
        h = np.array([1e-6 * p[0], 1e-6 * p[0]])
        J = np.column_stack([(solve(p[0] + h[0], p[1])[0] - r) / h[0], (solve(p[0], p[1] + h[1])[0] - r) / h[1]])
        step, *_ = np.linalg.lstsq(J, -r, rcond=None)
        p = p + step
        if np.all(np.abs(step) <= 1e-10 * p[0]):
            break
    _, coef = solve(*p)
    return p[0], p[1], float(np.hypot(coef[1], coef[2]))


def backbone(t, x, release, periods=3):
    """The first mode's decay after the release, window by window (`periods` periods long, one
    period apart): a damped sine fitted to the probe (a constant offset, friction's locked-in slip,
    drops out; the higher modes the release excites are small beside it) gives the amplitude at
    the window's middle, the frequency omega / 2 pi and the damping ratio sigma / |omega + i sigma|."""
    keep = t > release
    t, x = t[keep], x[keep]
    dt = t[1] - t[0]
    spec = np.abs(np.fft.rfft(x - x.mean()))
    f0 = np.fft.rfftfreq(len(x), dt)[1 + int(np.argmax(spec[1:]))]
    rows, start = [], t[0]
    while start + periods / f0 <= t[-1]:
        w = (t >= start) & (t < start + periods / f0)
        omega, sigma, amp = fit_decay(t[w], x[w], 2 * np.pi * f0)
        rows.append(dict(time=float(0.5 * (t[w][0] + t[w][-1])), amplitude=amp, frequency=float(omega / (2 * np.pi)),
                         damping=float(sigma / np.hypot(omega, sigma))))
        f0 = omega / (2 * np.pi)
        start += 1 / f0
    return rows


def cycle_differences(reference, other, counted):
    """Per cycle, other's relative difference from reference, or None where the reference cycle
    dissipates less than the share counted of its largest cycle (such a cycle's relative figure
    says nothing: a ROM may well dissipate twice a negligible amount)."""
    largest = max(abs(r) for r in reference) if reference else 0.0
    return [(o - r) / r if largest > 0 and abs(r) >= counted * largest else None for r, o in zip(reference, other)]
