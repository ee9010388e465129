"""A Ctrl-C while a command line is still loading its modules ends it in one line, as a Ctrl-C
later does (`cli.run`), not in a traceback through the imports."""

import sys

#: The packages whose `python -m` command lines this quiets.
COMMANDS = ("fem_asperity", "gw", "validation")


def quiet_while_loading():
    """If this process is `python -m` one of COMMANDS (`sys.orig_argv`), report an uncaught
    KeyboardInterrupt in one line on stderr (Python still exits as interrupted); any other
    process's `sys.excepthook` is left alone: a library does not change its host's."""
    argv = list(getattr(sys, "orig_argv", ()))
    if "-m" not in argv[:-1] or argv[argv.index("-m") + 1] not in COMMANDS:
        return
    if getattr(sys.excepthook, "quiets_interrupts", False):  # gw and validation load this too
        return
    prog, previous = f"python -m {argv[argv.index('-m') + 1]}", sys.excepthook

    def hook(kind, value, traceback):
        if issubclass(kind, KeyboardInterrupt):
            print(f"{prog}: interrupted", file=sys.stderr)
        else:
            previous(kind, value, traceback)

    hook.quiets_interrupts = True
    sys.excepthook = hook
