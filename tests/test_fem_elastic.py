"""The condensed axisymmetric half-space against Boussinesq-type closed forms (E* = 1 units)."""

import numpy as np
import pytest

from fem_asperity import InputError
from fem_asperity.path.grids import edge_grid
from fem_asperity.solids.fe import HalfSpace, Solid, boussinesq_point_load
from fem_asperity.solids.mesh import graded_mesh


def _model(order=2, grading=0.5, layer=None, solid=Solid()):
    # surface edges 2/32 = 0.0625 (the longest that 3 or fewer cells across r_fine = 2 allow)
    mesh = graded_mesh(h_surface=0.07, r_fine=2.0, size=1e4, grading=grading, layer_thickness=layer)
    return HalfSpace(mesh, order=order, solid=solid)


@pytest.fixture(scope="module")
def p2():
    return _model()


def _hertz_error(model):
    """Max |w + (1 − r²/2)| inside r < 0.9 under the Hertz pressure of a = R = 1 (δ = 1)."""
    r = model.r_quad
    pressure = np.where(r < 1.0, 2.0 / np.pi * np.sqrt(np.clip(1.0 - r**2, 0.0, None)), 0.0)
    w = model.deflection(pressure)
    inside = model.r_nodes < 0.9
    return np.max(np.abs(-w[inside] - (1.0 - 0.5 * model.r_nodes[inside] ** 2)))


def test_hertz_pressure_gives_hertz_displacement(p2):
    assert _hertz_error(p2) < 0.01 * 0.1  # 1% of δ = 1 asked; P2 gives 0.03%


def test_p1_hertz_within_one_percent():
    assert _hertz_error(_model(order=1, grading=0.2)) < 0.01


def test_uniform_disc_centre_deflection(p2):
    w = p2.deflection((p2.r_quad < 1.0).astype(float))
    assert p2.r_nodes[0] == 0.0
    assert -w[0] == pytest.approx(2.0, rel=0.01)  # 2 p a / E*


def _hertz_pressure(r):
    return np.where(r < 1.0, 2.0 / np.pi * np.sqrt(np.clip(1.0 - r**2, 0.0, None)), 0.0)


def test_a_restriction_to_every_node_is_the_half_space(p2):
    whole = p2.restricted(p2.r_nodes, keep_beyond=1.0)
    assert np.array_equal(whole.r_nodes, p2.r_nodes) and whole.dofs == p2.dofs
    scale = np.max(np.abs(p2.surface_stiffness))
    assert np.max(np.abs(whole.surface_stiffness - p2.surface_stiffness)) <= 1e-13 * scale
    pressure = _hertz_pressure(p2.r_quad)
    assert np.max(np.abs(whole.deflection(pressure) - p2.deflection(pressure))) <= 1e-12


def test_a_restriction_keeps_the_nearest_nodes_every_node_in_a_band_and_beyond(p2):
    """Radii off the nodes go to the nearest node; a grid of `edge_grid` as fine as the nodes
    keeps every node within its bands; every node from `keep_beyond` on is kept."""
    r = p2.r_nodes
    off = r[1:20] + np.array([-0.3, 0.3] * 9 + [0.1])[:19] * np.diff(r[:21])[1:20]
    assert np.array_equal(p2.restricted(off, keep_beyond=2.0).r_nodes[1:20], r[1:20])
    h = float(np.min(np.diff(r)))
    nodes = edge_grid(1.0, 1.4, lambda radius: 1.0 + radius**2, h=h, band=0.2, r_max=r[-1],
                      h_inside=0.1)
    kept = p2.restricted(nodes, keep_beyond=2.0).r_nodes
    banded = (np.abs(r - 1.0) <= 0.2) | (np.abs(r - 1.4) <= 0.2) | (r >= 2.0)
    assert np.isin(r[banded], kept).all() and kept.size < r.size


def test_a_restricted_surface_is_stiffer_and_converges_as_its_nodes_refine(p2):
    """Ritz: the energy minimised over fewer displacements leaves the solid stiffer, so a load's
    compliance energy can only fall, (Tᵀf)ᵀ C̃ (Tᵀf) ≤ fᵀ C f; and the Hertz deflection (δ = 1)
    approaches the half-space's as the strip r < 2 keeps every 8th, 4th, 2nd node."""
    pressure = _hertz_pressure(p2.r_quad)
    load = p2.nodal_load(pressure)
    energy = load @ p2.compliance @ load
    strip = p2.r_nodes[p2.r_nodes < 2.0]
    errors = []
    for every in (8, 4, 2):
        restricted = p2.restricted(strip[::every], keep_beyond=2.0)
        reduced = restricted.nodal_load(pressure)
        assert reduced @ restricted.compliance @ reduced <= energy * (1.0 + 1e-12)
        w = np.interp(p2.r_nodes, restricted.r_nodes, restricted.deflection(pressure))
        errors.append(np.max(np.abs(w - p2.deflection(pressure))))
    assert errors[2] < errors[1] < errors[0] < 0.05


def test_truncation_size_no_longer_matters():
    """The solid outside the truncation is restored: the centre deflection of a uniform disc
    (2 p a / E* = 2) is the same for L = 100 and L = 1e4 (uncorrected, it falls short like 1/L),
    and within 5e-5 of 2 (what remains is the bulk grading)."""
    deflections = []
    for size in (1e2, 1e4):
        mesh = graded_mesh(h_surface=0.07, r_fine=2.0, size=size, grading=0.3)
        model = HalfSpace(mesh, order=2)
        deflections.append(-model.deflection((model.r_quad < 1.0).astype(float))[0])
    assert deflections[0] == pytest.approx(deflections[1], abs=2e-6)
    assert deflections[1] == pytest.approx(2.0, abs=1e-4)


def test_boussinesq_point_load_on_the_surface_and_the_axis():
    """u_z = 2/r on the surface (P/(π E* r) with P = 2π), u_r = −(1 − 2ν)/((1 − ν) r) there,
    and on the axis u_z = (3 − 2ν)/((1 − ν) z), u_r = 0 (Johnson, eq. 3.18 at its two edges)."""
    nu = 0.3
    u_r, u_z = boussinesq_point_load(np.array([0.5, 2.0]), np.zeros(2), nu=nu)
    np.testing.assert_allclose(u_z, 2.0 / np.array([0.5, 2.0]), rtol=1e-14)
    np.testing.assert_allclose(u_r, -(1 - 2 * nu) / ((1 - nu) * np.array([0.5, 2.0])), rtol=1e-14)
    u_r, u_z = boussinesq_point_load(0.0, 3.0, nu=nu)
    assert u_r == 0.0 and u_z == pytest.approx((3 - 2 * nu) / ((1 - nu) * 3.0), rel=1e-14)


def test_displacement_field_carries_the_far_field(p2):
    """The full field's surface values are the condensed deflection (both include the solid
    outside the truncation), near the axis to 1e-9."""
    load = p2.nodal_load((p2.r_quad < 1.0).astype(float))
    u = p2.displacement_field(load)
    near = p2.r_nodes < 2.0
    np.testing.assert_allclose(u[p2.surface_dofs][near], (-p2.compliance @ load)[near],
                               rtol=0, atol=1e-9)


def test_force_weights_integrate_r():
    model = _model(order=1, grading=0.3)
    # ∫0^1 r dr = 1/2 exactly with the surface quadrature
    assert model.weights @ (model.r_quad < 1.0) == pytest.approx(0.5, rel=1e-12)


def test_layer_with_substrate_properties_is_the_half_space():
    layered = _model(layer=0.7, solid=Solid(layer_thickness=0.7))
    plain_same_mesh = _model(layer=0.7)
    load = (layered.r_quad < 1.0).astype(float)
    np.testing.assert_array_equal(layered.deflection(load), plain_same_mesh.deflection(load))
    plain = _model()
    w_plain = plain.deflection((plain.r_quad < 1.0).astype(float))[0]
    assert layered.deflection(load)[0] == pytest.approx(w_plain, rel=1e-3)


def test_thick_stiff_layer_acts_as_its_own_half_space():
    solid = Solid(layer_thickness=500.0, layer_modulus_ratio=2.0)
    model = _model(layer=500.0, solid=solid)
    w = model.deflection((model.r_quad < 1.0).astype(float))
    assert -w[0] == pytest.approx(1.0, rel=0.01)  # 2 p a / E*_layer


def test_soft_layer_is_more_compliant():
    stiff, soft = (_model(layer=0.5, solid=Solid(layer_thickness=0.5, layer_modulus_ratio=m))
                   for m in (4.0, 0.25))
    load = (stiff.r_quad < 1.0).astype(float)
    assert -stiff.deflection(load)[0] < 2.0 < -soft.deflection(load)[0]


@pytest.mark.parametrize(
    "kwargs",
    [dict(nu=0.5), dict(layer_modulus_ratio=2.0), dict(layer_thickness=-1.0),
     dict(layer_thickness=1.0, layer_modulus_ratio=0.0)],
)
def test_solid_rejects_bad_input(kwargs):
    with pytest.raises(InputError):
        Solid(**kwargs)


def test_mesh_rejects_bad_sizes():
    with pytest.raises(InputError, match="size"):
        graded_mesh(h_surface=0.1, r_fine=2.0, size=4.0)
    with pytest.raises(InputError, match="order"):
        HalfSpace(graded_mesh(h_surface=0.5, r_fine=2.0, size=100.0), order=3)


def test_mesh_is_graded_and_tagged():
    mesh = graded_mesh(h_surface=0.05, r_fine=1.0, size=1e3, layer_thickness=0.3)
    facets = mesh.facets[:, mesh.boundaries["top"]]
    r = mesh.p[0, facets]
    length = np.abs(r[1] - r[0])
    assert length[r.max(axis=0) <= 1.0].max() <= 0.05 + 1e-12
    assert length.max() > 10.0  # coarse far away
    assert np.isclose(mesh.p[1], -0.3).any()
    assert mesh.subdomains["layer"].size > 0


@pytest.mark.parametrize("h_surface", [0.05, 0.07, 0.09, 0.13])
def test_surface_edges_are_at_most_h_and_mostly_longer_than_two_thirds_h(h_surface):
    mesh = graded_mesh(h_surface=h_surface, r_fine=1.7, size=100.0)
    facets = mesh.facets[:, mesh.boundaries["top"]]
    r = mesh.p[0, facets]
    length = np.abs(r[1] - r[0])[r.max(axis=0) <= 1.7 + 1e-12]
    assert length.sum() == pytest.approx(1.7, rel=1e-12)
    assert length.max() <= h_surface + 1e-12
    assert 2.0 / 3.0 * h_surface < np.median(length)
    assert length.size <= 1.1 * 1.7 / np.median(length)  # a few halved by the conforming closure
