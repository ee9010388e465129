"""Files of one curve: CSV curves, a force/contact figure, under load-line control the
cantilever's deflection against the piezo position, and (FE) VTU + PNG fields at chosen states.

Field units: coordinates r, z in √(Rε); displacement in ε; σ_zz in Δγ/ε (the LJ traction unit,
so σ_zz ≈ −p̄ on the surface). `write_all` writes all files or none (a staging folder).
"""

from pathlib import Path

import numpy as np

from ..closed_forms.lj import traction
from ..plumbing.files import atomic_path, save_figure, staged_folder
from .result import write_curves


def plot_curve(result, path):
    """Two panels, P̄ and ā_c vs δ̄o: equilibrium curve (unstable dashed), approach, retraction."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10, 4), layout="constrained")
    axes = fig.subplots(1, 2)
    eq = result.equilibrium
    for ax, column, label in zip(axes, ("p", "a_c"), ("P̄ = P/(2πRΔγ)", "ā_c = a_c/√(εR)")):
        values = getattr(eq, column)
        if not eq.stable.all():
            ax.plot(eq.delta, np.where(eq.stable, np.nan, values), "k--", lw=1, label="unstable")
        ax.plot(result.approach.delta, getattr(result.approach, column), "-", color="tab:blue",
                lw=1.5, label="approach")
        ax.plot(result.retraction.delta, getattr(result.retraction, column), "-",
                color="tab:red", lw=1, label="retraction")
        ax.set_xlabel("δ̄o = δo/ε")
        ax.set_ylabel(label)
        ax.set_xlim(min(eq.delta), min(max(eq.delta), 10.0))
        ax.grid(alpha=0.3)
    axes[0].set_ylim(-1.1, max(0.2, min(1.2, float(np.max(eq.p)))))
    axes[0].legend()
    profile = "" if result.radius_ratio is None else f", sphere R/ε = {result.radius_ratio:g}"
    control = ("displacement control" if result.spring_constant is None
               else f"load-line control (k̄ = {result.spring_constant:g})")
    fig.suptitle(f"{result.method.upper()}, μ = {result.mu:g}, accuracy '{result.accuracy}', "
                 f"{result.solid.description()}{profile}, {control}")
    return save_figure(fig, path)


def plot_cantilever(result, path):
    """The curve as an AFM records it under load-line control (`spring_constant` k̄): the
    cantilever's deflection −P̄/k̄ against the spring end's (piezo) position z̄ = δ̄o − P̄/k̄, both
    in ε, approach and retraction, the jumps as horizontal segments at fixed z̄."""
    from matplotlib.figure import Figure

    k = result.spring_constant
    fig = Figure(figsize=(6, 4.5), layout="constrained")
    ax = fig.subplots()
    for name, colour in (("approach", "tab:blue"), ("retraction", "tab:red")):
        curve = getattr(result, name)
        ax.plot(curve.delta - curve.p / k, -curve.p / k, "-", color=colour, label=name)
    ax.set_xlabel("piezo position z̄ = z/ε (spring end)")
    ax.set_ylabel("cantilever deflection z̄ − δ̄o = −P̄/k̄ (ε); > 0: bent toward the surface")
    ax.set_xlim(None, 10.0)
    ax.grid(alpha=0.3)
    ax.legend()
    ax.set_title(f"{result.method.upper()}, μ = {result.mu:g}, k̄ = Kε/(2πRΔγ) = {k:g}, "
                 f"load-line control")
    return save_figure(fig, path)


def state_index(curve, delta, p):
    """Index of the equilibrium-curve point nearest to (δ̄o, P̄)."""
    return int(np.argmin(np.hypot(curve.delta - delta, curve.p - p)))


def state_fields(result, index):
    """(mesh, nodal displacement (n_vertices × 2, in ε), σ_zz per element (Δγ/ε)) at curve point
    `index` of `result.equilibrium`."""
    model = result.model
    surface, half_space = model.surface, model.half_space
    w, delta = model.trace.states[index], result.equilibrium.delta[index]
    pressure = surface.load_factor * traction(surface.gap(w, delta))
    u = half_space.displacement_field(half_space.nodal_load(pressure))
    nodal = u[half_space.basis.nodal_dofs].T
    return half_space.mesh, nodal, half_space.stress_zz(u) / surface.load_factor


def write_fields(result, folder, label, index):
    """fields_<label>.vtu (meshio) and fields_<label>.png (pyvista, off-screen) at curve point
    `index`: deformed surface region near the contact coloured by σ_zz."""
    import meshio

    mesh, nodal, sigma = state_fields(result, index)
    points = np.column_stack([mesh.p.T, np.zeros(mesh.p.shape[1])])
    u3 = np.column_stack([nodal, np.zeros(len(nodal))])
    grid = meshio.Mesh(points, [("triangle", mesh.t.T)], point_data={"u": u3},
                       cell_data={"sigma_zz": [sigma]})
    folder = Path(folder)
    vtu = folder / f"fields_{label}.vtu"
    with atomic_path(vtu) as tmp:
        meshio.write(tmp, grid, file_format="vtu")
    eq = result.equilibrium
    title = f"mu = {result.mu:g}, delta_o = {eq.delta[index]:.4g} eps, P = {eq.p[index]:.4g}"
    png = _render(points, mesh.t, u3, sigma, folder / f"fields_{label}.png", title,
                  window=max(1.5, 2.5 * float(eq.a_c[index])))
    return [vtu, png]


def _render(points, triangles, u3, sigma, path, title, window):
    import pyvista as pv
    from vtkmodules.vtkCommonCore import vtkLogger

    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)
    cells = np.column_stack([np.full(triangles.shape[1], 3), triangles.T]).ravel()
    grid = pv.UnstructuredGrid(cells, np.full(triangles.shape[1], pv.CellType.TRIANGLE), points)
    grid.cell_data["sigma_zz [dgamma/eps]"] = sigma
    shown = float(np.max(np.abs(u3[:, 1]))) or 1.0
    grid.point_data["u"] = u3 * (0.05 * window / shown)
    near = grid.clip_box([0.0, window, -window, 0.0, -1.0, 1.0], invert=False).warp_by_vector("u")
    limit = float(np.max(np.abs(near.cell_data["sigma_zz [dgamma/eps]"]))) or 1.0
    plotter = pv.Plotter(off_screen=True, window_size=(1000, 600))
    bar = dict(vertical=True, position_x=0.86, position_y=0.15, height=0.7, width=0.05,
               title="sigma_zz / (dgamma/eps)")
    plotter.add_mesh(near, scalars="sigma_zz [dgamma/eps]", cmap="RdBu_r", clim=(-limit, limit),
                     scalar_bar_args=bar)
    plotter.add_text(title + f"  (displacement x {0.05 * window / shown:.3g})", font_size=10)
    plotter.view_xy()
    plotter.show_bounds(xtitle="r / sqrt(R eps)", ytitle="z / sqrt(R eps)", location="outer")
    with atomic_path(path) as tmp:
        plotter.screenshot(tmp)
    plotter.close()
    return Path(path)


def write_all(result, folder):
    """Curves, the curve figure and, for the FE (the BEM has no bulk mesh), the fields at P̄max
    (approach) and P̄off (retraction). All or nothing: the files are written into a staging
    folder and moved into `folder` only when every one of them is complete."""
    folder = Path(folder)
    with staged_folder(folder) as stage:
        names = [p.name for p in write_curves(result, stage)]
        names.append(plot_curve(result, stage / "curve.png").name)
        if result.spring_constant is not None:
            names.append(plot_cantilever(result, stage / "cantilever.png").name)
        if result.method == "fem":
            ev, eq = result.events, result.equilibrium
            for label, delta, p in (("p_max", ev.delta_oc, ev.p_max),
                                    ("p_off", ev.delta_off, ev.p_off)):
                names += [p.name for p in write_fields(result, stage, label,
                                                       state_index(eq, delta, p))]
    return [folder / name for name in names]
