#!/usr/bin/python3
"""Charts and a report from facet-bench sweep's sweep.json: for each bake stage (irradiance,
specular, lut) error against GPU time, log-log, one series per method (each point a
parameter setting, the median over the environments), the Pareto front marked, and
settings that fail anywhere (NaN, Inf, negative values, error above the bound) drawn as
crosses. The final image (stage "image", chart_image.py): one panel per environment, the
worst roughness x metalness group's error against frame time for every shading method and
the reference mode's samples per pixel, the Pareto front and the automatic choice starred.
Writes DIR/chart_<stage>.svg and .png (the image chart: PNG only, one per BRDF model) and
DIR/report.md.

Usage: /usr/bin/python3 scripts/chart.py DIR   (Debian's python3-matplotlib)
"""
import json
import os
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from chart_image import image_section  # noqa: E402

# One sentence per method on what it is; the numbers in the report come from the data.
DESCRIPTIONS = {
    "convolve": "exact cosine (or GGX) sum over blocks of the input's own texels, each with its exact power",
    "riemann": "the thesis' Riemann sum over (phi, theta) of the cube, with a fixed angular step",
    "sh9": "nine spherical-harmonic coefficients per channel, Hanning-windowed against ringing",
    "sh9-raw": "nine spherical-harmonic coefficients without a window",
    "blur": "a spherical Gaussian blur of a small cube level (a cheap stand-in for the cosine lobe)",
    "lowmip": "a trilinear sample of a low level of the cube's mip chain (the cheapest stand-in)",
    "importance": "the thesis' GGX importance sampling of the full-resolution cube",
    "filtered": "GGX importance sampling that reads a mip matched to each sample's solid angle (Krivanek-Colbert)",
    "mips": "the environment's own box-filtered mip chain, one level per roughness",
    "hybrid": "filtered importance sampling of the sky clamped at 16x its mean, plus the excess summed exactly",
    "automatic": "hybrid for smooth levels, texel-block convolution from roughness 0.5",
}
STAGE_TITLES = {
    "irradiance": "Diffuse irradiance: error against the brute-force integral",
    "specular": "Specular prefilter (every level): error against the brute-force GGX integral",
    "lut": "Split-sum LUT: error against quadrature",
}


def aggregate(rows):
    """(method, parameters) -> median time, median error, failures by environment."""
    groups = {}
    for r in rows:
        groups.setdefault((r["method"], r["parameters"]), []).append(r)
    points = []
    for (method, params), rs in groups.items():
        points.append({
            "method": method,
            "parameters": params,
            "gpu_ms": statistics.median(r["gpu_ms"] for r in rs),
            "rel_rmse": statistics.median(r["rel_rmse"] for r in rs),
            "worst": max(rs, key=lambda r: r["rel_rmse"]),
            "failures": [(r["environment"], r["failure"]) for r in rs if r["failed"]],
        })
    return points


def pareto(points):
    """Settings no other setting beats in both time and error (failed ones excluded)."""
    ok = sorted((p for p in points if not p["failures"]), key=lambda p: (p["gpu_ms"], p["rel_rmse"]))
    front, best = [], float("inf")
    for p in ok:
        if p["rel_rmse"] < best:
            front.append(p)
            best = p["rel_rmse"]
    return front


def chart(stage, points, front, out_dir):
    fig, ax = plt.subplots(figsize=(8, 5.5))
    methods = sorted({p["method"] for p in points})
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, m in enumerate(methods):
        mine = sorted((p for p in points if p["method"] == m), key=lambda p: p["gpu_ms"])
        color = colors[i % len(colors)]
        xs = [max(p["gpu_ms"], 1e-3) for p in mine]
        ys = [max(p["rel_rmse"], 1e-6) for p in mine]
        ax.plot(xs, ys, "-", color=color, alpha=0.5, linewidth=1)
        for p, x, y in zip(mine, xs, ys):
            ax.plot(x, y, "x" if p["failures"] else "o", color=color, markersize=8 if p["failures"] else 6,
                    markeredgewidth=2 if p["failures"] else 1)
            ax.annotate(p["parameters"], (x, y), textcoords="offset points", xytext=(4, 3), fontsize=6,
                        color=color)
        ax.plot([], [], "o-", color=color, label=m)
    if front:
        ax.plot([max(p["gpu_ms"], 1e-3) for p in front], [max(p["rel_rmse"], 1e-6) for p in front], "k--",
                linewidth=1.5, label="Pareto front")
        for p in front:
            ax.plot(max(p["gpu_ms"], 1e-3), max(p["rel_rmse"], 1e-6), "o", markersize=11, markerfacecolor="none",
                    markeredgecolor="black")
    ax.plot([], [], "kx", label="fails somewhere (NaN, negative, above bound)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per bake or frame, ms (median; lavapipe unless stated)")
    ax.set_ylabel("relative RMS error (median over environments)")
    ax.set_title(STAGE_TITLES.get(stage, stage), fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    fig.tight_layout()
    for ext in ("svg", "png"):
        fig.savefig(os.path.join(out_dir, f"chart_{stage}.{ext}"), dpi=110)
    plt.close(fig)


def paragraph(method, points, front):
    mine = [p for p in points if p["method"] == method]
    best = min(mine, key=lambda p: p["rel_rmse"])
    fastest = min(mine, key=lambda p: p["gpu_ms"])
    on_front = [p for p in mine if p in front]
    text = f"**{method}**: {DESCRIPTIONS.get(method, '')}. "
    text += (f"Best error {100 * best['rel_rmse']:.2f}% ({best['parameters']}, {best['gpu_ms']:.2f} ms); "
             f"fastest {fastest['gpu_ms']:.2f} ms at {100 * fastest['rel_rmse']:.2f}% ({fastest['parameters']}). ")
    if on_front:
        text += "Wins (on the Pareto front) with " + ", ".join(p["parameters"] for p in on_front) + ". "
    else:
        text += "Never on the Pareto front. "
    broken = [(p["parameters"], f) for p in mine for f in p["failures"]]
    if broken:
        envs = sorted({f[0] for _, f in broken})
        text += (f"Breaks on {', '.join(envs)}: " +
                 "; ".join(sorted({f'{params}: {reason}' for params, (_, reason) in broken})[:4]) + ".")
    else:
        text += "No failure on any environment."
    worst = max(mine, key=lambda p: p["worst"]["rel_rmse"])["worst"]
    text += f" Worst case {100 * worst['rel_rmse']:.1f}% on {worst['environment']} ({worst['parameters']})."
    return text


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out_dir = sys.argv[1]
    path = os.path.join(out_dir, "sweep.json")
    try:
        with open(path) as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"chart.py: error: {path}: {e}")
    rows = data["rows"]
    lines = ["# Facet: speed against accuracy", "",
             f"`facet-bench sweep` on {data['device']}, environments downsampled to {data['environment_width']} "
             f"texels wide, {data['runs']} runs per setting (medians). Environments: "
             f"{', '.join(sorted({r['environment'] for r in rows if r['environment'] != 'any'}))}.", ""]
    for stage in ("irradiance", "specular", "lut"):
        stage_rows = [r for r in rows if r["stage"] == stage]
        if not stage_rows:
            continue
        points = aggregate(stage_rows)
        front = pareto(points)
        chart(stage, points, front, out_dir)
        lines += [f"## {STAGE_TITLES[stage]}", "", f"![{stage}](chart_{stage}.png)", ""]
        for method in sorted({p["method"] for p in points}):
            lines += [paragraph(method, points, front), ""]
    image_rows = [r for r in rows if r["stage"] == "image"]
    if image_rows:
        lines += image_section(image_rows, data, out_dir)
    report = os.path.join(out_dir, "report.md")
    with open(report + ".tmp", "w") as f:
        f.write("\n".join(lines))
    os.replace(report + ".tmp", report)
    print(f"wrote {report} and chart_*.svg/png in {out_dir}")


if __name__ == "__main__":
    main()
