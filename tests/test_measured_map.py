"""The measured map of where GW holds (gw.explicit.measured_map): reading a model's error off it
around a point, and the shipped map against a surface of it solved again."""

import numpy as np
import pytest

from fem_asperity.plumbing.errors import InputError
from gw.explicit import Scene, compare
from gw.explicit.measured_map import (
    MEASURE_MAX_SIDE,
    ON_GRID,
    map_record,
    measurable,
    measure_at,
    measured_error,
    sample_ratio,
    shipped_map,
)


def _surface(mu, zeta, sre, seed, cells, interacting=0.0):
    return {"mu": mu, "zeta": zeta, "sigma_r_eta": sre, "seed": seed, "pixel": 0.2,
            "summits": 16, "estimate": 0.01 * mu,
            "errors": {"gw_cells": cells, "interacting": interacting}}


@pytest.fixture
def grid():
    """Two μ, two ζ, two σRη, two draws: |gw_cells| = 0.1 μ ζ σRη × (1 + seed)."""
    surfaces = [_surface(mu, zeta, sre, seed, -0.1 * mu * zeta * sre * (1 + seed),
                         None if (mu, zeta, sre) == (1.0, 2.0, 0.15) else 0.0)
                for mu in (0.3, 1.0) for zeta in (0.5, 2.0) for sre in (0.05, 0.15)
                for seed in (0, 1)]
    return {"axes": {"mu": [0.3, 1.0], "zeta": [0.5, 2.0], "sigma_r_eta": [0.05, 0.15]},
            "surfaces": surfaces}


def test_a_point_between_grid_points_takes_the_largest_error_around_it(grid):
    found = measured_error("gw_cells", mu=0.5, zeta=1.0, sigma_r_eta=0.1, record=grid)
    assert found.surfaces == 16  # eight corners, two draws each
    assert found.size == pytest.approx(0.1 * 1.0 * 2.0 * 0.15 * 2)
    # the largest estimate, 0.01 μ, plus the draws' spread there, 0.1 μ ζ σRη: at the corner
    # (1, 2, 0.15), 0.01 + 0.03
    assert found.uncertainty == pytest.approx(0.01 + 0.03)
    assert found.around == {"mu": [0.3, 1.0], "zeta": [0.5, 2.0], "sigma_r_eta": [0.05, 0.15]}


def test_a_point_on_the_grid_takes_its_own_surfaces(grid):
    found = measured_error("gw_cells", mu=0.3, zeta=0.5, sigma_r_eta=0.05, record=grid)
    assert found.surfaces == 2
    assert found.size == pytest.approx(0.1 * 0.3 * 0.5 * 0.05 * 2)
    on_an_edge = measured_error("gw_cells", mu=0.3, zeta=1.0, sigma_r_eta=0.05, record=grid)
    assert on_an_edge.surfaces == 4 and on_an_edge.around["zeta"] == [0.5, 2.0]


def test_outside_the_box_or_without_an_answer_nothing_is_read(grid):
    assert measured_error("gw_cells", mu=0.2, zeta=1.0, sigma_r_eta=0.1, record=grid) is None
    assert measured_error("gw_cells", mu=0.5, zeta=1.0, sigma_r_eta=0.2, record=grid) is None
    # the interacting model stopped in tension on one corner: no bound around it
    assert measured_error("interacting", mu=0.5, zeta=1.0, sigma_r_eta=0.1,
                          record=grid).size is None
    assert measured_error("interacting", mu=0.3, zeta=0.5, sigma_r_eta=0.05,
                          record=grid).size == 0.0
    with pytest.raises(InputError, match="model must be one of gw_cells, interacting"):
        measured_error("gw_cellz", mu=0.5, zeta=1.0, sigma_r_eta=0.1, record=grid)


def test_a_grid_point_not_solved_bounds_nothing_around_it(grid):
    """A map whose grid is not a full product (a corner left out) gives no size around the
    missing corner, and names it; elsewhere it reads as before."""
    grid["surfaces"] = [s for s in grid["surfaces"]
                        if (s["mu"], s["zeta"], s["sigma_r_eta"]) != (1.0, 2.0, 0.15)]
    found = measured_error("gw_cells", mu=0.5, zeta=1.0, sigma_r_eta=0.1, record=grid)
    assert found.size is None and found.missing == ((1.0, 2.0, 0.15, 0), (1.0, 2.0, 0.15, 1))
    assert found.surfaces == 14
    kept = measured_error("gw_cells", mu=0.5, zeta=1.0, sigma_r_eta=0.05, record=grid)
    assert kept.missing == () and kept.size == pytest.approx(0.1 * 1.0 * 2.0 * 0.05 * 2)


def test_a_draw_not_solved_bounds_nothing_at_its_grid_point(grid):
    """One of a grid point's two draws left out (a map resumed half-way): the point is not
    read from the other draw alone."""
    grid["surfaces"] = [s for s in grid["surfaces"]
                        if (s["mu"], s["zeta"], s["sigma_r_eta"], s["seed"]) != (0.3, 0.5, 0.05, 1)]
    found = measured_error("gw_cells", mu=0.3, zeta=0.5, sigma_r_eta=0.05, record=grid)
    assert found.size is None and found.missing == ((0.3, 0.5, 0.05, 1),)


def test_a_point_at_the_edge_of_the_box_is_on_it_not_across_it(grid):
    """Within ON_GRID of the lowest μ the point is on that grid value (never bracketed by the
    top and bottom of the axis); a little farther it is outside."""
    below = measured_error("gw_cells", mu=0.3 * (1 - 0.5 * ON_GRID), zeta=0.5,
                           sigma_r_eta=0.05, record=grid)
    assert below.around["mu"] == [0.3] and below.surfaces == 2
    above = measured_error("gw_cells", mu=1.0 * (1 + 0.5 * ON_GRID), zeta=2.0,
                           sigma_r_eta=0.15, record=grid)
    assert above.around["mu"] == [1.0]
    assert measured_error("gw_cells", mu=0.3 * (1 - 2 * ON_GRID), zeta=0.5,
                          sigma_r_eta=0.05, record=grid) is None


def test_the_compact_map_keeps_each_error_and_drops_a_path_that_stopped_in_tension():
    record = {"scene": {"mu": 1.0, "zeta": 2.0, "sigma_r_eta": 0.05, "seed": 0, "pixel": 0.2,
                        "summits": 16},
              "estimate": 0.004, "errors": {"gw_cells": 0.03, "interacting": -0.7},
              "models": {"whole": {"f_max": 0.4, "stopped": None, "approach": [-0.1, 0.1]},
                         "gw_cells": {"stopped": None, "approach": [-0.2, 0.1]},
                         "interacting": {"stopped": 3.0, "approach": [-0.1, -0.2]}}}
    compact = map_record([record], {"command": "test"})
    surface = compact["surfaces"][0]
    assert surface["errors"] == {"gw_cells": 0.03, "interacting": None}
    assert surface["estimate"] == pytest.approx(0.01)
    assert compact["axes"] == {"mu": [1.0], "zeta": [2.0], "sigma_r_eta": [0.05]}


def test_a_reading_gives_the_largest_sample_ratio_around_it(grid):
    """`sample`: the caps' summed F̄max against GW's integral, (1 + e_sum)/(1 + e_GW) from the
    errors against the whole surface, the largest over the surfaces read; none where a surface
    lacks either."""
    for k, s in enumerate(grid["surfaces"]):
        s["errors"] |= {"gw_sum": 0.1 * k, "gw_solved": -0.5}
    found = measured_error("gw_cells", mu=0.3, zeta=0.5, sigma_r_eta=0.05, record=grid)
    assert sample_ratio(grid["surfaces"][1]["errors"]) == pytest.approx(1.1 / 0.5)
    assert found.sample == pytest.approx(1.1 / 0.5)  # draws 0 and 1 of the first point
    grid["surfaces"][0]["errors"]["gw_sum"] = None
    assert measured_error("gw_cells", mu=0.3, zeta=0.5, sigma_r_eta=0.05,
                          record=grid).sample is None


def test_the_shipped_maps_caps_stand_for_a_large_surface_where_zeta_is_small():
    """The sample ratio of the shipped map against 16 Gaussian heights drawn here, summed on
    the table's law (no solve): near 1 at ζ = 0.5 (1.05 on 40 draws at μ = 0.3), far above at
    ζ = 12 (136 there): the few highest caps set a small surface's F̄max."""
    found = {zeta: measured_error("gw_sum", mu=0.3, zeta=zeta, sigma_r_eta=0.05).sample
             for zeta in (0.5, 12.0)}
    assert 0.8 < found[0.5] < 1.5 and found[12.0] > 20


def test_the_shipped_map_is_what_the_solver_gives_now():
    """One surface of the shipped map solved again (the cheapest at μ = 1, where caps jump in:
    37² pixels): each model's F̄max error as shipped, so a map made by another solver fails
    here and is made again (python -m validation rough-explicit --full --ship)."""
    shipped = shipped_map()
    assert shipped is not None
    surface = min((s for s in shipped["surfaces"] if s["mu"] == 1.0),
                  key=lambda s: (s["zeta"] / s["sigma_r_eta"] / s["pixel"] ** 2, s["seed"]))
    found = compare(Scene(mu=surface["mu"], zeta=surface["zeta"],
                          sigma_r_eta=surface["sigma_r_eta"], summits=surface["summits"],
                          seed=surface["seed"], pixel=surface["pixel"]), accuracy="draft")
    for name, error in surface["errors"].items():
        if error is not None:
            assert found.errors[name] == pytest.approx(error, rel=1e-4, abs=1e-6), name
    assert np.isfinite(surface["estimate"])


def test_a_point_too_large_or_out_of_range_is_refused_before_anything_is_solved():
    """The map's surface at μ = 2, ζ = 12, σRη = 0.02 is 883 pixels wide and measurable; at
    σRη = 0.005 it would be 1765, beyond MEASURE_MAX_SIDE; μ = 20 is beyond the explicit
    surfaces' range: InputError at once, naming why."""
    assert measurable(2.0, 12.0, 0.02) == 883 <= MEASURE_MAX_SIDE
    with pytest.raises(InputError, match="would be 1765 x 1765 pixels, more than the 1024"):
        measure_at("gw_cells", mu=2.0, zeta=12.0, sigma_r_eta=0.005)
    with pytest.raises(InputError, match="mu"):
        measure_at("gw_cells", mu=20.0, zeta=2.0, sigma_r_eta=0.05)
