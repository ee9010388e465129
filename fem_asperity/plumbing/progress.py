"""Progress of a part of the work, told as the whole's (solver code imports this, not the
command-line plumbing: it stays out of the store's revision key)."""


def share(progress, start, stop):
    """`progress` (callable(fraction done) or None) told of one part of the work: that part's
    fractions 0-1 become start-stop of the whole."""
    if progress is None:
        return None
    return lambda fraction: progress(start + (stop - start) * fraction)
