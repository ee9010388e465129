"""Where a number came from: the git commit of a checkout and the machine it ran on. Shared by
the verification report and the benchmark tables."""

import os
import platform
import subprocess
from importlib.metadata import PackageNotFoundError, version


def _git(folder, *args):
    try:
        done = subprocess.run(["git", *args], cwd=folder, capture_output=True, text=True,
                              check=True, timeout=30)
    except (OSError, subprocess.SubprocessError):
        return None
    return done.stdout.strip() or None


def git_commit(folder):
    """`git rev-parse --short HEAD` of the checkout holding `folder`, plus " + uncommitted
    changes" where tracked files differ from it; None outside a git checkout."""
    head = _git(folder, "rev-parse", "--short", "HEAD")
    if head is None:
        return None
    dirty = _git(folder, "status", "--porcelain", "--untracked-files=no")
    return head + (" + uncommitted changes" if dirty else "")


def _proc_field(path, key):
    """The value of the first `key: value` line of a /proc file, or None."""
    try:
        with open(path, encoding="utf-8") as f:
            for line in f:
                name, _, value = line.partition(":")
                if name.strip() == key:
                    return value.strip()
    except OSError:
        pass
    return None


def _memory():
    total = _proc_field("/proc/meminfo", "MemTotal")  # e.g. "24684092 kB"
    if total is None or not total.endswith("kB"):
        return None
    return f"{int(total.split()[0]) / 2**20:.1f} GiB"


def _version(package):
    try:
        return version(package)
    except PackageNotFoundError:
        return None


def _blas():
    """BLAS libraries loaded, as `internal_api version (the wheel that ships it)`: numpy's and
    scipy's wheels each bundle their own."""
    import numpy  # noqa: F401  (threadpoolctl lists only libraries already loaded)
    import scipy.linalg  # noqa: F401
    from threadpoolctl import threadpool_info

    found = set()
    for lib in threadpool_info():
        if lib.get("user_api") == "blas":
            owner = next((p for p in ("numpy", "scipy") if p in lib.get("filepath", "")), None)
            found.add(f"{lib['internal_api']} {lib['version']}" + (f" ({owner})" if owner else ""))
    return ", ".join(sorted(found)) or None


def machine():
    """CPU model, architecture, cores, memory, OS and the numerical software's versions."""
    return {
        "cpu": _proc_field("/proc/cpuinfo", "model name") or platform.processor() or None,
        "arch": platform.machine() or None,
        "cpu_count": os.cpu_count(),
        "memory": _memory(),
        "os": platform.platform(),
        "python": platform.python_version(),
        "numpy": _version("numpy"),
        "scipy": _version("scipy"),
        "scikit-fem": _version("scikit-fem"),
        "blas": _blas(),
    }
