"""The eight constants refitted from BEM curves, against the paper's and Wu's values."""

import numpy as np
import pytest

from fem_asperity.closed_forms.laws import PAPER_LAWS
from fem_asperity.studies.refit import refit, stored_refit


@pytest.fixture(scope="module")
def fitted(tmp_path_factory):
    cache = tmp_path_factory.mktemp("cache")
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("ADHESION_CACHE", str(cache))
        yield refit((0.1, 0.2, 0.3, 0.4, 1.0, 1.5, 2.0), accuracy="draft"), cache


@pytest.mark.slow
def test_refit_is_close_to_the_paper_where_the_paper_is_right(fitted):
    found, _ = fitted
    laws = found.laws
    assert laws.c_off == pytest.approx(PAPER_LAWS.c_off, rel=0.02)  # Wu's fit of the LJ curve
    assert laws.x_0 == pytest.approx(PAPER_LAWS.x_0, abs=0.2)
    assert laws.c_a == pytest.approx(PAPER_LAWS.c_a, rel=0.1)
    assert 0.69 < laws.mu_jump < 0.705  # the measured onset, not the paper's 0.5
    assert found.residuals["p_off (eq. 2)"][1] < 0.01
    assert found.mu == (0.1, 0.2, 0.3, 0.4, 1.0, 1.5, 2.0)


@pytest.mark.slow
def test_stored_refit_round_trips(fitted, tmp_path, monkeypatch):
    monkeypatch.setenv("ADHESION_CACHE", str(fitted[1]))
    first = stored_refit(accuracy="draft", cache=tmp_path)  # computes (curves already stored)
    again = stored_refit(accuracy="draft", cache=tmp_path)  # reads the JSON
    assert again.laws == first.laws and again.residuals == first.residuals


@pytest.mark.slow
def test_a_refit_reports_its_progress_while_it_solves(fitted, monkeypatch):
    """Curves read from the store report nothing and take no share; the one solved reports
    over the first 0.8; the fit ends at 1."""
    monkeypatch.setenv("ADHESION_CACHE", str(fitted[1]))
    mus = (0.1, 0.2, 0.3, 0.4, 1.0, 1.5, 2.0, 0.25)  # 0.25 is not stored yet
    fractions = []
    refit(mus, accuracy="draft", progress=fractions.append)
    assert fractions[-2] == pytest.approx(0.8) and fractions[-1] == 1.0
    assert len(fractions) > 3 and 0.0 <= min(fractions) and np.all(np.diff(fractions) >= 0)
