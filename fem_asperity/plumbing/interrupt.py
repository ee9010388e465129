"""A Ctrl-C while a command line is still loading its modules is held until they have loaded,
then ends the command in one line (`cli.run`), as a Ctrl-C later does: an import cut short
leaves a traceback through the imports, or a C extension's half-initialised module."""

import signal
import sys

#: The packages whose `python -m` command lines this holds.
COMMANDS = ("fem_asperity", "gw", "validation", "advisor")

_held = []  # the Ctrl-Cs that came while the modules loaded


def _command():
    """The package `python -m` is starting, while it imports it (sys.argv[0] is '-m' until the
    module is found), else None."""
    if sys.argv[:1] != ["-m"]:
        return None
    argv = list(getattr(sys, "orig_argv", ()))
    for i, arg in enumerate(argv[1:], 1):
        if arg == "-m":
            return argv[i + 1] if i + 1 < len(argv) else None
        if arg.startswith("-m"):
            return arg[2:]
    return None


def _hold(signum, _frame):
    """The first Ctrl-C is held; a second one (the loading hangs?) interrupts at once."""
    if _held:
        raise KeyboardInterrupt
    _held.append(signum)


def hold_while_loading():
    """If this process is `python -m` one of COMMANDS, starting, hold Ctrl-C (SIGINT) until
    `released`; any other process's handler is left alone: a library does not change its
    host's."""
    if _command() in COMMANDS and signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        signal.signal(signal.SIGINT, _hold)


def released():
    """Give Ctrl-C back its usual KeyboardInterrupt; whether one came while it was held."""
    if signal.getsignal(signal.SIGINT) is _hold:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    return bool(_held)


def interrupted(error):
    """Whether `error` is a KeyboardInterrupt or was raised by one (an import that a Ctrl-C cut
    short raises ImportError from it)."""
    while error is not None:
        if isinstance(error, KeyboardInterrupt):
            return True
        error = error.__cause__ or error.__context__
    return False
