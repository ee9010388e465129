"""The speed-accuracy trade, measured: `python -m validation accuracy --out DIR [--quick]`.

For each μ and method, one curve per setting (every preset; then, at `default`, one setting at a
time: surface element size, turn limit, FE bulk grading and truncation, BEM traction radius),
its wall time, and the error of each event against a reference: the BEM on elements half as
long as `fine`'s (and half its turn limit), whose own uncertainty is its difference from
`fine`; the FE rows, an independent method, cross-check it (their errors fall towards it under
refinement). The presets are also solved with their error estimate, to give the ratio of
estimate to true error. The observed order of each event comes from consecutive presets (their
element sizes and turn limits halve, except where the ripple cap makes two alike), the GW
strength F̄max's error from the quadrature's sample count against a 4x denser one. Last, the
exact sphere profile against Derjaguin's parabola for R/ε from 10 to 1e5.

Writes accuracy.md (tables), accuracy.json (every row) and accuracy.png (error against wall
time, log-log, the Pareto front and the presets marked)."""

import time
from dataclasses import replace

import numpy as np

from fem_asperity.solver.discretised import solve_discretised
from fem_asperity.solver.presets import PRESETS, discretisation
from fem_asperity.solver.solve import solve_curve

#: Events judged: the pull-off force, the most tensile approach force's separation and contact
#: radius, the gap before the jump-in, the jumps' positions, and the approach force maximum.
KEYS = ("p_off", "p_max", "delta_oc", "a_c", "x_oc", "delta_jump_in", "delta_jump_out")
#: One μ per regime; the FE's curves above FE_MU_MAX, and its `fine` above FE_FINE_MU_MAX, cost
#: minutes: left out (methods.md §14). Not pinned by a test.
STUDY_MUS, FE_MU_MAX, FE_FINE_MU_MAX = (0.1, 1.0, 5.0, 10.0), 5.0, 1.0
#: --quick: the transition only, the two cheaper presets, one setting of each kind.
QUICK_MUS, QUICK_PRESETS = (1.0,), ("draft", "default")
#: Settings varied one at a time around `default` (field of the discretisation, values).
SETTINGS = {
    "fem": (("grading", (0.4, 0.1)), ("size", (1e2, 1e4))),
    "bem": (("r_max", (25.0, 50.0)),),
}
TURNS = (0.2, 0.05)
#: Element-size ratio below which two presets' errors give no order (they differ in the turn
#: limit rather than the elements).
ORDER_MIN_RATIO = 1.2
#: An error is judged against the estimate only where it exceeds the reference's uncertainty
#: this many times.
RESOLVED = 10.0
#: The exact sphere against Derjaguin's parabola: R/ε values, the slope fitted from
#: DERJAGUIN_FIT_FROM on (methods.md §14). Not pinned by a test.
DERJAGUIN_RATIOS, DERJAGUIN_FIT_FROM = (10.0, 1e2, 1e3, 1e4, 1e5), 1e2
#: GW quadrature: F̄max at these sample counts against REFERENCE_SAMPLES.
GW_SAMPLES, GW_REFERENCE_SAMPLES = (12, 24, 48), 192


def _errors(events, reference):
    """Relative error per key against the reference (None where either lacks the event)."""
    return {k: (abs(events[k] - reference[k]) / abs(reference[k])
                if events.get(k) is not None and reference.get(k) else None) for k in KEYS}


def _row(mu, method, setting, disc, reference):
    result = solve_discretised(mu, disc)
    return {"mu": mu, "method": method, "setting": setting, "h_surface": disc.h_surface,
            "folds": result.folds, "wall_s": result.wall_s,
            "error": _errors(result.events.records(), reference)}


def _reference(mu, step):
    """The reference events (BEM on `fine.refined()`), its uncertainty (relative difference from
    `fine`) and the BEM `fine` row."""
    step(f"mu = {mu:g}: reference (BEM, half the fine elements)")
    fine = discretisation(mu, "fine", method="bem")
    reference = solve_discretised(mu, fine.refined())
    events = reference.events.records()
    fine_result = solve_discretised(mu, fine)
    return events, {"events": events, "wall_s": reference.wall_s,
                    "uncertainty": _errors(fine_result.events.records(), events)}


def _presets(mu, method, presets, reference, uncertainty, step):
    """A row per preset: its wall time alone (`wall_s`, as the settings' rows) and with its error
    estimate (`wall_with_estimate_s`), its errors, and the estimate's ratio to the true error per
    key, where that error exceeds RESOLVED times the reference's own `uncertainty` (below, the
    reference cannot tell the true error)."""
    rows = []
    for name in presets:
        step(f"mu = {mu:g}: {method} {name}, alone and with its error estimate")
        alone = solve_curve(mu, method=method, accuracy=name, error_estimate=False)
        start = time.perf_counter()
        result = solve_curve(mu, method=method, accuracy=name)
        events, estimate = result.events.records(), result.error_estimate or {}
        error = _errors(events, reference)
        ratio = {k: (estimate[k] / abs(reference[k]) / error[k]
                     if error[k] and error[k] > RESOLVED * (uncertainty[k] or 0.0)
                     and estimate.get(k) is not None else None) for k in KEYS}
        rows.append({"mu": mu, "method": method, "setting": name, "preset": True,
                     "h_surface": discretisation(mu, name, method=method).h_surface,
                     "turn": PRESETS[name][1], "folds": result.folds, "status": result.status,
                     "estimated_by": result.estimated_by,
                     "wall_s": alone.wall_s, "wall_with_estimate_s": time.perf_counter() - start,
                     "error": error, "estimate_over_error": ratio})
    return rows


def _settings(mu, method, reference, quick, step):
    """A row per setting varied alone around `default` (no estimate: one curve each)."""
    base = discretisation(mu, "default", method=method)
    variants = [(f"turn {t:g}", replace(base, trace=replace(base.trace, turn=t)))
                for t in TURNS[:1 if quick else None]]
    for field, values in SETTINGS[method][:1 if quick else None]:
        if hasattr(base, field):
            variants += [(f"{field} {v:g}", replace(base, **{field: v}))
                         for v in values[:1 if quick else None]]
    rows = []
    for name, disc in variants:
        step(f"mu = {mu:g}: {method} default, {name}")
        rows.append({**_row(mu, method, name, disc, reference), "preset": False})
    return rows


def _orders(rows):
    """Observed order in the element size per key, between consecutive presets of each (μ,
    method): log(error ratio) / log(element-size ratio). Where the ripple cap gives two presets
    elements of nearly equal size (ratio below ORDER_MIN_RATIO) they differ in the turn limit
    only, and no order is given."""
    orders = []
    for (mu, method) in sorted({(r["mu"], r["method"]) for r in rows}):
        found = {r["setting"]: r for r in rows
                 if r["preset"] and r["mu"] == mu and r["method"] == method}
        for coarse, fine in (("draft", "default"), ("default", "fine")):
            if coarse not in found or fine not in found:
                continue
            a, b = found[coarse], found[fine]
            ratio = a["h_surface"] / b["h_surface"]
            orders.append({"mu": mu, "method": method, "between": f"{coarse}-{fine}",
                           "h_ratio": ratio, **{
                               k: (float(np.log(a["error"][k] / b["error"][k]) / np.log(ratio))
                                   if ratio >= ORDER_MIN_RATIO and a["error"][k]
                                   and b["error"][k] else None) for k in KEYS}})
    return orders


def _gw(quick):
    """F̄max of the paper's law at μ = 1, ω = 1 (σ = 1 nm-like) per quadrature sample count,
    relative error against GW_REFERENCE_SAMPLES, and wall time."""
    from gw.integrate import strength
    from gw.laws import PaperLaw
    from gw.surface import RoughSurface

    law, surface = PaperLaw(1.0), RoughSurface(zeta=1.0, omega=1.0)
    reference = strength(law, surface, samples=GW_REFERENCE_SAMPLES).f_max
    rows = []
    for samples in GW_SAMPLES[-1:] if quick else GW_SAMPLES:
        start = time.perf_counter()
        f_max = strength(law, surface, samples=samples).f_max
        rows.append({"samples": samples, "wall_s": time.perf_counter() - start,
                     "error_f_max": abs(f_max - reference) / reference})
    return rows


def derjaguin():
    """Relative difference of each event between the exact sphere (R/ε) and Derjaguin's
    parabola, per R/ε, and the log-log slope of the P̄off difference against R/ε (−1: the
    difference falls like ε/R)."""
    import warnings

    from fem_asperity.plumbing.errors import DerjaguinWarning

    def events(radius_ratio):
        with warnings.catch_warnings():  # R/ε < 300 is what is measured here
            warnings.simplefilter("ignore", DerjaguinWarning)
            return solve_curve(1.0, method="bem", accuracy="draft", error_estimate=False,
                               radius_ratio=radius_ratio).events.records()

    parabola = events(None)
    rows = [{"radius_ratio": r, "difference": _errors(events(r), parabola)}
            for r in DERJAGUIN_RATIOS]
    fit = [(np.log(r["radius_ratio"]), np.log(r["difference"]["p_off"])) for r in rows
           if r["radius_ratio"] >= DERJAGUIN_FIT_FROM and r["difference"]["p_off"]]
    slope = float(np.polyfit(*zip(*fit), 1)[0])
    return {"mu": 1.0, "rows": rows, "slope_p_off": slope}


def pareto(points):
    """Indices of the points (wall, error) no other point beats in both (lower is better)."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], np.inf
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def run(*, quick=False, mus=None, step=print):
    """The study's data: {'rows', 'references', 'orders', 'gw', 'wall_s'}; `mus` replaces
    STUDY_MUS (or QUICK_MUS)."""
    start = time.perf_counter()
    rows, references = [], []
    for mu in mus or (QUICK_MUS if quick else STUDY_MUS):
        reference, about = _reference(mu, step)
        references.append({"mu": mu, **about})
        for method in ("bem", "fem"):
            if method == "fem" and mu > FE_MU_MAX:
                continue
            presets = QUICK_PRESETS if quick else tuple(PRESETS)
            if method == "fem" and mu > FE_FINE_MU_MAX:
                presets = tuple(p for p in presets if p != "fine")
            rows += _presets(mu, method, presets, reference, about["uncertainty"], step)
            rows += _settings(mu, method, reference, quick, step)
    step("GW quadrature; the exact sphere against Derjaguin")
    return {"rows": rows, "references": references, "orders": _orders(rows), "gw": _gw(quick),
            "derjaguin": derjaguin(), "wall_s": time.perf_counter() - start}


def _fmt(x):
    return "-" if x is None else f"{x:.1e}"


def markdown(study, header):
    """The study's tables as Markdown lines, below `header` (provenance lines)."""
    lines = [*header, "",
             "## Error against wall time", "",
             "Relative error of each event against the reference, and the wall time of one curve; "
             "for the presets also with their error estimate. The other settings: one curve at "
             "`default` with one setting changed.", "",
             "| mu | method | setting | h | folds | wall s | with estimate s | "
             + " | ".join(KEYS) + " |", "|---" * (7 + len(KEYS)) + "|"]
    for r in study["rows"]:
        with_estimate = r.get("wall_with_estimate_s")
        lines.append(f"| {r['mu']:g} | {r['method']} | {r['setting']} | {r['h_surface']:.3g} | "
                     f"{r['folds']} | {r['wall_s']:.1f} | "
                     f"{'-' if with_estimate is None else f'{with_estimate:.1f}'} | "
                     + " | ".join(_fmt(r["error"][k]) for k in KEYS) + " |")
    lines += ["", "## Error estimate over true error (presets)", "",
              "Between 1 and 10: the estimate bounds the error without overstating it more than "
              "tenfold. Below 1: it missed. '-': the error is below "
              f"{RESOLVED:g} times the reference's uncertainty (or the event is missing). "
              "Estimated by: 'finer', the preset's finer discretisation; 'bem', the FE against the "
              "boundary integral's curve at the same preset plus that curve's estimate.", "",
              "| mu | method | preset | estimated by | " + " | ".join(KEYS) + " |",
              "|---" * (4 + len(KEYS)) + "|"]
    for r in study["rows"]:
        if r["preset"]:
            ratio = r["estimate_over_error"]
            lines.append(f"| {r['mu']:g} | {r['method']} | {r['setting']} | "
                         f"{r['estimated_by']} | "
                         + " | ".join("-" if ratio[k] is None else f"{ratio[k]:.2g}"
                                      for k in KEYS) + " |")
    lines += ["", "## Observed order in the element size (consecutive presets)", "",
              "log(error ratio)/log(h ratio); '-' where the h ratio is below "
              f"{ORDER_MIN_RATIO:g} (the ripple cap: the presets differ in the turn limit only).",
              "", "| mu | method | presets | h ratio | " + " | ".join(KEYS) + " |",
              "|---" * (4 + len(KEYS)) + "|"]
    for o in study["orders"]:
        lines.append(f"| {o['mu']:g} | {o['method']} | {o['between']} | {o['h_ratio']:.2f} | "
                     + " | ".join("-" if o[k] is None else f"{o[k]:.1f}" for k in KEYS) + " |")
    lines += ["", "## References", "",
              "Uncertainty: the relative difference of the BEM `fine` from the reference.", "",
              "| mu | wall s | " + " | ".join(KEYS) + " |", "|---" * (2 + len(KEYS)) + "|"]
    for ref in study["references"]:
        lines.append(f"| {ref['mu']:g} | {ref['wall_s']:.1f} | "
                     + " | ".join(_fmt(ref["uncertainty"][k]) for k in KEYS) + " |")
    lines += ["", "## GW quadrature (F̄max, paper's law, μ = 1, ω = ζ = 1)", "",
              "| samples | wall s | relative error |", "|---|---|---|"]
    lines += [f"| {g['samples']} | {g['wall_s']:.3f} | {_fmt(g['error_f_max'])} |"
              for g in study["gw"]]
    sphere = study["derjaguin"]
    lines += ["", "## The exact sphere against Derjaguin's parabola (μ = 1, BEM draft)", "",
              "Relative difference of each event; the P̄off difference falls like "
              f"(R/ε)^{sphere['slope_p_off']:.3f} from R/ε = {DERJAGUIN_FIT_FROM:g} on.", "",
              "| R/ε | " + " | ".join(KEYS) + " |", "|---" * (1 + len(KEYS)) + "|"]
    lines += [f"| {r['radius_ratio']:g} | " + " | ".join(_fmt(r["difference"][k]) for k in KEYS)
              + " |" for r in sphere["rows"]]
    return lines


def figure(study):
    """Error of P̄off and δ̄oc against the wall time of one curve (no estimate), log-log, per μ:
    the Pareto front as a line, the presets as filled markers, the other settings open."""
    from matplotlib.figure import Figure
    from matplotlib.ticker import NullFormatter

    mus = sorted({r["mu"] for r in study["rows"]})
    fig = Figure(figsize=(4.2 * len(mus), 7.0), layout="constrained")
    axes = fig.subplots(2, len(mus), squeeze=False)
    for col, mu in enumerate(mus):
        for row, key in enumerate(("p_off", "delta_oc")):
            ax = axes[row][col]
            rows = [r for r in study["rows"] if r["mu"] == mu and r["error"][key]]
            for method, colour in (("bem", "tab:blue"), ("fem", "tab:orange")):
                for r in rows:
                    if r["method"] == method:
                        ax.loglog(r["wall_s"], r["error"][key], "o", color=colour,
                                  fillstyle="full" if r["preset"] else "none")
                        if r["preset"]:
                            ax.annotate(f"{method} {r['setting']}", (r["wall_s"], r["error"][key]),
                                        fontsize=7, xytext=(3, 3), textcoords="offset points")
            points = [(r["wall_s"], r["error"][key]) for r in rows]
            front = sorted(points[i] for i in pareto(points))
            if front:
                ax.loglog(*zip(*front), "k--", lw=0.8, label="Pareto front")
                ax.legend(fontsize=7)
            ax.xaxis.set_minor_formatter(NullFormatter())  # minor labels overlap on short axes
            ax.set_xlabel("wall time of one curve [s]")
            ax.set_ylabel(f"relative error of {key}")
            ax.set_title(f"μ = {mu:g}")
    fig.suptitle("Speed against accuracy: one curve per setting (filled: the presets; open: "
                 "one setting changed at default; blue BEM, orange FE)")
    return fig
