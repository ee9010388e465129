"""A Ctrl-C while a command line is still loading its modules ends it in one line, as a Ctrl-C
later does (`cli.run`), not in a traceback through the imports."""

import sys

#: The packages whose `python -m` command lines this quiets.
COMMANDS = ("fem_asperity", "gw", "validation")


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


def quiet_while_loading():
    """If this process is `python -m` one of COMMANDS, starting, report an uncaught
    KeyboardInterrupt in one line on stderr (Python still exits as interrupted); any other
    process's `sys.excepthook` is left alone: a library does not change its host's."""
    command = _command()
    if command not in COMMANDS or getattr(sys.excepthook, "quiets_interrupts", False):
        return

    def hook(kind, value, traceback, previous=sys.excepthook):
        if issubclass(kind, KeyboardInterrupt):
            print(f"python -m {command}: interrupted", file=sys.stderr)
        else:
            previous(kind, value, traceback)

    hook.quiets_interrupts = True
    sys.excepthook = hook
