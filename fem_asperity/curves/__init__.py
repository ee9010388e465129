"""What a single-asperity solve yields, for every consumer to import without reaching into the
algorithms: the sampled `Curve` (curve.py) and the `Jump`s and `Events` read off it (events.py).
numpy only."""
