"""The version of synth: a leaf module, so that what stamps its outputs with it (fingerprints, STEP headers,
workbooks, the command line) need not import the package's top (``tests/test_cli.py`` holds it equal to
``pyproject.toml``)."""

__all__ = ["__version__"]

__version__ = "0.1.0"
