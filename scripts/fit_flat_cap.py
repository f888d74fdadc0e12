#!/usr/bin/env python3
"""Fits the polynomial of shaders/ibl/irradiance_convolve.comp's flat_cap_cosine.

A narrow cap of radius sigma (s = sin(sigma)) whose axis is t s above a normal's horizon,
taken as a flat disk, receives s (t / 2 + G(t)) of the clamped cosine (per pi s^2), where
G(t) = (t asin(t) + sqrt(1 - t^2)(2 + t^2) / 3) / pi for |t| < 1. G is even: this fits
G(t) ~ c0 + c1 t^2 + c2 t^4 + c3 t^6 near-minimax (iteratively reweighted least squares)
and prints the coefficients and the largest error on [-1, 1]. Also prints how far the flat
disk is from the exact spherical cap (Snyder 1996) at a few radii. Standard library only.
"""
import math

from make_sheen_albedo import solve  # Gaussian elimination, beside this script

TERMS = 4
N = 4001


def g(t):
    return (t * math.asin(t) + math.sqrt(max(0.0, 1.0 - t * t)) * (2.0 + t * t) / 3.0) / math.pi


def fit():
    ts = [-1.0 + 2.0 * i / (N - 1) for i in range(N)]
    ys = [g(t) for t in ts]
    w = [1.0] * N
    for _ in range(40):
        a = [[sum(w[j] * ts[j] ** (2 * (p + q)) for j in range(N)) for q in range(TERMS)] for p in range(TERMS)]
        b = [sum(w[j] * ts[j] ** (2 * p) * ys[j] for j in range(N)) for p in range(TERMS)]
        c = solve(a, b)
        r = [sum(c[k] * ts[j] ** (2 * k) for k in range(TERMS)) - ys[j] for j in range(N)]
        worst = max(abs(x) for x in r)
        w = [w[j] * (1.0 + abs(r[j]) / worst) for j in range(N)]
        total = sum(w)
        w = [x / total * N for x in w]
    return c, worst


def snyder(c, s2):
    if c * c > s2:
        return max(c, 0.0)
    st = math.sqrt(max(1.0 - c * c, 0.0))
    x = math.sqrt(max(1.0 / s2 - 1.0, 0.0))
    y = max(-1.0, min(1.0, -x * c / max(st, 1e-7)))
    sts = st * math.sqrt(1.0 - y * y)
    e = (c * math.acos(y) - x * sts) * s2 + math.atan2(sts, x)
    return max(e, 0.0) / (math.pi * s2)


def flat(c, s):
    if abs(c) >= s:
        return max(c, 0.0)
    t = c / s
    return s * (0.5 * t + g(t))


if __name__ == "__main__":
    coefficients, worst = fit()
    print("G(t) ~ " + " + ".join(f"{c:.8f} t^{2 * k}" for k, c in enumerate(coefficients)))
    print(f"largest error on [-1, 1]: {worst:.2e}")
    for sigma in (0.05, 0.1, 0.2, 0.3):
        s = math.sin(sigma)
        error = max(abs(flat(s * i / 500, s) - snyder(s * i / 500, s * s)) for i in range(-500, 501))
        print(f"cap radius {sigma} rad: flat disk within {error:.1e} of the exact clipped cosine")
