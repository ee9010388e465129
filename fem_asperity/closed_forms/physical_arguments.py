"""The physical inputs of every command line, one vocabulary (`python -m fem_asperity ...` and
`python -m gw ...`): E* directly (--E-star) or the two bodies' moduli and Poisson's ratios
(--E1 --nu1 [--E2 --nu2], body 2 rigid when left out), the work of adhesion (--dgamma), the
equilibrium spacing (--eps) and the radius (--R), all SI. gw's earlier spellings --estar,
--work-of-adhesion and --radius stay as aliases.

`add_physical_arguments` puts them on a parser; `physical_scales` turns the parsed values into
`Scales` (None when none is given), with one clear usage error for a missing or a conflicting
input. With `several=True` (a sweep) every option takes one or more values: options with several
values must have the same number of them, and the others are held fixed.
"""

from .scales import Scales, effective_modulus

#: Option → (attribute, help). Help says the unit; aliases keep gw's earlier spellings.
_OPTIONS = {
    ("--E-star", "--estar"): ("E_star", "effective modulus E* [Pa] (or --E1 --nu1 [--E2 --nu2])"),
    ("--E1",): ("E1", "Young's modulus of the half-space [Pa]"),
    ("--nu1",): ("nu1", "Poisson's ratio of the half-space"),
    ("--E2",): ("E2", "Young's modulus of the sphere [Pa] (omit with --nu2: rigid)"),
    ("--nu2",): ("nu2", "Poisson's ratio of the sphere"),
    ("--dgamma", "--work-of-adhesion"): ("dgamma", "work of adhesion [J/m^2]"),
    ("--eps",): ("eps", "Lennard-Jones equilibrium spacing [m]"),
    ("--R", "--radius"): ("R", "radius of curvature of the sphere (asperity) [m]"),
}
NAMES = tuple(attr for attr, _ in _OPTIONS.values())
USAGE = "--E-star (or --E1 --nu1 [--E2 --nu2]), --dgamma, --eps and --R"


def add_physical_arguments(parser, *, several=False):
    """Add the physical options to `parser` (an argparse parser or group); with `several`,
    each takes one or more values."""
    for flags, (attr, text) in _OPTIONS.items():
        parser.add_argument(*flags, dest=attr, type=float, nargs="+" if several else None,
                            help=text + (" (one or more values)" if several else ""))


def physical_given(args):
    """Whether any physical option was given."""
    return any(getattr(args, name, None) is not None for name in NAMES)


def physical_scales(args, error, command, *, several=False):
    """`Scales` of the parsed physical options, None when none is given. With `several`, a list
    of `Scales` (options with several values are zipped, the others held fixed). `error(text)`
    reports a usage error (argparse's `parser.error`); `command` names the command in it."""
    if not physical_given(args):
        return None
    values = {name: getattr(args, name, None) for name in NAMES}
    lists = {k: (v if several or v is None else [v]) for k, v in values.items()}
    counts = {len(v) for v in lists.values() if v is not None and len(v) > 1}
    if len(counts) > 1:
        error(f"{command}: options with several values need the same number of them")
    n = counts.pop() if counts else 1
    rows = [{k: (None if v is None else v[i if len(v) > 1 else 0]) for k, v in lists.items()}
            for i in range(n)]
    scales = [_one(row, error, command) for row in rows]
    return scales if several else scales[0]


def _one(row, error, command):
    bodies = [row[k] for k in ("E1", "nu1", "E2", "nu2")]
    if (row["E_star"] is None) == (row["E1"] is None):
        error(f"{command}: give --E-star or --E1 --nu1 [--E2 --nu2], one of the two")
    if row["E_star"] is not None and any(v is not None for v in bodies):
        error(f"{command}: --E-star and --E1/--nu1/--E2/--nu2 are alternatives")
    if row["E1"] is not None and row["nu1"] is None:
        error(f"{command}: --E1 needs --nu1")
    missing = [f"--{k}" for k in ("dgamma", "eps", "R") if row[k] is None]
    if missing:
        error(f"{command}: the physical inputs need {USAGE}; missing {', '.join(missing)}")
    E_star = row["E_star"]
    if E_star is None:
        E_star = effective_modulus(E1=row["E1"], nu1=row["nu1"], E2=row["E2"], nu2=row["nu2"])
    return Scales(E_star=E_star, dgamma=row["dgamma"], eps=row["eps"], R=row["R"])


def scale_record(scales):
    """The scales of a physical input, SI, with its inputs E* [Pa], Δγ [J/m²], ε and R [m], μ
    and R/ε (for JSON and tables)."""
    return {"mu": scales.mu, "R_over_eps": scales.R / scales.eps, "E_star": scales.E_star,
            "dgamma": scales.dgamma, "eps": scales.eps, "R": scales.R,
            "force": scales.force, "length_z": scales.length_z, "length_r": scales.length_r}
