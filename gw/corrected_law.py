"""The corrected closed form (`fem_asperity.closed_forms.corrected`) measured against the table of
solved laws: its F̄max error on GW surfaces at every table node and held-out μ over the table's ζ,
and the fit of its constants (`python -m gw corrected-law [--fit]`).

The measured errors ship as package data (ERROR_FILE); `stated_error(mu)` reads the largest one
at the measured μ around mu, as the table's own error is stated.
"""

import functools
import json
from dataclasses import astuple, fields
from datetime import datetime, timezone
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares

from fem_asperity.closed_forms.corrected import CORRECTED_LAWS, CorrectedLaws
from fem_asperity.plumbing.errors import InputError
from fem_asperity.plumbing.files import write_atomic
from fem_asperity.plumbing.provenance import git_commit

from .integrate import strength
from .law_table import ZETAS, shipped_table
from .laws import CorrectedLaw, PaperLaw
from .surface import RoughSurface

#: The shipped measurement of the corrected law's F̄max error.
ERROR_FILE = Path(__file__).with_name("data") / "corrected_law_error.json"
#: The fit's sample of the table (every FIT_STEP-th node) and the weight of P̄(δ̄o) beside F̄max
#: (methods.md §14). Not pinned by a test; docs/corrected_law.md has the errors.
FIT_STEP, CURVE_WEIGHT = 3, 0.3
#: The weight of log(δ̄J/δ̄o of the solved jump-in) at the fit's nodes that jump: without it
#: the fit left δ̄J 21 % out at μ = 50, where F̄max barely depends on it (methods.md §14).
JUMP_WEIGHT = 1.0
#: Points of the solved approach each fit curve is compared at, from its deepest δ̄o to three
#: times its jump (or δ̄o*), leaving out 0.05 (1 + √μ) on either side of the jump.
CURVE_POINTS = 40
#: Relative step of the central differences behind the constants' 95 % intervals: wide enough
#: to step over the residuals' small jumps, small beside the intervals it gives.
INTERVAL_STEP = 1e-3


def measured_mus(table=None):
    """(μ, held out?) of the measurement: the table's nodes and its held-out μ, increasing."""
    table = table or shipped_table()
    mus = [(float(m), False) for m in table.mus]
    mus += [(float(e["held_out"]), True) for e in table.errors]
    return sorted(mus)


def _f_max(law, zetas=ZETAS):
    """F̄max of `law` on GW surfaces (ω = 1) at each ζ."""
    return np.array([strength(law, RoughSurface(zeta=float(z))).f_max for z in zetas])


def f_max_errors(mu, constants=CORRECTED_LAWS, table=None, solved=None):
    """Relative F̄max errors of the corrected law at `mu` against the table's law, one per ζ of
    ZETAS (`solved`: the table's F̄max there, if known)."""
    solved = _f_max((table or shipped_table()).law(mu)) if solved is None else solved
    return list(_f_max(CorrectedLaw(mu, constants)) / solved - 1.0)


def measure(constants=CORRECTED_LAWS, table=None, progress=None):
    """The error table: one row per measured μ (`measured_mus`) with its errors per ζ."""
    table = table or shipped_table()
    rows, mus = [], measured_mus(table)
    for k, (mu, held_out) in enumerate(mus):
        solved = _f_max(table.law(mu))
        errors = f_max_errors(mu, constants, solved=solved)
        paper = _f_max(PaperLaw(mu)) / solved - 1.0
        rows.append({"mu": mu, "held_out": held_out, "f_max": errors,
                     "largest": max(abs(e) for e in errors),
                     "paper_largest": max(abs(e) for e in paper)})
        if progress:
            progress((k + 1) / len(mus))
    return rows


def _fit_samples(table):
    """(μ, solved F̄max per ζ, δ̄o samples, solved P̄ there, δ̄o of the jump-in or None) of the
    fit's nodes."""
    samples = []
    for k in range(0, len(table.mus), FIT_STEP):
        e, law = table.entries[k], table.law(table.mus[k])
        top = e.jump_in or e.delta_o_star
        d = np.linspace(min(e.approach.delta), 3.0 * top, CURVE_POINTS)
        if e.jump_in is not None:
            d = d[np.abs(d - e.jump_in) > 0.05 * (1.0 + np.sqrt(e.mu))]
        samples.append((e.mu, _f_max(law), d, law.force(d), e.jump_in))
    return samples


def _residuals(table, samples, c_off, progress=None):
    """The fit's residuals as a function of (a, b, c, q): log F̄max ratios over ZETAS,
    CURVE_WEIGHT (P̄ − P̄solved)/√n over each sampled curve, and JUMP_WEIGHT log(δ̄J/jump-in)
    where the solved curve jumps."""
    calls = [0]

    def residuals(x):
        constants = CorrectedLaws(*x, c_off=c_off)
        out = []
        for mu, f_max, d, p, jump in samples:
            law = CorrectedLaw(mu, constants)
            out += [np.log(_f_max(law) / f_max),
                    CURVE_WEIGHT * (law.force(d) - p) / np.sqrt(len(d))]
            if jump is not None:
                out.append([JUMP_WEIGHT * np.log(law.delta_jump / jump)])
        calls[0] += 1
        if progress:
            progress(min(calls[0] / 40.0, 0.99))
        return np.concatenate(out)

    return residuals


def _fitted_names():
    return [f.name for f in fields(CorrectedLaws) if f.name != "c_off"]


def fit(table=None, start=CORRECTED_LAWS, progress=None):
    """The constants a, b, c, q (c_off stays Wu's) that fit the table best (least squares of
    `_residuals`, from `start`)."""
    table = table or shipped_table()
    residuals = _residuals(table, _fit_samples(table), start.c_off, progress)
    result = least_squares(residuals, astuple(start)[:len(_fitted_names())], x_scale=0.1,
                           diff_step=INTERVAL_STEP)  # as `intervals`: over the residuals' jumps
    if not result.success:
        raise InputError(f"the corrected law's fit did not converge: {result.message}")
    return CorrectedLaws(*(float(v) for v in result.x), c_off=start.c_off)


def intervals(constants=CORRECTED_LAWS, table=None, progress=None):
    """95 % intervals {name: (lo, hi)} of the fitted constants at `constants`, from the
    residuals' Jacobian. Central differences at INTERVAL_STEP: the residuals jump where a sample
    crosses δ̄J, so steps of ~1e-8 (least_squares' own) read those jumps as slopes of ~1e8 and
    give intervals of ~1e-8."""
    table = table or shipped_table()
    names = _fitted_names()
    x = np.array([getattr(constants, n) for n in names])
    residuals = _residuals(table, _fit_samples(table), constants.c_off,
                           progress and (lambda f: progress(min(f * 40.0 / 9.0, 1.0))))
    jacobian = np.column_stack([
        (residuals(x + h) - residuals(x - h)) / (2.0 * h[i])
        for i, h in enumerate(np.diag(INTERVAL_STEP * np.abs(x)))])
    fun = residuals(x)
    covariance = (np.linalg.pinv(jacobian.T @ jacobian) * (fun @ fun)
                  / max(fun.size - len(names), 1))
    half = 1.96 * np.sqrt(np.diag(covariance))
    return {n: (float(v - h), float(v + h)) for n, v, h in zip(names, x, half)}


def save_errors(path, rows, constants, record):
    """Write the measured errors, the constants they belong to and the record (JSON, whole or
    not at all)."""
    data = {"constants": dict(zip([f.name for f in fields(CorrectedLaws)], astuple(constants))),
            "zetas": [float(z) for z in ZETAS], "rows": rows, "record": record}
    write_atomic(path, json.dumps(data, indent=1) + "\n")


@functools.cache
def shipped_errors():
    """The shipped measurement (read once per process)."""
    return json.loads(ERROR_FILE.read_text())


def stated_error(mu):
    """The corrected law's relative F̄max error stated at `mu`: the largest measured at the
    measured μ from the one below mu's neighbour to the one above its other neighbour (None
    outside the measured range)."""
    rows = shipped_errors()["rows"]
    mus = np.array([r["mu"] for r in rows])
    if not mus[0] <= mu <= mus[-1]:
        return None
    i = int(np.clip(np.searchsorted(mus, mu, side="right") - 1, 0, len(mus) - 2))
    return max(r["largest"] for r in rows[max(i - 1, 0):i + 3])


def record(command):
    """How a measurement was made: the constants' source, the table's solver revision, the
    command, the commit and the date."""
    return {"table_solver_revision": shipped_table().record.get("solver_revision"),
            "command": command, "commit": git_commit(Path(__file__).parent) or "unknown",
            "date": datetime.now(timezone.utc).isoformat(timespec="seconds")}


def report(rows, constants, bounds=None, recorded=None):
    """docs/corrected_law.md: the form, its constants and the measured error table."""
    names = [f.name for f in fields(CorrectedLaws)]
    largest = max(rows, key=lambda r: r["largest"])
    held = [r for r in rows if r["held_out"]]
    lines = [
        "# The corrected closed-form asperity law",
        "",
        "Written by `python -m gw corrected-law --report docs/corrected_law.md`"
        + (f" at commit {recorded['commit']} on {recorded['date']}" if recorded else "")
        + ". The form is in `fem_asperity/closed_forms/corrected.py` (its docstring has the "
        "equations); `python -m gw fmax --law corrected` uses it.",
        "",
        "## The form (units: δ̄o in ε, P̄ in 2πRΔγ, Ā in εR)",
        "",
        "- δ̄o > δ̄J(μ): Bradley, P̄ = (δ̄o⁻⁸ − 4δ̄o⁻²)/3.",
        "- below: parametric in s ≥ s_t = (√(2π)/4)^(2/3),",
        "  P̄(s) = P̄off(μ) + 2s³/(3π) − √(2/π) s^(3/2) + 3/4,",
        "  δ̄o(s) = δ̄m(μ) + [x̄_B(min(P̄, 0)) − 1] − μ [s² − √(2πs) − u_m],",
        "  Ā(s) = π μ [s² − √(π/2) √s], 0 below s³ = π/2 (the JKR contact's compressive zone),",
        "  with P̄off = −(1/8)[7 + (1 − c_off μ^1.5)/(1 + c_off μ^1.5)] (Wu, the paper's eq. 2), "
        "x̄_B(P̄) ≤ 1 solving x̄⁻⁸ − 4x̄⁻² = 3P̄ (Bradley's wall, on the tensile side only: "
        "under compression it stays at x̄_B(0) = 4^(−1/6)), u_m = −0.77342.",
        "- δ̄J = 1 + a μ^b, δ̄m = δ̄J + 0.77342 μ − c μ^q; the approach leaves Bradley's curve "
        "at δ̄J, or at the top of the s-branch where that is deeper.",
        "",
        "| constant | value | 95 % interval |",
        "|---|---|---|",
    ]
    for n in names:
        value = getattr(constants, n)
        ci = bounds.get(n) if bounds else None
        lines.append(f"| {n} | {value:.4g} | "
                     + (f"{ci[0]:.4g} to {ci[1]:.4g} |" if ci else "Wu's (the paper's) |"))
    lines += [
        "",
        "## Its F̄max error against the table of solved laws",
        "",
        "Relative error of F̄max on GW surfaces (ω = 1) at ζ = "
        + ", ".join(f"{z:g}" for z in ZETAS)
        + f", at the table's {len(rows) - len(held)} nodes and {len(held)} held-out μ "
        "(held out: not used to build the table; the fit used every third node). "
        f"Largest: {largest['largest']:.3g} at μ = {largest['mu']:.4g}; "
        f"{sum(r['largest'] <= 0.02 for r in rows)} of {len(rows)} μ within 2 %, "
        f"{sum(r['largest'] <= 0.05 for r in rows)} within 5 %. The paper's law, on the same "
        f"surfaces: largest {max(r['paper_largest'] for r in rows):.3g}, "
        f"{sum(r['paper_largest'] <= 0.05 for r in rows)} of {len(rows)} μ within 5 % (its "
        "largest error per μ is the last column). The table's own error is in "
        "docs/law_table.md.",
        "",
        "| μ | held out | " + " | ".join(f"ζ = {z:.3g}" for z in ZETAS)
        + " | largest | paper's largest |",
        "|---|---|" + "---|" * (len(ZETAS) + 2),
    ]
    for r in rows:
        lines.append(f"| {r['mu']:.4g} | {'yes' if r['held_out'] else ''} | "
                     + " | ".join(f"{e:+.3f}" for e in r["f_max"])
                     + f" | {r['largest']:.3f} | {r['paper_largest']:.3f} |")
    return "\n".join(lines) + "\n"
