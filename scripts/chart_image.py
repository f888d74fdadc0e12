"""The final-image part of scripts/chart.py: facet-bench sweep's stage "image" rows
(builtin:spheres, every shading method and the reference mode at several samples per
pixel, each against the exact integral per roughness x metalness group, issue 13).

Chart (one PNG per BRDF model): one panel per environment, worst group's mean error
against frame time, log-log; one series per method (the reference mode's samples per
pixel joined as one series), the Pareto front dashed, the automatic choice starred, the
3% and 5% targets as lines. Report: a table per model and a paragraph per method, every
figure taken from the rows.
"""
import math
import os
import statistics

import matplotlib.pyplot as plt

TARGETS = (0.03, 0.05)  # issue 13: 3% on the sunny skies, 5% on the studio and warehouse
FORWARD = ["split-sum", "dominant", "lights", "lights+dominant"]
DESCRIPTIONS = {
    "split-sum": "the prefiltered cube along R times the LUT (Karis 2013)",
    "dominant": "the split sum with three lookups fitted to the true lobe",
    "lights": "bright regions taken out of the map and shaded as disk lights with the full BRDF, "
              "the residual through the split sum",
    "lights+dominant": "extracted lights and the fitted lookups together",
    "auto": "the method the session picks for the environment (RenderJob::shading = automatic)",
    "reference": "the reference mode, Monte Carlo over the whole environment at a fixed number of samples "
                 "per pixel (its time: the whole call)",
}
COLORS = {"split-sum": "tab:blue", "dominant": "tab:orange", "lights": "tab:green",
          "lights+dominant": "tab:red", "reference": "tab:purple", "auto": "black"}


def target_of(env):
    """Issue 13's target for an environment: 5% under the studio and the warehouse, else 3%."""
    return TARGETS[1] if env.startswith(("studio_small_03", "empty_warehouse_01")) else TARGETS[0]


def err(r):
    e = r.get("worst_group_mean_rel")
    return e if isinstance(e, (int, float)) and math.isfinite(e) else float("inf")


def pct(e):
    return "n/a" if not math.isfinite(e) else f"{100 * e:.1f}%"


def pareto(points):
    """Rows no other row beats in both time and error (failed rows left out)."""
    ok = sorted((p for p in points if not p["failed"] and math.isfinite(err(p))), key=lambda p: (p["gpu_ms"], err(p)))
    front, best = [], float("inf")
    for p in ok:
        if err(p) < best:
            front.append(p)
            best = err(p)
    return front


def by_env(rows):
    envs = {}
    for r in rows:
        envs.setdefault(r["environment"], []).append(r)
    return envs


def leading(v):
    """The leading digit of a positive number (log-axis tick labels: 1, 2 and 5 only)."""
    return int(round(v / 10 ** math.floor(math.log10(v) + 1e-9))) if v > 0 else 0


def panel(ax, env, rows):
    for method in FORWARD + ["reference"]:
        mine = sorted((r for r in rows if r["method"] == method), key=lambda r: r["gpu_ms"])
        if not mine:
            continue
        xs, ys = [max(r["gpu_ms"], 1e-3) for r in mine], [max(err(r), 1e-4) for r in mine]
        ax.plot(xs, ys, "-" if len(mine) > 1 else "", color=COLORS[method], alpha=0.6, linewidth=1)
        for r, x, y in zip(mine, xs, ys):
            ax.plot(x, y, "x" if r["failed"] else "o", color=COLORS[method], markersize=6)
            if method == "reference":
                ax.annotate(str(r["samples_per_pixel"]), (x, y), textcoords="offset points", xytext=(4, 2),
                            fontsize=6, color=COLORS[method])
    front = pareto(rows)
    if front:
        ax.plot([p["gpu_ms"] for p in front], [max(err(p), 1e-4) for p in front], "k--", linewidth=1, alpha=0.7)
    for r in rows:
        if r["method"] == "auto":
            ax.plot(max(r["gpu_ms"], 1e-3), max(err(r), 1e-4), "*", color="gold", markeredgecolor="black",
                    markersize=15, zorder=5)
            ax.annotate(f"auto: {r.get('auto_choice', '?')}", (r["gpu_ms"], max(err(r), 1e-4)),
                        textcoords="offset points", xytext=(6, -10), fontsize=7)
    for target, style in zip(TARGETS, (":", "-.")):
        ax.axhline(target, color="gray", linestyle=style, linewidth=0.8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_title(env, fontsize=9)
    ax.grid(True, which="both", alpha=0.25)
    ax.tick_params(which="both", labelsize=7)
    ax.set_ylim(bottom=min(ax.get_ylim()[0], 0.02))  # the targets always in view
    for axis, unit in ((ax.xaxis, lambda v: f"{v:g}"), (ax.yaxis, lambda v: f"{100 * v:g}%")):
        axis.set_major_formatter(plt.FuncFormatter(lambda v, _, unit=unit: unit(v) if leading(v) in (1, 2, 5) else ""))
        axis.set_minor_formatter(plt.FuncFormatter(lambda v, _, unit=unit: unit(v) if leading(v) in (2, 5) else ""))


def chart(rows, brdf, data, out_dir):
    envs = by_env(rows)
    n = len(envs) + 1  # the last panel holds the legend
    cols = min(3, n)
    nrows = math.ceil(n / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(3.6 * cols, 3.0 * nrows), squeeze=False)
    flat = [a for row in axes for a in row]
    for ax, (env, mine) in zip(flat, sorted(envs.items())):
        panel(ax, env, mine)
    for ax in flat[len(envs):]:
        ax.axis("off")
    legend = flat[len(envs)]
    for method in FORWARD + ["reference"]:
        legend.plot([], [], "o-", color=COLORS[method], label=method + (" (spp marked)" if method == "reference" else ""))
    legend.plot([], [], "*", color="gold", markeredgecolor="black", markersize=12, label="auto's choice")
    legend.plot([], [], "k--", label="Pareto front")
    legend.plot([], [], "x", color="gray", label="NaN, Inf or negative")
    legend.plot([], [], color="gray", linestyle=":", label="3% target")
    legend.plot([], [], color="gray", linestyle="-.", label="5% target")
    legend.legend(loc="center", fontsize=8, frameon=False)
    for row in axes:
        row[0].set_ylabel("worst group's mean error", fontsize=8)
    for ax in flat[max(0, len(envs) - cols):len(envs)]:
        ax.set_xlabel("frame time, ms (median wall time)", fontsize=8)
    fig.suptitle(f"Final image of builtin:spheres ({data.get('image_width', '?')}x{data.get('image_height', '?')}, "
                 f"{brdf} BRDF):\nworst roughness x metalness group against the exact integral", fontsize=10)
    fig.tight_layout()
    name = "chart_image.png" if brdf == "gltf" else f"chart_image_{brdf}.png"
    fig.savefig(os.path.join(out_dir, name), dpi=80)
    plt.close(fig)
    return name


def envs_meeting(rows, method, target):
    return sorted(r["environment"] for r in rows if r["method"] == method and err(r) <= target and not r["failed"])


def ratio_text(ratios):
    if not ratios:
        return ""
    if len(ratios) == 1:
        return f"{ratios[0]:.2f}x the split sum's frame"
    return (f"{statistics.median(ratios):.2f}x the split sum's frame (median; "
            f"{min(ratios):.2f}-{max(ratios):.2f}x)")


def paragraph(method, rows, envs):
    split = {r["environment"]: r for r in rows if r["method"] == "split-sum"}
    mine = [r for r in rows if r["method"] == method]
    text = f"**{method}**: {DESCRIPTIONS.get(method, '')}. "
    if method == "reference":
        parts = []
        for env in sorted(envs):
            env_rows = sorted((r for r in mine if r["environment"] == env), key=lambda r: r["samples_per_pixel"])
            meets = next((r for r in env_rows if err(r) <= target_of(env)), None)
            shown = meets or min(env_rows, key=err)
            base = split.get(env, {}).get("gpu_ms", 0)
            cost = f", {shown['gpu_ms'] / base:.0f}x the split sum's frame" if base > 0 else ""
            parts.append(f"{env}: within {pct(target_of(env))} from {shown['samples_per_pixel']} spp{cost}" if meets else
                         f"{env}: {pct(err(shown))} at {shown['samples_per_pixel']} spp{cost}")
        text += ("Unbiased, its error is noise falling as 1/sqrt(spp). Against each environment's target: " +
                 "; ".join(parts) + ".")
        return text
    met3, met5 = envs_meeting(mine, method, 0.03), envs_meeting(mine, method, 0.05)
    on_target = [r["environment"] for r in mine if err(r) <= target_of(r["environment"]) and not r["failed"]]
    text += f"Meets its environment's target on {', '.join(sorted(on_target)) or 'none'}. "
    text += f"Within 3% on {', '.join(met3) or 'none'}"
    more5 = [e for e in met5 if e not in met3]
    text += f"; within 5% also on {', '.join(more5)}" if more5 else ""
    missed = sorted((r for r in mine if err(r) > 0.05), key=lambda r: -err(r))
    if missed:
        text += "; breaks on " + ", ".join(f"{r['environment']} ({pct(err(r))}, {r['worst_group']})" for r in missed)
    text += ". "
    ratios = [r["gpu_ms"] / split[r["environment"]]["gpu_ms"] for r in mine
              if r["environment"] in split and split[r["environment"]]["gpu_ms"] > 0]
    if method != "split-sum":
        text += f"Costs {ratio_text(ratios)}. "
        worse = [r["environment"] for r in mine if r["environment"] in split and
                 err(r) > err(split[r["environment"]]) * 1.02 + 1e-4]
        text += (f"Worse than the split sum on {', '.join(sorted(worse))}. " if worse
                 else "Never worse than the split sum. ")
    wins = [env for env, rs in sorted(by_env(rows).items()) if any(p["method"] == method for p in pareto(rs))]
    text += f"On the Pareto front on {', '.join(wins)}. " if wins else "Never on the Pareto front. "
    if method == "auto":
        picks = [f"{r['environment']}: {r.get('auto_choice', '?')} ({r.get('auto_reason', '')})" for r in
                 sorted(mine, key=lambda r: r["environment"])]
        text += "Picks " + "; ".join(picks) + ". "
        cheaper = []
        for r in mine:
            env_rows = [x for x in rows if x["environment"] == r["environment"] and x["method"] in FORWARD]
            fit = [x for x in env_rows if err(x) <= 0.03]
            if fit:
                best = min(fit, key=lambda x: x["gpu_ms"])
                if best["method"] != r.get("auto_choice"):
                    cheaper.append(f"{r['environment']} ({best['method']}, {pct(err(best))})")
        if cheaper:
            text += "The cheapest method within 3% was another one on " + ", ".join(cheaper) + ". "
    failed = sorted({r["environment"] for r in mine if r["failed"]})
    if failed:
        text += f"NaN, Inf or negative values on {', '.join(failed)}."
    return text.strip()


def table(rows, envs):
    methods = FORWARD + ["auto"]
    spps = sorted({r["samples_per_pixel"] for r in rows if r["method"] == "reference"})
    head = ["environment"] + methods + [f"ref {s} spp" for s in spps]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for env in sorted(envs):
        cells = [env]
        for m in methods:
            r = next((x for x in rows if x["environment"] == env and x["method"] == m), None)
            cells.append(f"{pct(err(r))}, {r['gpu_ms']:.0f} ms" if r else "")
        for s in spps:
            r = next((x for x in rows if x["environment"] == env and x["method"] == "reference"
                      and x["samples_per_pixel"] == s), None)
            cells.append(f"{pct(err(r))}, {r['gpu_ms']:.0f} ms" if r else "")
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def group_table(rows, envs):
    """Every group's mean error, per environment and method (the forward methods)."""
    groups = [g["group"].replace("roughness ", "") for g in rows[0]["groups"]]
    lines = ["| environment | method | " + " | ".join(groups) + " |", "|---|---|" + "---|" * len(groups)]
    for env in sorted(envs):
        for m in FORWARD:
            r = next((x for x in rows if x["environment"] == env and x["method"] == m), None)
            if r:
                lines.append(f"| {env} | {m} | " + " | ".join(pct(g["mean_rel"]) if g["pixels"] else "-"
                                                             for g in r["groups"]) + " |")
    return lines


def image_section(rows, data, out_dir):
    lines = ["## Final image of builtin:spheres: every shading method against the exact integral", "",
             f"{data.get('image_width', '?')}x{data.get('image_height', '?')} pixels; error: the worst "
             "roughness x metalness group's mean of |lum(render) - lum(truth)| / lum(truth) (n.v > 0.3, roughness "
             f">= 0.2; up to {data.get('truth_pixels', '?')} pixels), the truth the double-precision sum of the "
             "BRDF over every environment texel. Time: median wall time of the frame's passes (the views drawn for "
             "the measurement left out), or of the reference-mode call. Targets: 3% (builtin:sky, venice_sunset, "
             "royal_esplanade), 5% (studio_small_03, empty_warehouse_01).", ""]
    for brdf in sorted({r.get("brdf", "gltf") for r in rows}, key=lambda b: b != "gltf"):
        mine = [r for r in rows if r.get("brdf", "gltf") == brdf]
        envs = set(by_env(mine))
        name = chart(mine, brdf, data, out_dir)
        lines += [f"### {brdf} BRDF", "", f"![final image, {brdf} BRDF]({name})", "",
                  "Worst group's error and frame time:", ""] + table(mine, envs) + [""]
        for method in FORWARD + ["auto", "reference"]:
            if any(r["method"] == method for r in mine):
                lines += [paragraph(method, mine, envs), ""]
        lines += ["Every group's mean error:", ""] + group_table(mine, envs) + [""]
    return lines
