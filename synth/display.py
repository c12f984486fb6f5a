"""How a notebook shows synth's objects: views registered from above.

The core defines the types (:class:`synth.design.result.Result`) and knows nothing of HTML; the
presentation layer registers, per type name, the function that renders one (``synth``'s top registers
the report's digest, :func:`synth.report.html.digest_html`, for a ``Result``). A type without a view
shows as its ``repr``.

>>> class Thing: ...
>>> html(Thing()) is None
True
"""

from __future__ import annotations

__all__ = ["HTML_VIEWS", "html"]

#: type name -> ``view(obj) -> str`` (HTML), registered by the presentation layer
HTML_VIEWS: dict = {}


def html(obj) -> str | None:
    """The HTML view of ``obj`` (its type's registered view), or None (a notebook then shows its repr)."""
    view = HTML_VIEWS.get(type(obj).__name__)
    return view(obj) if view is not None else None
