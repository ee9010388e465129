"""The explicit interfaces: both solids are `ElasticSurface`s, both grid kinds `Grids`, and each
method has its own discretisation type whose refinements touch its own fields."""

import pytest

from fem_asperity.path.grids import EdgeGrids, FixedGrid, Grids
from fem_asperity.plumbing.errors import InputError
from fem_asperity.solids.fe import Solid
from fem_asperity.solids.operator import ElasticSurface
from fem_asperity.solver.presets import (
    ESTIMATE_GRADING,
    BEMDiscretisation,
    EdgeDiscretisation,
    FEDiscretisation,
    discretisation,
)


@pytest.mark.parametrize("method", ["fem", "bem"])
def test_both_solids_offer_the_elastic_surface_interface(method):
    elastic = discretisation(2.0, "draft", method=method).elastic()
    assert isinstance(elastic, ElasticSurface)
    n = elastic.r_nodes.size
    assert elastic.compliance.shape == (n, n) and elastic.interp.shape == (elastic.r_quad.size, n)


@pytest.mark.parametrize("mu, method, kind", [(2.0, "fem", FixedGrid), (2.0, "bem", FixedGrid),
                                              (8.0, "bem", EdgeGrids)])
def test_each_discretisation_builds_grids_of_the_grids_interface(mu, method, kind):
    grids = discretisation(mu, "draft", method=method).grids(mu)
    assert isinstance(grids, kind) and isinstance(grids, Grids)
    assert grids.start.mu == mu
    assert (grids.summary() == "") == (kind is FixedGrid)  # only moving grids have news


@pytest.mark.parametrize("mu, method, track, kind, grading", [
    (2.0, "fem", None, FEDiscretisation, "grading"),
    (2.0, "bem", None, BEMDiscretisation, "growth"),
    (2.0, "bem", True, EdgeDiscretisation, "growth"),
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
        assert partner.h_contact == fine.h_contact / 2 and partner.band == fine.band


@pytest.mark.parametrize("track", [None, True])
def test_boundary_integral_discretisations_refuse_a_layer(track):
    disc = discretisation(2.0, "draft", method="bem", track_edge=track)
    with pytest.raises(InputError, match="homogeneous"):
        disc.grids(2.0, solid=Solid(layer_thickness=1.0))
