"""Shared by every test: each FE half-space built once per worker process.

An FE half-space (`solids.fe.HalfSpace`: the mesh assembled, factorised and condensed onto its
surface) is a deterministic function of its discretisation and solid and is not changed by a
solve, so tests that solve on the same one share it: the finer half-space of the estimate at
μ = 5 took 26 s to build, and test_near_events.py built it twice, for the events near the curve's
and for the whole finer solve. The cache holds the last HALF_SPACES built (a `fine` one holds
a sparse LU of its whole mesh). A hit skips `elastic`'s own checks (FE_MAX_SURFACE_ELEMENTS):
a test that lowers such a limit must build a discretisation no earlier test built. A solve that
changed a half-space would leak into later tests: none does (its matrices are only read).
"""

import threading
from collections import OrderedDict

import pytest

from fem_asperity.solids.fe import Solid
from fem_asperity.solver.presets import FEDiscretisation

#: FE half-spaces kept per worker process.
HALF_SPACES = 6


@pytest.fixture(autouse=True, scope="session")
def one_fe_half_space_per_discretisation():
    built, build, lock = OrderedDict(), FEDiscretisation.elastic, threading.Lock()

    def elastic(self, solid=Solid()):  # an estimate builds its finer one in a second thread
        key = (self, solid)
        with lock:
            if key in built:
                built.move_to_end(key)
                return built[key]
        half_space = build(self, solid)
        with lock:
            built[key] = half_space
            while len(built) > HALF_SPACES:
                built.popitem(last=False)
        return half_space

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(FEDiscretisation, "elastic", elastic)
        yield
