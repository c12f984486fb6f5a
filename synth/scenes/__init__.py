"""User-facing scenes (use cases): each one a sub-command of ``synth``."""
