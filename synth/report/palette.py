"""The one verdict palette (RGB hex) of every output, after the thesis's legend (Fig. 24-25): green verified,
red failed, orange not verified; amber an advisory warning, grey not applicable. The HTML report, the
workbooks and the web UI colour checks with it.

>>> VERDICT_FILLS["fail"]
'FFC7CE'
"""

from synth.design.result import FAIL, NOT_APPLICABLE, NOT_VERIFIED, PASS, WARNING

__all__ = ["VERDICT_FILLS"]

VERDICT_FILLS = {PASS: "C6EFCE", FAIL: "FFC7CE", NOT_VERIFIED: "FFD966", WARNING: "FFD8A8", NOT_APPLICABLE: "EDEDED"}
