"""Studies over many curves: the jump-in onset, the store of solved curves, the refit of the
paper's constants."""
