"""An independent engine for the explicit rough-surface problem: ContactMechanics + Adhesion.

A cross-check only: the same problem (a rigid height map over an elastic half-space with the
Lennard-Jones 9-3 surface law) solved by other people's code, the FFT half-spaces of the PyPI
package ContactMechanics and the `Lj82` interaction of its companion package Adhesion:

    pip install ContactMechanics Adhesion

`Lj82(w, z0)` is the potential φ(h) = w[(1/3)(z0/h)⁸ − (4/3)(z0/h)²] (Adhesion's
`VDW82(c_sr = w z0⁸/3, hamaker = 16π w z0²)`: φ = −A/(12π h²) + c_sr/h⁸), whose minimum is −w at
h = z0 and whose pressure −φ'(h) = (8w/3z0)[(z0/h)⁹ − (z0/h)³] is the 9-3 law with w = Δγ and
z0 = ε. (Adhesion's `LJ93` is a different law.) Its repulsion is replaced by its tangent below
`r_core` (`linearize_core`, as the engine's own examples do) so that no trial step of the
minimiser meets the singularity; the pressure there is at least 1344 Δγ/ε (at the default
0.5 ε), and `min_gap` tells whether a state reached it.

ContactMechanics' convention is gap = u − (heights + offset), u its displacement, repulsive
pressure pushing u up. With the heights z given here, offset = −d and u = −w this is
h = d − z − w, the gap of this package (w the elastic surface's deflection toward the rigid
one), and the engine's normal force (the sum of the interaction's pixel forces) is the force on
the rigid surface, positive repulsive.

The engine gets everything in units of ε (lengths) and E* (pressures), so Δγ enters as
Δγ/(E*ε); forces come back in E*ε² and are converted to newtons.

The solves run with one BLAS thread: L-BFGS-B's small vector operations on a threaded OpenBLAS
are 50-100 times slower when the other core is busy.
"""

import time
import warnings
from importlib import metadata

import numpy as np
from threadpoolctl import threadpool_limits

from fem_asperity.plumbing.errors import InputError

_PIP = "pip install ContactMechanics Adhesion"


def _import_engine():
    """The engine's modules, imported on demand, without NuMPI's 'no mpi4py' ImportWarning."""
    try:
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", message="Could not import mpi4py")
            import scipy.optimize
            from Adhesion.Interactions import Lj82
            from Adhesion.System import SmoothContactSystem
            from ContactMechanics import FreeFFTElasticHalfSpace, PeriodicFFTElasticHalfSpace
            from SurfaceTopography import Topography
    except ImportError as err:
        raise InputError(f"the other engine needs ContactMechanics and Adhesion: {_PIP}") from err
    return {
        # the distributions' versions: the modules' __version__ can be a build's git hash
        "version": f"ContactMechanics {metadata.version('ContactMechanics')}"
        f" + Adhesion {metadata.version('Adhesion')}",
        "Lj82": Lj82,
        "SmoothContactSystem": SmoothContactSystem,
        "Free": FreeFFTElasticHalfSpace,
        "Periodic": PeriodicFFTElasticHalfSpace,
        "Topography": Topography,
        "minimize": scipy.optimize.minimize,
    }


def _positive(name, value):
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a finite number > 0, got {value!r}") from None
    if not (np.isfinite(value) and value > 0):
        raise InputError(f"{name} must be a finite number > 0, got {value!r}")
    return value


def _solve(system, engine, offset, disp, options, periodic):
    """L-BFGS-B from `disp` at one offset; (the minimiser's result, the new displacement)."""
    shape = disp.shape
    if not periodic:
        sol = system.minimize_proxy(offset=offset, initial_displacements=disp, options=options)
        return sol, np.asarray(system.disp).reshape(shape)
    # The mean deflection is a free mode of the energy at a fixed offset (its stiffness is the
    # engine's stiffness_q0): hold it at zero by minimising over y with u = y − mean(y).
    fun = system.objective(offset, gradient=True)

    def zero_mean(y):
        energy, grad = fun(y - y.mean())
        return energy, grad - grad.mean()

    sol = engine["minimize"](zero_mean, disp.ravel(), method="L-BFGS-B", jac=True, options=options)
    disp = (sol.x - sol.x.mean()).reshape(shape)
    system.evaluate(disp, offset, forces=True)  # the state at the solution, not the last trial
    return sol, disp


def other_engine_forces(
    heights,
    *,
    pixel,
    e_star,
    dgamma,
    eps,
    separations,
    periodic,
    gtol=1e-6,
    r_core=0.5,
    maxiter=100_000,
) -> dict:
    """Force on a rigid height map along a path of separations, by ContactMechanics + Adhesion.

    heights: (n1, n2) heights of the rigid surface (m), the largest touching first; pixel: its
    square pixel's side (m); e_star: the half-space's effective modulus E* (Pa); dgamma, eps: the
    9-3 law's work of adhesion Δγ (J/m²) and zero-traction gap ε (m); separations: d (m), the
    distance from the heights' z = 0 to the undeformed elastic surface, solved in the order given,
    each warm-started from the previous state (so a path that reverses traces approach then
    retraction, jumps included); periodic: a periodic half-space whose mean deflection is held at
    zero, else a free (zero-padded FFT) half-space under the map only.

    Options: gtol, the minimiser's tolerance on every pixel's force balance in units of
    Δγ/ε times the pixel area; r_core, the gap (in ε) below which the repulsion is linearised;
    maxiter, L-BFGS-B's iteration limit per separation.

    Returns a dict: d (m) and force (N, positive repulsive) per separation, seconds (wall time of
    the solves), engine (the two packages' versions), converged (L-BFGS-B's success per
    separation), and also nit (its iterations) and min_gap (m, the smallest gap of each state).
    """
    z = np.asarray(heights, dtype=float)
    if z.ndim != 2 or min(z.shape) < 2:
        raise InputError(f"heights must be a 2-D array of at least 2×2 pixels, got shape {z.shape}")
    if not np.all(np.isfinite(z)):
        raise InputError("heights must be finite everywhere")
    pixel = _positive("pixel", pixel)
    e_star = _positive("e_star", e_star)
    dgamma = _positive("dgamma", dgamma)
    eps = _positive("eps", eps)
    gtol = _positive("gtol", gtol)
    r_core = _positive("r_core", r_core)
    if r_core >= 1:
        raise InputError(f"r_core must lie in (0, 1) (in ε), got {r_core!r}")
    d = np.asarray(separations, dtype=float).ravel()
    if d.size == 0 or not np.all(np.isfinite(d)):
        raise InputError("separations must be a non-empty sequence of finite numbers")

    engine = _import_engine()
    n1, n2 = z.shape
    px = pixel / eps  # the engine's units: ε for lengths, E* for pressures
    sizes = (n1 * px, n2 * px)
    area = px * px
    w = dgamma / (e_star * eps)
    topography = engine["Topography"](z / eps, sizes, periodic=bool(periodic))
    half_space = engine["Periodic"] if periodic else engine["Free"]
    substrate = half_space((n1, n2), 1.0, sizes)
    interaction = engine["Lj82"](w, 1.0).linearize_core(r_ti=r_core)
    system = engine["SmoothContactSystem"](substrate, interaction, topography)
    options = dict(gtol=gtol * w * area, ftol=0, maxcor=3, maxiter=int(maxiter), maxfun=10**9)

    shape = substrate.nb_subdomain_grid_pts  # (2n1, 2n2) for the free half-space
    disp = np.zeros(shape)
    force, converged, nit, min_gap = [], [], [], []
    start = time.perf_counter()
    with threadpool_limits(1, user_api="blas"):
        for d_i in d / eps:
            sol, disp = _solve(system, engine, -d_i, disp, options, periodic)
            force.append(float(system.compute_normal_force()) * e_star * eps**2)
            converged.append(bool(sol.success))
            nit.append(int(sol.nit))
            min_gap.append(float(np.min(system.gap)) * eps)
    seconds = time.perf_counter() - start
    return {
        "d": d,
        "force": np.array(force),
        "seconds": seconds,
        "engine": engine["version"],
        "converged": converged,
        "nit": nit,
        "min_gap": np.array(min_gap),
    }
