"""What a browser tab keeps while it moves between the pages: its design and its portfolio.

NiceGUI builds a page anew at every navigation (a link, Back, a reload); what the engineer did on it lived in that
page's objects and was gone: Back from an application opened on the design page threw away a 20-35 s screening
(issue 35). A tab's state is kept here by the tab's id (NiceGUI's, kept by the browser in the tab's
``sessionStorage``: the same across the tab's pages, another in another tab), so that the portfolio page shows the
screening again (and one still running goes on) and the design page the design as it was left.

A tab that has shown no page for :data:`KEEP_S` seconds is forgotten (its files removed), the least recently seen
first when more than :data:`MAX_TABS` are kept.

>>> import tempfile
>>> root = Path(tempfile.mkdtemp())
>>> a = state("tab-a", root)
>>> state("tab-a", root) is a, state("tab-b", root) is a
(True, False)
>>> forget_all()
"""

from __future__ import annotations

import shutil
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["TabState", "state", "forget_all", "KEEP_S", "MAX_TABS"]

#: seconds a tab's state is kept after its last page closed
KEEP_S = 3 * 3600.0
#: the most tabs kept (a portfolio of 100,000 applications holds about 100 MB)
MAX_TABS = 16


@dataclass
class TabState:
    """One tab's design session and portfolio session (None until its page first made them), its folder."""

    folder: Path
    design: object = None
    portfolio: object = None
    pages: int = 0          # pages of this tab open now
    seen: float = field(default_factory=time.monotonic)

    def opened(self) -> None:
        self.pages += 1
        self.seen = time.monotonic()

    def closed(self) -> None:
        self.pages = max(0, self.pages - 1)
        self.seen = time.monotonic()


_TABS: dict[str, TabState] = {}
_LOCK = threading.Lock()


def state(tab_id: str, root: Path) -> TabState:
    """The state of tab ``tab_id`` (made, with its folder under ``root``, on first use); old tabs are forgotten."""
    now = time.monotonic()
    with _LOCK:
        st = _TABS.get(tab_id)
        if st is None:
            st = _TABS[tab_id] = TabState(Path(tempfile.mkdtemp(prefix="tab-", dir=root)))
        st.seen = now
        idle = sorted((t.seen, k) for k, t in _TABS.items() if t.pages == 0 and k != tab_id)
        old = [k for seen, k in idle if now - seen > KEEP_S]
        old += [k for _, k in idle if k not in old][:max(0, len(_TABS) - len(old) - MAX_TABS)]
        gone = [_TABS.pop(k) for k in old]
    for t in gone:
        shutil.rmtree(t.folder, ignore_errors=True)
    return st


def forget_all() -> None:
    """Forget every tab (the server stops: its folder goes with it)."""
    with _LOCK:
        gone = list(_TABS.values())
        _TABS.clear()
    for t in gone:
        shutil.rmtree(t.folder, ignore_errors=True)
