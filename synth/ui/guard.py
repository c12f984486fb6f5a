"""Which requests ``synth ui`` answers: the local server trusts nothing it did not serve (issue 39).

Any page the engineer visits can make the browser send requests to 127.0.0.1 (a link, a form, an image, a script,
a websocket), and a DNS name an attacker controls can be made to resolve to 127.0.0.1 (DNS rebinding). Design
inputs are a company's confidential data, so every HTTP request and every websocket handshake, whatever its path,
passes :class:`Guard` before NiceGUI sees it:

1. ``Host`` names this server at its port: ``127.0.0.1``, ``localhost``, ``[::1]``, or the name ``--host`` gave (a
   wildcard bind, ``0.0.0.0``: this machine's names and addresses). A rebound name (``attacker.example``) is refused.
2. ``Origin``, when the request has one (a browser sends it with every websocket, every POST and every
   cross-origin fetch), is the server's own: ``http://`` and the request's ``Host``. A page of another site, or of
   another port of this machine, is foreign.
3. ``Sec-Fetch-Site`` (sent by Chromium, Firefox and Safari): a request that another site or another port made
   (an image, a script, a frame, a fetch) is refused; only a top-level navigation to a page passes (a link to the
   server: the page then loads everything else as its own).
4. Bound beyond the loopback: the per-launch token (as Jupyter's), given once in the URL the server prints
   (``?token=...``: the server answers with a cookie and the same URL without the token) or in an
   ``Authorization: token ...`` header.
5. A request body is at most :data:`BODY_LIMIT` bytes (an upload: its page's limit, :mod:`synth.ui.uploads`): a
   longer ``Content-Length`` is refused before a byte is read; a body without one is counted as it streams.

A refusal is a line of text with HTTP 403 (400 for a malformed request, 413 for a body too large) and
``Connection: close``; a websocket is closed before it is accepted (the browser sees 403). Every answer carries
``X-Frame-Options: DENY`` and ``Content-Security-Policy: frame-ancestors 'none'`` (no other site frames the page)
and ``Referrer-Policy: no-referrer``. Socket.io answers CORS for the server's own origins only
(:meth:`Policy.origins`, its ``cors_allowed_origins``; NiceGUI's default is ``*``).

>>> p = Policy.of("127.0.0.1", 8080)
>>> p.refusal({"type": "http", "method": "GET", "path": "/", "headers": [(b"host", b"127.0.0.1:8080")]}) is None
True
>>> p.refusal({"type": "http", "method": "GET", "path": "/", "headers": [(b"host", b"attacker.example:8080")]})
(403, "Host 'attacker.example:8080' is not this server's (127.0.0.1, localhost or [::1] at port 8080)")
>>> p.refusal({"type": "http", "method": "GET", "path": "/",
...            "headers": [(b"host", b"127.0.0.1:8080"), (b"origin", b"http://127.0.0.1:9999")]})[1]
"Origin 'http://127.0.0.1:9999' is not this server's (http://127.0.0.1:8080)"
"""

from __future__ import annotations

import ipaddress
import secrets
import socket
from dataclasses import dataclass
from http.cookies import CookieError, SimpleCookie
from urllib.parse import parse_qsl, urlencode, urlsplit

__all__ = ["Policy", "Guard", "BODY_LIMIT", "is_loopback", "WILDCARD", "TooLarge"]

#: the largest request body but an upload's: socket.io's own limit on a message is 1,000,000 bytes
#: (python-engineio's ``max_http_buffer_size``); NiceGUI's pages send nothing bigger
BODY_LIMIT = 2 * 1024 * 1024

#: the addresses that bind every interface
WILDCARD = ("0.0.0.0", "::", "")

_LOOPBACK_NAMES = ("127.0.0.1", "localhost", "::1")


def is_loopback(host: str) -> bool:
    """Whether binding ``host`` keeps the server to this machine (127.0.0.0/8, ::1, localhost).

    >>> is_loopback("127.0.0.1"), is_loopback("localhost"), is_loopback("::1"), is_loopback("0.0.0.0")
    (True, True, True, False)
    """
    name = host.strip().strip("[]").lower()
    if name == "localhost":
        return True
    try:
        return ipaddress.ip_address(name).is_loopback
    except ValueError:
        return False


def _machine_names() -> set[str]:
    """This machine's host names and interface addresses (a wildcard bind is reached by any of them)."""
    names = set()
    for f in (socket.gethostname, socket.getfqdn):
        try:
            names.add(f().lower())
        except OSError:  # pragma: no cover - a machine without a name
            pass
    try:
        import ifaddr  # NiceGUI's own dependency (its welcome message lists the addresses)
        for adapter in ifaddr.get_adapters():
            for ip in adapter.ips:
                names.add(str(ip.ip[0] if isinstance(ip.ip, tuple) else ip.ip).lower())
    except Exception:  # noqa: BLE001 - the names above still serve
        pass
    return {n for n in names if n}


def _split_authority(value: str) -> tuple[str, int | None] | None:
    """``(host name, port)`` of a ``Host`` header or an origin's authority; None when it is not one."""
    if not value or any(c in value for c in "@/\\?# \t\r\n"):
        return None
    try:
        u = urlsplit("//" + value)
        return (u.hostname or "").rstrip("."), u.port
    except ValueError:
        return None


@dataclass(frozen=True)
class Policy:
    """What :class:`Guard` accepts: the bound ``host`` and ``port``, the host ``names`` a request may use, and the
    ``token`` (None on the loopback: no token asked)."""

    host: str
    port: int
    names: frozenset
    token: str | None = None

    @classmethod
    def of(cls, host: str, port: int, token: str | None = None) -> "Policy":
        """The policy of a server bound to ``host:port``: a token is made when ``host`` is beyond the loopback."""
        names = set(_LOOPBACK_NAMES) | {host.strip().strip("[]").lower()}
        if host in WILDCARD:
            names |= _machine_names()
        names.discard("")
        if not is_loopback(host) and token is None:
            token = secrets.token_urlsafe(32)
        return cls(host, port, frozenset(names), token if not is_loopback(host) else None)

    @property
    def cookie(self) -> str:
        """The token's cookie (one per port: cookies are not told apart by port)."""
        return f"synth-ui-token-{self.port}"

    def origins(self) -> list[str]:
        """The server's own origins (``http://NAME:PORT``), socket.io's ``cors_allowed_origins``."""
        return sorted(f"http://{'[' + n + ']' if ':' in n else n}:{self.port}" for n in self.names)

    def url(self, path: str = "/") -> str:
        """The URL to open (with the token when one is asked)."""
        name = socket.gethostname() if self.host in WILDCARD else self.host
        shown = f"[{name}]" if ":" in name else name
        return f"http://{shown}:{self.port}{path}" + (f"?token={self.token}" if self.token else "")

    def _names_text(self) -> str:
        shown = sorted({"[" + n + "]" if ":" in n else n for n in self.names} - {"127.0.0.1", "localhost", "[::1]"})
        return ", ".join(["127.0.0.1", "localhost"] + shown) + f" or [::1] at port {self.port}"

    def refusal(self, scope: dict) -> tuple[int, str] | None:
        """``(status, why)`` when the request of ``scope`` (ASGI, http or websocket) is refused, else None.

        The token is not checked here (:meth:`token_state`)."""
        headers = _headers(scope)
        host = headers.get("host")
        if host is None:
            return 400, "a request without a Host header"
        hp = _split_authority(host)
        if hp is None or hp[0] not in self.names or (hp[1] or 80) != self.port:
            return 403, f"Host {host!r} is not this server's ({self._names_text()})"
        origin = headers.get("origin")
        if origin is not None:
            own = "http://" + host.lower()
            u = None
            try:
                u = urlsplit(origin.lower())
                same = (u.scheme == "http" and (u.hostname or "") == hp[0] and (u.port or 80) == self.port
                        and u.path in ("", "/") and not u.query and not u.username)
            except ValueError:
                same = False
            if not same:
                return 403, f"Origin {origin!r} is not this server's ({own})"
        site = headers.get("sec-fetch-site")
        if site in ("cross-site", "same-site"):
            navigation = (scope["type"] == "http" and scope.get("method") in ("GET", "HEAD")
                          and headers.get("sec-fetch-mode") == "navigate"
                          and headers.get("sec-fetch-dest", "document") == "document")
            if not navigation:
                return 403, (f"a request another site made (Sec-Fetch-Site: {site}, "
                             f"{headers.get('sec-fetch-dest', '?')}); only this server's own pages use it")
        return None

    def token_state(self, scope: dict) -> str:
        """``ok`` (no token asked, or a valid one in the cookie or ``Authorization`` header), ``query`` (a valid one
        in the URL: answer with the cookie) or ``missing``."""
        if self.token is None:
            return "ok"
        headers = _headers(scope)
        given = []
        auth = headers.get("authorization", "")
        if auth.lower().startswith(("token ", "bearer ")):
            given.append(auth.split(None, 1)[1].strip())
        try:
            jar = SimpleCookie(headers.get("cookie", ""))
            if self.cookie in jar:
                given.append(jar[self.cookie].value)
        except CookieError:
            pass
        if any(secrets.compare_digest(g.encode(), self.token.encode()) for g in given):
            return "ok"
        query = dict(parse_qsl(scope.get("query_string", b"").decode("latin-1")))
        if secrets.compare_digest(query.get("token", "").encode(), self.token.encode()):
            return "query"
        return "missing"


def _headers(scope: dict) -> dict[str, str]:
    """The request's headers, lower-case names; a repeated one keeps its first value."""
    out: dict[str, str] = {}
    for k, v in scope.get("headers", []):
        out.setdefault(k.decode("latin-1").lower(), v.decode("latin-1"))
    return out


_SECURITY_HEADERS = [(b"x-frame-options", b"DENY"), (b"content-security-policy", b"frame-ancestors 'none'"),
                     (b"referrer-policy", b"no-referrer"), (b"x-content-type-options", b"nosniff")]


class TooLarge(Exception):
    """A request body crossed its limit while streaming (raised from the request's ``receive``)."""


class Guard:
    """ASGI middleware: every request through :class:`Policy` (see the module docstring).

    ``body_limit(path)``: the largest body a request to ``path`` may send (default :data:`BODY_LIMIT`).
    """

    def __init__(self, app, policy: Policy, body_limit=None):
        self.app, self.policy = app, policy
        self.body_limit = body_limit or (lambda path: BODY_LIMIT)

    async def __call__(self, scope, receive, send):
        if scope["type"] not in ("http", "websocket"):
            return await self.app(scope, receive, send)
        refused = self.policy.refusal(scope)
        if refused is None:
            state = self.policy.token_state(scope)
            if state == "query" and scope["type"] == "http" and scope.get("method") in ("GET", "HEAD"):
                return await self._set_cookie(scope, send)
            if state == "missing":
                refused = (403, "this server asks for the token it printed when it started: open the URL it printed "
                                "(http://...?token=...)")
        if refused is not None:
            return await _refuse(scope, receive, send, *refused)
        if scope["type"] == "websocket":
            return await self.app(scope, receive, send)
        return await self._http(scope, receive, send)

    async def _http(self, scope, receive, send):
        limit = self.body_limit(scope.get("path", ""))
        length = _headers(scope).get("content-length")
        if length is not None:
            if not length.strip().isdigit():
                return await _refuse(scope, receive, send, 400, f"Content-Length {length!r} is not a number")
            if int(length) > limit:
                return await _refuse(scope, receive, send, 413, f"a request body of {int(length):,} bytes; "
                                     f"this address takes at most {limit:,}")
        seen = 0
        started = False

        async def counted():
            nonlocal seen
            message = await receive()
            if message["type"] == "http.request":
                seen += len(message.get("body", b""))
                if seen > limit:
                    raise TooLarge()
            return message

        async def secured(message):
            nonlocal started
            if message["type"] == "http.response.start":
                started = True
                names = {k.lower() for k, _ in message.get("headers", [])}
                message = {**message, "headers": [*message.get("headers", []),
                                                  *[(k, v) for k, v in _SECURITY_HEADERS if k not in names]]}
            await send(message)

        try:
            await self.app(scope, counted, secured)
        except TooLarge:
            if not started:
                await _refuse(scope, receive, send, 413, f"a request body of more than {limit:,} bytes; "
                                                         f"this address takes at most {limit:,}")

    async def _set_cookie(self, scope, send):
        """The token in the URL: the cookie, and the same URL without the token (not kept in the history)."""
        query = [(k, v) for k, v in parse_qsl(scope.get("query_string", b"").decode("latin-1")) if k != "token"]
        location = scope.get("path", "/") + ("?" + urlencode(query) if query else "")
        cookie = f"{self.policy.cookie}={self.policy.token}; Path=/; HttpOnly; SameSite=Strict"
        await send({"type": "http.response.start", "status": 303,
                    "headers": [(b"location", location.encode("latin-1")), (b"set-cookie", cookie.encode("latin-1")),
                                (b"content-length", b"0"), *_SECURITY_HEADERS]})
        await send({"type": "http.response.body", "body": b""})


async def _refuse(scope, receive, send, status: int, why: str) -> None:
    """Answer ``status`` with ``why`` (http), or close the websocket before accepting it (the client sees 403)."""
    if scope["type"] == "websocket":
        message = await receive()  # websocket.connect
        if message.get("type") == "websocket.connect":
            await send({"type": "websocket.close", "code": 1008, "reason": why[:120]})
        return
    body = f"synth ui refused this request: {why}\n".encode("utf-8")
    await send({"type": "http.response.start", "status": status,
                "headers": [(b"content-type", b"text/plain; charset=utf-8"), (b"content-length", str(len(body)).encode()),
                            (b"connection", b"close"), *_SECURITY_HEADERS]})
    await send({"type": "http.response.body", "body": body})
