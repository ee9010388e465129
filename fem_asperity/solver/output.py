"""Files of one curve: CSV curves, a force/contact figure, under load-line control the
cantilever's deflection against the piezo position, and (FE) VTU + PNG fields at chosen states.

Field units (`field_units`): coordinates and displacements in one length unit, m with physical
inputs or √(Rε) with the exact sphere (a Derjaguin result has no R/ε: displacements stay in ε,
named "u [eps]"); stresses in Pa with physical inputs, else Δγ/ε (the LJ traction unit, so
σ_zz ≈ −p̄ on the surface). `write_all` writes all files or none (a staging folder).
"""

from pathlib import Path

import numpy as np

from ..closed_forms.lj import scaled_traction
from ..plumbing.files import atomic_path, save_figure, staged_folder, write_atomic
from .result import PATH_COLUMNS, SI_PATH_COLUMNS, csv_text, write_curves

#: Who writes a curve's output folder, as its record says (`plumbing.files.staged_folder`).
OWNER = "python -m fem_asperity curve"


def plot_curve(result, path, scales=None):
    """`curve_figure` saved at `path` (PNG)."""
    return save_figure(curve_figure(result, scales), path)


def _branches(ax, curve, column, colour, width, label):
    """`curve`'s `column` against δ̄o, a line per branch, the jumps between them dotted."""
    values = getattr(curve, column)
    starts = np.flatnonzero(np.diff(curve.branch)) + 1
    for k, piece in enumerate(np.split(np.arange(len(curve)), starts)):
        ax.plot(curve.delta[piece], values[piece], "-", color=colour, lw=width,
                label=label if k == 0 else None)
    for i in starts:  # a jump: from the last state of a branch to the first of the next
        ax.plot(curve.delta[[i - 1, i]], values[[i - 1, i]], ":", color=colour, lw=width)


def curve_figure(result, scales=None):
    """Two panels, P̄ and ā_c vs δ̄o: the equilibrium curve (unstable dashed), the approach and
    the retraction, a line per branch and their jumps dotted, P̄max (approach) and the pull-off
    P̄off (retraction) marked. With `scales` (physical inputs) a second pair of axes in nm and
    nN."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10, 4.5), layout="constrained")
    axes = fig.subplots(1, 2)
    eq, ev = result.equilibrium, result.events
    for ax, column, label in zip(axes, ("p", "a_c"), ("P̄ = P/(2πRΔγ)", "ā_c = a_c/√(εR)")):
        values = getattr(eq, column)
        if not eq.stable.all():
            ax.plot(eq.delta, np.where(eq.stable, np.nan, values), "k--", lw=1, label="unstable")
        _branches(ax, result.approach, column, "tab:blue", 1.5, "approach")
        _branches(ax, result.retraction, column, "tab:red", 1.0, "retraction")
        ax.set_xlabel("δ̄o = δo/ε")
        ax.set_ylabel(label)
        ax.set_xlim(min(eq.delta), min(max(eq.delta), 10.0))
        ax.grid(alpha=0.3)
    axes[0].plot([ev.delta_oc], [ev.p_max], "o", mfc="none", color="tab:blue",
                 label=f"P̄max = {ev.p_max:.4g}")
    axes[0].plot([ev.delta_off], [ev.p_off], "s", mfc="none", color="tab:red",
                 label=f"pull-off P̄off = {ev.p_off:.4g}")
    axes[0].set_ylim(-1.1, max(0.2, min(1.2, float(np.max(eq.p)))))
    axes[0].legend(fontsize=8)
    if scales is not None:
        nm, force_nn, radius_nm = scales.length_z * 1e9, scales.force * 1e9, scales.length_r * 1e9
        for ax, unit, scale in ((axes[0], "P [nN]", force_nn), (axes[1], "a_c [nm]", radius_nm)):
            ax.secondary_xaxis("top", functions=(lambda d: d * nm, lambda d: d / nm)).set_xlabel(
                "δo [nm]")
            ax.secondary_yaxis("right", functions=(lambda v, s=scale: v * s,
                                                   lambda v, s=scale: v / s)).set_ylabel(unit)
    profile = "" if result.radius_ratio is None else f", sphere R/ε = {result.radius_ratio:g}"
    control = ("displacement control" if result.spring_constant is None
               else f"load-line control (k̄ = {result.spring_constant:g})")
    fig.suptitle(f"{result.method.upper()}, μ = {result.mu:g}, accuracy '{result.accuracy}', "
                 f"{result.solid.description()}{profile}, {control}")
    return fig


def plot_cantilever(result, path):
    """`cantilever_figure` saved at `path` (PNG)."""
    return save_figure(cantilever_figure(result), path)


def cantilever_figure(result):
    """The curve as an AFM records it under load-line control (`spring_constant` k̄): the
    cantilever's deflection −P̄/k̄ against the spring end's (piezo) position z̄ = δ̄o − P̄/k̄, both
    in ε, approach and retraction, the jumps as horizontal segments at fixed z̄ (dotted lines
    at their z̄; the view covers both)."""
    from matplotlib.figure import Figure

    k = result.spring_constant
    fig = Figure(figsize=(6, 4.5), layout="constrained")
    ax = fig.subplots()
    for name, colour in (("approach", "tab:blue"), ("retraction", "tab:red")):
        curve = getattr(result, name)
        ax.plot(curve.delta - curve.p / k, -curve.p / k, "-", color=colour, label=name)
    ax.set_xlabel("piezo position z̄ = z/ε (spring end)")
    ax.set_ylabel("cantilever deflection z̄ − δ̄o = −P̄/k̄ (ε); > 0: bent toward the surface")
    # the far retraction is a flat line at zero; the view ends a fifth of the span past the
    # farther jump (the snap-out, far out on a soft lever), or at z̄ = 10 without jumps
    jumps = [z for z in (result.z_jumps or {}).values() if z is not None]
    z_left = min(np.min(getattr(result, name).delta - getattr(result, name).p / k)
                 for name in ("approach", "retraction"))
    right = max(jumps) + 0.2 * (max(jumps) - z_left) if jumps else 10.0
    ax.set_xlim(None, right)
    for z in jumps:
        ax.axvline(z, color="0.6", lw=0.8, ls=":")
    ax.grid(alpha=0.3)
    ax.legend()
    ax.set_title(f"{result.method.upper()}, μ = {result.mu:g}, k̄ = Kε/(2πRΔγ) = {k:g}, "
                 f"load-line control")
    return fig


def state_index(curve, delta, p):
    """Index of the equilibrium-curve point nearest to (δ̄o, P̄)."""
    return int(np.argmin(np.hypot(curve.delta - delta, curve.p - p)))


def state_fields(result, index):
    """(mesh, nodal displacement (n_vertices × 2: u_r, u_z, in ε), stress per element
    (n_elements × 4: σ_rr, σ_zz, σ_θθ, σ_rz, in Δγ/ε)) at curve point `index` of
    `result.equilibrium`."""
    model = result.model
    surface, half_space = model.surface, model.half_space
    delta = result.equilibrium.delta[index]
    # the state on the half-space's surface nodes (from a grid that followed the edge: linear
    # between its nodes, as on that grid); the quadrature points are the half-space's on either
    w = np.interp(half_space.r_nodes, model.trace.nodes[index], model.trace.states[index])
    gap = delta + surface.profile - half_space.interp @ w
    pressure = surface.load_factor * scaled_traction(gap)  # inf gap: 0
    u = half_space.displacement_field(half_space.nodal_load(pressure))
    nodal = u[half_space.basis.nodal_dofs].T
    return half_space.mesh, nodal, half_space.stress(u) / surface.load_factor


def field_units(result, scales=None):
    """(unit, coordinate factor, displacement factor): the one length unit of a VTU's
    coordinates and displacements and the factors that bring coordinates (in √(Rε)) and
    displacements (in ε) to it: m with physical inputs, √(Rε) where R/ε is known (the exact
    sphere). None for a Derjaguin result: it has no R/ε, so its displacements stay in ε."""
    if scales is not None:
        return "m", scales.length_r, scales.length_z
    if result.radius_ratio is not None:
        return "sqrt(R eps)", 1.0, 1.0 / np.sqrt(result.radius_ratio)
    return None


def write_fields(result, folder, label, index, scales=None):
    """fields_<label>.vtu and fields_<label>.png (pyvista, off-screen) at curve point `index`:
    the deformed region near the contact coloured by σ_zz.

    The VTU's arrays carry their unit in their name. It holds the displacement "u [unit]" in
    the coordinates' own unit (`field_units`: m with physical inputs, √(Rε) with the exact
    sphere; a Derjaguin result, which has no R/ε, holds "u [eps]"), the stress tensor
    (sigma_rr, sigma_zz, sigma_tt, sigma_rz; Pa with physical inputs, else Δγ/ε), the material
    (0 substrate, 1 layer), and as field data the state (mu, delta_o, p)."""
    import pyvista as pv

    mesh, nodal, stress = state_fields(result, index)
    eq = result.equilibrium
    units = field_units(result, scales)
    length = units[1] if units else 1.0
    points = np.column_stack([mesh.p.T * length, np.zeros(mesh.p.shape[1])])
    u3 = np.column_stack([nodal * (units[2] if units else 1.0), np.zeros(len(nodal))])
    cells = np.column_stack([np.full(mesh.t.shape[1], 3), mesh.t.T]).ravel()
    grid = pv.UnstructuredGrid(cells, np.full(mesh.t.shape[1], pv.CellType.TRIANGLE), points)
    length_unit = units[0] if units else "sqrt(R eps)"
    grid.point_data[f"u [{length_unit if units else 'eps'}]"] = u3
    stress_unit = "Pa" if scales is not None else "dgamma/eps"
    stress = stress * (scales.traction if scales is not None else 1.0)
    for column, name in enumerate(("sigma_rr", "sigma_zz", "sigma_tt", "sigma_rz")):
        grid.cell_data[f"{name} [{stress_unit}]"] = stress[:, column]
    grid.cell_data["material (0 substrate, 1 layer)"] = (
        result.model.half_space.in_layer.astype(np.int32))
    grid.field_data.update({"mu": [result.mu], "delta_o [eps]": [float(eq.delta[index])],
                            "p [2 pi R dgamma]": [float(eq.p[index])]})
    folder = Path(folder)
    vtu = folder / f"fields_{label}.vtu"
    with atomic_path(vtu) as tmp:
        grid.save(tmp)
    title = f"mu = {result.mu:g}, delta_o = {eq.delta[index]:.4g} eps, P = {eq.p[index]:.4g}"
    window = max(1.5, 2.5 * float(eq.a_c[index])) * length
    png = _render(grid, folder / f"fields_{label}.png", title, window, stress_unit,
                  length_unit)
    return [vtu, png]


def _render(grid, path, title, window, stress_unit, length_unit):
    import pyvista as pv
    from vtkmodules.vtkCommonCore import vtkLogger

    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)
    grid = grid.copy()
    u = next(grid.point_data[name] for name in grid.point_data if name.startswith("u ["))
    if length_unit == "m":  # axis ticks in nm, not 0.0
        grid.points, u = grid.points * 1e9, u * 1e9
        window, length_unit = window * 1e9, "nm"
    shown = float(np.max(np.abs(u[:, 1]))) or 1.0
    grid.point_data["shown"] = u * (0.05 * window / shown)  # a visible warp, its factor printed
    near = grid.clip_box([0.0, window, -window, 0.0, -1.0, 1.0],
                         invert=False).warp_by_vector("shown")
    sigma_zz = f"sigma_zz [{stress_unit}]"
    limit = float(np.max(np.abs(near.cell_data[sigma_zz]))) or 1.0
    plotter = pv.Plotter(off_screen=True, window_size=(1000, 600))
    bar = dict(vertical=True, position_x=0.86, position_y=0.15, height=0.7, width=0.05,
               title=f"sigma_zz [{stress_unit}]")
    plotter.add_mesh(near, scalars=sigma_zz, cmap="RdBu_r", clim=(-limit, limit),
                     scalar_bar_args=bar)
    plotter.add_text(title + f"  (displacement x {0.05 * window / shown:.3g})", font_size=10)
    plotter.view_xy()
    plotter.show_bounds(xtitle=f"r [{length_unit}]", ytitle=f"z [{length_unit}]",
                        location="outer")
    with atomic_path(path) as tmp:
        plotter.screenshot(tmp)
    plotter.close()
    return Path(path)


def write_all(result, folder, scales=None):
    """Curves, the curve figure and, for the FE (the BEM has no bulk mesh), the fields at P̄max
    (approach) and P̄off (retraction). With `scales` (physical inputs): result.json's SI block
    (`result.records(scales)`, as the command line prints it), paths_si.csv (both paths in SI,
    `result.path_rows`), the figure's second axes in nm and nN, the fields in SI. All or
    nothing: the files are written into a staging folder and moved into `folder` only when
    every one of them is complete. `folder` is new, empty or an earlier curve's (`OWNER`);
    files in it that a curve did not write stay, and a folder holding other files is
    refused."""
    folder = Path(folder)
    with staged_folder(folder, owner=OWNER) as stage:
        names = [p.name for p in write_curves(result, stage, scales)]
        if scales is not None:
            names.append(write_atomic(stage / "paths_si.csv", csv_text(
                result.path_rows(scales), [*PATH_COLUMNS, *SI_PATH_COLUMNS])).name)
        names.append(plot_curve(result, stage / "curve.png", scales).name)
        if result.spring_constant is not None:
            names.append(plot_cantilever(result, stage / "cantilever.png").name)
        if result.method == "fem":
            ev, eq = result.events, result.equilibrium
            for label, delta, p in (("p_max", ev.delta_oc, ev.p_max),
                                    ("p_off", ev.delta_off, ev.p_off)):
                names += [p.name for p in write_fields(result, stage, label,
                                                       state_index(eq, delta, p), scales)]
    return [folder / name for name in names]
