"""The scene advisor: a scene file in (TOML, `advisor.scene`), the cheapest model that meets the
user's tolerance out, with the measured size of every effect a model leaves out
(`advisor.advice`). `python -m advisor FILE` on the command line."""

from .advice import Advice, Effect, Model, advise
from .scene import Scene, parse_scene, read_scene

__all__ = ["Advice", "Effect", "Model", "Scene", "advise", "parse_scene", "read_scene"]
