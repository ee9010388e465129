"""Command-line plumbing shared by the package's entry points: one-line errors, tables, JSON."""

import argparse
import contextlib
import json
import math
import os
import re
import sys
import time
import warnings

from . import interrupt
from .errors import ContinuationError, InputError
from .version import __version__

#: What argparse must read as a negative number: its own patterns and e-notation.
NEGATIVE_NUMBER = re.compile(r"^-(\d+|\d*\.\d+|\d*\.?\d+[eE][+-]?\d+)$")


class Parser(argparse.ArgumentParser):
    """An ArgumentParser whose usage errors are one line on stderr and exit code 2, with a
    `--version` flag."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        # Negative numbers in e-notation (--tolerance -1e-3, --d -1e3 1e3) are values, not options.
        self._negative_number_matcher = NEGATIVE_NUMBER
        self.add_argument("--version", action="version", version=f"%(prog)s {__version__}")

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message}\n")


def _warn_one_line(message, *_args, **_kwargs):
    print(f"warning: {message}", file=sys.stderr)


def run(main, prog, argv=None):
    """Call `main(argv)`: warnings print as one line, an `InputError` as one line + exit code 2,
    Ctrl-C (also one held while the modules loaded, `interrupt`) as one line + exit code 130,
    an `OSError` (e.g. an output folder that cannot be written) or a `ContinuationError` (a
    curve the solver could not follow) as one line + exit code 1."""
    with warnings.catch_warnings():
        warnings.showwarning = _warn_one_line
        try:
            if interrupt.released():
                raise KeyboardInterrupt
            return main(argv)
        except InputError as exc:
            print(f"{prog}: error: {exc}", file=sys.stderr)
            return 2
        except KeyboardInterrupt:
            print(f"{prog}: interrupted", file=sys.stderr)
            return 130
        except BrokenPipeError:  # output piped into e.g. `head`, which stopped reading
            sys.stdout = open(os.devnull, "w")
            return 0
        except (OSError, ContinuationError) as exc:
            print(f"{prog}: error: {exc}", file=sys.stderr)
            return 1
        except Exception as exc:
            if not interrupt.interrupted(exc):  # an import that a Ctrl-C cut short
                raise
            print(f"{prog}: interrupted", file=sys.stderr)
            return 130


def dump_json(obj):
    """Print `obj` as JSON, refusing NaN (which is not JSON)."""
    print(json.dumps(obj, indent=2, allow_nan=False))


def format_cell(value, *, missing="-", words=("yes", "no"), digits=5):
    """A table or CSV cell: `missing` for None and non-finite floats, `words` for True/False,
    floats to `digits` significant digits."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return missing
    if isinstance(value, bool):
        return words[0] if value else words[1]
    if isinstance(value, float):
        return f"{value:.{digits}g}"
    return str(value)


def print_table(rows, columns):
    """Print dict rows as an aligned plain-text table with the given column keys."""
    cells = [[format_cell(row[c]) for c in columns] for row in rows]
    widths = [max(len(c), *(len(r[i]) for r in cells)) for i, c in enumerate(columns)]
    print("  ".join(c.rjust(w) for c, w in zip(columns, widths)))
    for r in cells:
        print("  ".join(v.rjust(w) for v, w in zip(r, widths)))


def _duration(seconds):
    """'42 s', '7 min', '2.5 h'."""
    if seconds < 120:
        return f"{seconds:.0f} s"
    return f"{seconds / 60:.0f} min" if seconds < 7200 else f"{seconds / 3600:.1f} h"


class ProgressBar:
    """A one-line progress bar on stderr: `label [#####.....] 50%`, redrawn in place on a
    terminal, printed every 10% otherwise (logs stay short); it only moves forward. With
    `time_left`, it adds the time left, extrapolated from the time so far."""

    def __init__(self, label, width=30, stream=None, time_left=False):
        self.label, self.width = label, width
        self.stream = stream or sys.stderr
        self.tty = self.stream.isatty()
        self.shown = -1
        self.started = time.perf_counter() if time_left else None

    def __call__(self, fraction):
        percent = int(100 * min(max(fraction, 0.0), 1.0))
        step = 1 if self.tty else 10
        if percent // step <= self.shown // step:  # never backwards (e.g. on an unstable branch)
            return
        self.shown = percent
        filled = self.width * percent // 100
        bar = f"{self.label} [{'#' * filled}{'.' * (self.width - filled)}] {percent:3d}%"
        if self.started is not None and 0 < percent < 100:
            elapsed = time.perf_counter() - self.started
            bar += f", about {_duration(elapsed * (100 - percent) / percent)} left"
        self.stream.write(("\r" + bar) if self.tty else bar + "\n")
        self.stream.flush()

    def close(self):
        """Finish the bar at 100% (and end the line on a terminal)."""
        self(1.0)
        if self.tty:
            self.stream.write("\n")


@contextlib.contextmanager
def shown(bars, label):
    """The progress callable of one long step: `bars(label)` (a `ProgressBar`), finished when
    the step ends without error if it moved at all (a step that only read the store shows
    nothing); None where `bars` is None."""
    if bars is None:
        yield None
        return
    bar = bars(label)
    try:
        yield bar
    except BaseException:  # the error's line starts on a line of its own
        if bar.tty and bar.shown >= 0:
            bar.stream.write("\n")
        raise
    if bar.shown >= 0:
        bar.close()
