"""The report's closed-form checks reach the verdicts that hand arithmetic gives."""

import pytest

from validation.closed_forms import closed_form_checks


@pytest.fixture(scope="module")
def by_claim():
    return {c.claim: c for c in closed_form_checks()}


def find(by_claim, text):
    return next(c for claim, c in by_claim.items() if text in claim)


def test_verdicts_match_hand_arithmetic(by_claim):
    eq10 = find(by_claim, "eq. 10 constant")
    assert eq10.verdict == "holds" and eq10.expected == pytest.approx(2.11623, abs=1e-5)
    cross = find(by_claim, "cross at mu = 0.19")
    assert cross.found == pytest.approx((0.922 / 2.116) ** 2) and cross.verdict == "holds"
    assert find(by_claim, "eq. 19 constant").verdict == "holds"  # 0.83^2 = 0.6889


def test_the_mu_half_discontinuity_fails(by_claim):
    jumps = [c for claim, c in by_claim.items() if "continuous at mu = 0.5" in claim]
    assert [c.verdict for c in jumps] == ["fails", "fails"]  # errata: 1.461 and 1.748 vs 2.03
    assert {c.verdict for c in by_claim.values()} <= {"holds", "fails", "note"}
