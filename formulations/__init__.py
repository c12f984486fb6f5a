"""Mathematical programs as functions of plain data (no ``synth`` import): ``formulations.platform``."""
