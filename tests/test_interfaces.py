"""The explicit interfaces: both solids are `ElasticSurface`s, both grid kinds `Grids`, and each
method has its own discretisation type whose refinements touch its own fields."""

import numpy as np
import pytest
from scipy.linalg import LinAlgError

from fem_asperity.path.grids import EdgeGrids, FixedGrid, Grids
from fem_asperity.path.paths import GridMoves
from fem_asperity.plumbing.errors import InputError
from fem_asperity.solids.fe import Solid
from fem_asperity.solids.operator import ElasticSurface, spd_inverse
from fem_asperity.solver.presets import (
    ESTIMATE_GRADING,
    BEMDiscretisation,
    EdgeDiscretisation,
    FEDiscretisation,
    FEEdgeDiscretisation,
    discretisation,
)


@pytest.mark.parametrize("method", ["fem", "bem", "fem restricted"])
def test_both_solids_offer_the_elastic_surface_interface(method):
    elastic = discretisation(2.0, "draft", method=method.split()[0]).elastic()
    if method == "fem restricted":  # every other node of the fine strip
        elastic = elastic.restricted(elastic.r_nodes[::2], keep_beyond=4.0)
    assert isinstance(elastic, ElasticSurface)
    n = elastic.r_nodes.size
    assert elastic.compliance.shape == (n, n) and elastic.interp.shape == (elastic.r_quad.size, n)
    # the stiffness is the compliance's inverse (the BEM builds both from B, as M B⁻¹ M and
    # M⁻¹ B M⁻¹): to the rounding of a product of condition number κ, κ·1e-15
    product = elastic.surface_stiffness @ elastic.compliance
    kappa = np.linalg.cond(elastic.compliance)
    assert np.max(np.abs(product - np.eye(n))) <= 1e-15 * kappa


@pytest.mark.parametrize("mu, method, track, kind", [
    (2.0, "fem", None, FixedGrid), (2.0, "bem", None, FixedGrid), (8.0, "bem", None, EdgeGrids),
    (2.0, "fem", True, EdgeGrids)])
def test_each_discretisation_builds_grids_of_the_grids_interface(mu, method, track, kind):
    grids = discretisation(mu, "draft", method=method, track_edge=track).grids(mu)
    assert isinstance(grids, kind) and isinstance(grids, Grids)
    assert grids.start.mu == mu
    assert (grids.summary(GridMoves()) == "") == (kind is FixedGrid)  # only moving grids say
    assert grids.follows_edge == (kind is EdgeGrids)


@pytest.mark.parametrize("mu, method, track, kind, grading", [
    (2.0, "fem", None, FEDiscretisation, "grading"),
    (2.0, "bem", None, BEMDiscretisation, "growth"),
    (2.0, "bem", True, EdgeDiscretisation, "growth"),
    (5.0, "fem", None, FEEdgeDiscretisation, "grading"),
])
def test_refinements_keep_the_type_and_scale_its_lengths(mu, method, track, kind,
                                                                      grading):
    fine = discretisation(mu, "default", method=method, track_edge=track)
    partner, finer = fine.for_estimate(), fine.refined()
    assert type(fine) is type(partner) is type(finer) is kind
    assert partner.h_surface == finer.h_surface == fine.h_surface / 2
    assert getattr(partner, grading) == pytest.approx(getattr(fine, grading) / ESTIMATE_GRADING)
    assert getattr(finer, grading) == getattr(fine, grading)
    assert partner.trace.turn == finer.trace.turn == fine.trace.turn / 2
    if kind is EdgeDiscretisation:
        assert partner.h_contact == fine.h_contact / 2
    if kind in (EdgeDiscretisation, FEEdgeDiscretisation):
        assert partner.band == fine.band


def test_the_uniform_boundary_integral_takes_a_layer_the_edge_grids_refuse_it():
    layer = Solid(layer_thickness=1.0, layer_modulus_ratio=0.5)
    uniform = discretisation(2.0, "draft", method="bem").grids(2.0, solid=layer)
    homogeneous = discretisation(2.0, "draft", method="bem").grids(2.0)
    assert not np.allclose(uniform.elastic.compliance, homogeneous.elastic.compliance)
    for method in ("bem", "fem"):
        with pytest.raises(InputError, match="homogeneous"):
            discretisation(2.0, "draft", method=method, track_edge=True).grids(2.0, solid=layer)


def test_spd_inverse_inverts_and_refuses_an_indefinite_matrix():
    """The FE's surface stiffness is its compliance's inverse by `spd_inverse`: against
    numpy's inverse on a matrix of condition 1e6, and a LinAlgError, not a wrong answer, for an
    eigenvalue −1e-6."""
    rng = np.random.default_rng(4)
    q, _ = np.linalg.qr(rng.standard_normal((60, 60)))
    matrix = (q * np.logspace(-6, 0, 60)) @ q.T
    matrix = 0.5 * (matrix + matrix.T)
    inverse = spd_inverse(matrix)
    assert np.array_equal(inverse, inverse.T)
    np.testing.assert_allclose(inverse, np.linalg.inv(matrix), rtol=0, atol=1e-8 * 1e6)
    with pytest.raises(LinAlgError):
        spd_inverse(matrix - 2e-6 * np.eye(60))
