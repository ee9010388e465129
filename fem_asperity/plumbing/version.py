"""The installed package's version (for `--version` and `fem_asperity.__version__`)."""

from importlib.metadata import PackageNotFoundError, version

#: Distribution name in pyproject.toml.
DISTRIBUTION = "adhesive-contact-verification"

try:
    __version__ = version(DISTRIBUTION)
except PackageNotFoundError:  # a source tree that was never installed
    __version__ = "unknown"
