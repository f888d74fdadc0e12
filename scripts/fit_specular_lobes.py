#!/usr/bin/env python3
"""Fits the split sum's lookups to the true specular lobe; writes engine/render/specular_lobes_table.cpp.

The split sum reads the prefiltered cube along R with the lobe of n = v = R: a GGX kernel
symmetric about its axis. The true lobe D V (n.l) at n.v < 1 is not: it leans towards n and
stretches in the plane of n and v. This script fits, for each (n.v, roughness) of a table, three
kernels of the prefiltered cube (the bake's own kernel, D(h) (d.l) around an axis d, at any
roughness) to the normalised lobe by least squares over the sphere: each kernel's axis lies in the
plane of n and R at a fraction s of the angle from n to R (s = 1: R itself), with its own roughness
and weight (weights summing to 1, so a uniform environment stays exact). Continuation over n.v and
roughness keeps the table smooth enough to interpolate.

Usage: python3 scripts/fit_specular_lobes.py [OUT.cpp]   (needs Debian's python3-numpy, python3-scipy;
about 10 minutes on two cores). Fresnel is left out of the fit: the LUT scales the lookups' sum.

       python3 scripts/fit_specular_lobes.py --two [OUT.cpp]   fits two kernels of equal weight instead
(engine/render/specular_lobes_two_table.cpp; under a minute): one table read and one cube read fewer,
which the forward pass uses from roughness 0.6 up and wherever the automatic shading choice predicts
them about as good (FrameSettings::two_lookup_groups; docs/accuracy.md).
"""
import sys
import numpy as np
from scipy.optimize import least_squares

K = 3  # kernels per entry (2 with --two: equal weights, only the axes and roughnesses fitted)
NV = [round(0.1 * i, 2) for i in range(1, 10)]   # n.v columns 0.1 .. 0.9
ROUGH = [round(0.1 * i, 2) for i in range(2, 11)]  # roughness rows 0.2 .. 1.0


def directions(h, w):
    v = 1.0 - (np.arange(h) + 0.5) / h
    u = (np.arange(w) + 0.5) / w
    lat, lon = np.meshgrid((v - 0.5) * np.pi, (u - 0.5) * 2 * np.pi, indexing='ij')
    d = np.stack([np.cos(lat) * np.cos(lon), np.sin(lat), np.cos(lat) * np.sin(lon)], -1)
    dw = (2 * np.pi / w) * (np.pi / h) * np.cos(lat)
    return d.reshape(-1, 3), dw.reshape(-1)


def ggx(a, nh):
    a2 = a * a
    t = nh * nh * (a2 - 1) + 1
    return a2 / (np.pi * t * t)


def visibility(model, r, nv, nl):
    a2 = r ** 4
    if model == 'gltf':  # height-correlated Smith (glTF 2.0 appendix B)
        return 0.5 / (nl * np.sqrt(nv * nv * (1 - a2) + a2) + nv * np.sqrt(nl * nl * (1 - a2) + a2))
    k = r * r / 2  # the thesis' Schlick-GGX with k_IBL
    return 1 / (4 * (nl * (1 - k) + k) * (nv * (1 - k) + k))


class Fitter:
    def __init__(self, model, grid_h):
        self.model = model
        self.dirs, self.dw = directions(grid_h, 2 * grid_h)
        self.sq = np.sqrt(self.dw)
        # canonical frame on the grid's equator: n = +x, v in the x-z plane, R on the -z side
        self.n, self.t = np.array([1.0, 0, 0]), np.array([0, 0, 1.0])

    def lobe(self, nv, r):
        v = self.n * nv + self.t * np.sqrt(1 - nv * nv)
        nl = self.dirs @ self.n
        h = self.dirs + v
        h /= np.linalg.norm(h, axis=1, keepdims=True)
        f = np.where(nl > 0, ggx(r * r, np.clip(h @ self.n, -1, 1)) *
                     visibility(self.model, r, nv, np.maximum(nl, 1e-9)) * nl, 0) * self.dw
        return f / f.sum()

    def kernel(self, beta, r):
        d = self.n * np.cos(beta) - self.t * np.sin(beta)
        c = self.dirs @ d
        k = np.where(c > 0, ggx(r * r, np.sqrt(np.maximum((1 + c) / 2, 0))) * c, 0) * self.dw
        return k / k.sum()

    def mix(self, p, theta):
        return sum(p[2 * K + k] * self.kernel(p[k] * theta, p[K + k]) for k in range(K))

    def fit(self, nv, r, p0):
        f, theta = self.lobe(nv, r), np.arccos(nv)
        if K == 2:
            # Equal weights: the free parameters are the axes and roughnesses.
            def residual(q):
                return (self.mix(np.concatenate([q, [0.5, 0.5]]), theta) - f) / self.sq
            lo = np.array([-0.5, -0.5, 0.03, 0.03])
            hi = np.array([4.0, 4.0, 1.0, 1.0])
            q = least_squares(residual, np.clip(p0[:2 * K], lo + 1e-6, hi - 1e-6), bounds=(lo, hi), x_scale='jac',
                              max_nfev=400).x
            p = np.concatenate([q, [0.5, 0.5]])
        else:
            def residual(p):
                return np.concatenate([(self.mix(p, theta) - f) / self.sq, [10.0 * (p[2 * K:].sum() - 1)]])
            lo = np.concatenate([np.full(K, -0.5), np.full(K, 0.03), np.zeros(K)])
            hi = np.concatenate([np.full(K, 4.0), np.ones(K), np.ones(K)])
            p = least_squares(residual, np.clip(p0, lo + 1e-6, hi - 1e-6), bounds=(lo, hi), x_scale='jac',
                              max_nfev=400).x
            p[2 * K:] /= p[2 * K:].sum()
        fitted = np.abs(f - self.mix(p, theta)).sum()
        mirror = np.abs(f - self.kernel(theta, r)).sum()
        return p, fitted, mirror


def fit_model(model):
    table, start = {}, None
    for r in ROUGH:
        fitter = Fitter(model, 256 if r <= 0.35 else 128)  # finer grid for narrow lobes
        p0 = start if start is not None else (
            np.array([0.6, 0.9, 1.1, r, 0.8 * r, 0.8 * r, 0.4, 0.35, 0.25]) if K == 3 else
            np.array([0.7, 1.05, 0.9 * r, 0.8 * r, 0.5, 0.5]))
        p, fitted, mirror = fitter.fit(0.5, r, p0)
        start = p.copy()
        table[(0.5, r)] = p
        print(f'{model} r={r:.1f} n.v=0.5: L1 {fitted:.3f} (one lookup along R: {mirror:.3f})', flush=True)
        for sweep in ([0.6, 0.7, 0.8, 0.9], [0.4, 0.3, 0.2, 0.1]):
            q = p.copy()
            for nv in sweep:
                q, fitted, mirror = fitter.fit(nv, r, q)
                table[(nv, r)] = q.copy()
                print(f'{model} r={r:.1f} n.v={nv:.1f}: L1 {fitted:.3f} (one lookup along R: {mirror:.3f})',
                      flush=True)
    return table


def write_table(out, entries):
    """entries: (model, roughness, n.v, lookup, s, lookup roughness, weight), in table order."""
    if K == 2:
        rows = '\n'.join(f'    {{{e[4]:.5f}f, {e[5]:.5f}f}},  // {e[0]} r {e[1]:.1f} n.v {e[2]:.1f} lookup {e[3]}'
                         for e in entries)
        text = '''// Generated by scripts/fit_specular_lobes.py --two (do not edit): two lookups of equal weight of
// the prefiltered cube fitted to the specular lobe D V (n.l) by least squares, per BRDF model (glTF,
// then the thesis'), roughness 0.2 .. 1.0 by 0.1 (rows) and n.v 0.1 .. 0.9 by 0.1 (columns), two per
// entry: (s, roughness), the lookup's axis at the fraction s of the angle from n to R.
#include "render/specular_lobes_table.h"

namespace facet {

const float kSpecularLobeTwoEntries[kSpecularLobeModels * kSpecularLobeRows * kSpecularLobeColumns * 2][2] = {
%s
};

}  // namespace facet
'''
    else:
        rows = '\n'.join(f'    {{{e[4]:.5f}f, {e[5]:.5f}f, {e[6]:.5f}f}},  // {e[0]} r {e[1]:.1f} n.v {e[2]:.1f} lookup {e[3]}'
                         for e in entries)
        text = '''// Generated by scripts/fit_specular_lobes.py (do not edit): three lookups of the prefiltered
// cube fitted to the specular lobe D V (n.l) by least squares, per BRDF model (glTF, then the
// thesis'), roughness 0.2 .. 1.0 by 0.1 (rows) and n.v 0.1 .. 0.9 by 0.1 (columns), three per
// entry: (s, roughness, weight), the lookup's axis at the fraction s of the angle from n to R.
#include "render/specular_lobes_table.h"

namespace facet {

const float kSpecularLobeEntries[kSpecularLobeModels * kSpecularLobeRows * kSpecularLobeColumns * 3][3] = {
%s
};

}  // namespace facet
'''
    with open(out, 'w') as f:
        f.write(text % rows)


def main():
    global K
    args = sys.argv[1:]
    if args and args[0] == '--two':
        K = 2
        args = args[1:]
    out = args[0] if args else ('engine/render/specular_lobes_two_table.cpp' if K == 2 else
                                'engine/render/specular_lobes_table.cpp')
    entries = []
    for model in ('gltf', 'thesis'):
        table = fit_model(model)
        for r in ROUGH:
            for nv in NV:
                p = table[(nv, r)]
                entries += [(model, r, nv, k, p[k], p[K + k], p[2 * K + k]) for k in range(K)]
    write_table(out, entries)


if __name__ == '__main__':
    main()
