"""``synth ui`` as a server, by raw requests (issue 39): what it answers, what it refuses, and how it stops.

Each test reproduces a probe of issue 39 against a real server process (``python -m synth ui``): a foreign
``Host`` (DNS rebinding) and a foreign ``Origin`` on HTTP, socket.io polling and the websocket, a page of another
port, the token beyond the loopback, a 2 GB upload refused while it streams, a 305-character file name, crafted
socket events, an input's design rules, SIGTERM during a 100,000-application screening. A page is driven as its
browser would: the page's HTML gives its elements and client id, python-socketio speaks to its socket.
The browser's view of the same doors: ``tests/test_ui_browser.py``.
"""

from __future__ import annotations

import asyncio
import json
import re
import select
import signal
import socket
import time
import uuid
from pathlib import Path

import pytest

pytest.importorskip("nicegui")
httpx = pytest.importorskip("httpx")
socketio = pytest.importorskip("socketio")
pytest.importorskip("aiohttp")  # python-socketio's asyncio client transport

from synth.ui.browser import free_port, start_server, stop_server  # noqa: E402

MB = 1024 * 1024
WS = "/_nicegui_ws/socket.io/"


# --- a server, a page, raw requests --------------------------------------------------------------------------------
class Server:
    def __init__(self, tmp: Path, *args: str):
        self.port = free_port()
        self.tmp = tmp
        (tmp / "t").mkdir(parents=True, exist_ok=True)
        self.log = tmp / "server.log"
        self.proc, self.line = start_server(self.port, *args, env={"TMPDIR": str(tmp / "t")}, output=self.log)
        self.base = f"http://127.0.0.1:{self.port}"
        deadline = time.perf_counter() + 60
        while True:
            try:
                httpx.get(self.base + "/favicon.ico", timeout=5)
                break
            except httpx.TransportError:
                if time.perf_counter() > deadline or self.proc.poll() is not None:
                    raise RuntimeError("synth ui did not start: " + self.output())
                time.sleep(0.1)

    def output(self) -> str:
        return self.log.read_text(encoding="utf-8", errors="replace")

    def uploads_left(self) -> list[Path]:
        """Files of uploads still in the server's temporary folder (synth's ``upload-*``, a spooled ``tmp*``)."""
        root = self.tmp / "t"
        return [p for p in root.rglob("*") if p.is_file()
                and ("upload" in p.relative_to(root).as_posix() or p.name.startswith("tmp"))]

    def peak_rss_mb(self) -> float:
        status = Path(f"/proc/{self.proc.pid}/status").read_text()
        return int(re.search(r"VmHWM:\s+(\d+) kB", status).group(1)) / 1024


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    s = Server(tmp_path_factory.mktemp("ui-server"))
    try:
        yield s
    finally:
        stop_server(s.proc)


def raw(port: int, head: list[str], body: bytes = b"", timeout: float = 30.0) -> tuple[int, dict, bytes]:
    """One request over a socket, exactly the header lines given (``Host`` included): status, headers, body."""
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as s:
        s.sendall(("\r\n".join(head) + "\r\n\r\n").encode("latin-1") + body)
        data = b""
        while b"\r\n\r\n" not in data:
            chunk = s.recv(65536)
            if not chunk:
                break
            data += chunk
        head_bytes, _, rest = data.partition(b"\r\n\r\n")
        lines = head_bytes.decode("latin-1").split("\r\n")
        status = int(lines[0].split()[1])
        headers = {}
        for ln in lines[1:]:
            k, _, v = ln.partition(":")
            headers.setdefault(k.strip().lower(), v.strip())
        n = headers.get("content-length")
        while (n is None and status != 101) or len(rest) < int(n or 0):  # no length: until the server closes
            chunk = s.recv(65536)
            if not chunk:
                break
            rest += chunk
        return status, headers, rest


def get(port: int, path: str, host: str | None = None, **headers) -> tuple[int, dict, bytes]:
    headers.setdefault("Connection", "close")
    lines = [f"GET {path} HTTP/1.1", f"Host: {host or f'127.0.0.1:{port}'}"]
    lines += [f"{k.replace('_', '-')}: {v}" for k, v in headers.items()]
    return raw(port, lines)


def websocket(port: int, host: str | None = None, **headers) -> int:
    """The status of a websocket handshake to the socket.io endpoint (101: opened)."""
    return get(port, WS + "?EIO=4&transport=websocket", host=host, Upgrade="websocket", Connection="Upgrade",
               Sec_WebSocket_Key="dGhlIHNhbXBsZSBub25jZQ==", Sec_WebSocket_Version="13", **headers)[0]


def elements_of(html: str) -> dict:
    """The page's elements as NiceGUI embeds them (its ``parseElements(String.raw`...`)``)."""
    raw_json = re.search(r"parseElements\(String\.raw`(.*?)`\)", html, re.S).group(1)
    for a, b in (("&#36;", "$"), ("&#96;", "`"), ("&gt;", ">"), ("&lt;", "<"), ("&amp;", "&")):
        raw_json = raw_json.replace(a, b)
    return {int(k): v for k, v in json.loads(raw_json).items()}


def texts(o):
    """Every text the server sent a page (labels' text, HTML content, notifications)."""
    if isinstance(o, dict):
        for k, v in o.items():
            if k in ("text", "innerHTML", "content", "message") and isinstance(v, str):
                yield v
            else:
                yield from texts(v)
    elif isinstance(o, (list, tuple)):
        for v in o:
            yield from texts(v)


class Page:
    """A page as its browser holds it: its elements, its socket; what the server sent it in ``received``."""

    def __init__(self, server: Server, path: str):
        self.server = server
        html = httpx.get(server.base + path, timeout=120).text
        self.client_id = re.search(r"'client_id': '([^']+)'", html).group(1)
        self.elements = elements_of(html)
        self.received: list = []

    def find(self, **props) -> int:
        hits = [i for i, e in self.elements.items()
                if all(e.get("props", {}).get(k) == v or e.get(k) == v for k, v in props.items())]
        assert hits, f"no element with {props}"
        return hits[0]

    def upload_url(self) -> str:
        return next(e["props"]["url"] for e in self.elements.values() if "upload" in e.get("tag", ""))

    async def connect(self) -> None:
        self.sio = socketio.AsyncClient()
        self.sio.on("*", lambda event, data=None: self.received.append((event, data)))
        q = (f"client_id={self.client_id}&tab_id={uuid.uuid4()}&document_id={uuid.uuid4()}&next_message_id=0"
             "&implicit_handshake=true")
        await self.sio.connect(f"{self.server.base}/?{q}", socketio_path=WS.strip("/"), transports=["websocket"])

    async def event(self, element: int, kind: str, *args) -> None:
        listener = next(ev["listener_id"] for ev in self.elements[element]["events"] if ev["type"] == kind)
        await self.sio.emit("event", {"id": element, "client_id": self.client_id, "listener_id": listener,
                                      "args": [json.dumps(a) for a in args]})

    def notes(self) -> list[str]:
        return [d.get("message", "") for e, d in self.received if e == "notify" and isinstance(d, dict)]

    def shown(self) -> str:
        return "\n".join(texts(self.received))

    async def wait_for(self, pred, timeout: float = 120.0, what: str = "") -> None:
        deadline = time.perf_counter() + timeout
        while not pred():
            if time.perf_counter() > deadline:
                raise AssertionError(f"the page never showed {what}; notes: {self.notes()[-3:]}; server: "
                                     + self.server.output()[-1500:])
            await asyncio.sleep(0.1)

    async def close(self) -> None:
        await self.sio.disconnect()


def run(coro):
    return asyncio.run(coro)


# --- Host, Origin, token ---------------------------------------------------------------------------------------------
def test_a_foreign_host_is_refused_on_http_polling_and_websocket(server):
    """DNS rebinding: attacker.example resolved to 127.0.0.1 reaches the server with its own name in Host."""
    port = server.port
    assert get(port, "/")[0] == 200
    for path in ("/", "/portfolio", WS + "?EIO=4&transport=polling", "/favicon.ico"):
        status, _, body = get(port, path, host=f"attacker.example:{port}")
        assert status == 403, path
        assert b"Host 'attacker.example:" in body and b"is not this server's" in body
    assert websocket(port, host=f"attacker.example:{port}") == 403
    assert websocket(port, host=f"attacker.example:{port}", Origin=f"http://attacker.example:{port}") == 403
    assert get(port, "/", host=f"127.0.0.1:{port + 1}")[0] == 403  # the right name, another port
    assert get(port, "/", host=f"localhost:{port}")[0] == 200


def test_a_foreign_origin_is_refused_on_http_polling_and_websocket(server):
    port = server.port
    own = f"http://127.0.0.1:{port}"
    for origin in ("http://evil.example", f"http://127.0.0.1:{port + 1}", f"https://127.0.0.1:{port}", "null"):
        status, headers, _ = get(port, "/", Origin=origin)
        assert status == 403, origin
        status, headers, _ = get(port, WS + "?EIO=4&transport=polling", Origin=origin)
        assert status == 403 and "access-control-allow-origin" not in headers, origin
        assert websocket(port, Origin=origin) == 403, origin
    status, headers, body = get(port, WS + "?EIO=4&transport=polling", Origin=own)
    assert status == 200 and headers["access-control-allow-origin"] == own and b'"sid"' in body
    assert websocket(port, Origin=own) == 101
    # a page of another site or port fetching a resource (an image, a script): refused though it sends no Origin
    assert get(port, "/favicon.ico", Sec_Fetch_Site="same-site", Sec_Fetch_Mode="no-cors",
               Sec_Fetch_Dest="image")[0] == 403
    assert get(port, "/", Sec_Fetch_Site="cross-site", Sec_Fetch_Mode="navigate", Sec_Fetch_Dest="iframe")[0] == 403
    assert get(port, "/", Sec_Fetch_Site="cross-site", Sec_Fetch_Mode="navigate", Sec_Fetch_Dest="document")[0] == 200
    status, headers, _ = get(port, "/")
    assert headers["x-frame-options"] == "DENY" and "frame-ancestors 'none'" in headers["content-security-policy"]


def test_bound_beyond_the_loopback_the_server_asks_for_its_token(tmp_path):
    s = Server(tmp_path, "--host", "0.0.0.0")
    try:
        m = re.search(r"http://([^/]+)/\?token=([\w-]+) \(bound to 0\.0\.0\.0: REACHABLE", s.line)
        assert m, s.line
        token, port = m.group(2), s.port
        status, _, body = get(port, "/")
        assert status == 403 and b"token" in body
        assert get(port, "/?token=wrong")[0] == 403
        assert websocket(port, Origin=f"http://127.0.0.1:{port}") == 403
        status, headers, _ = get(port, f"/portfolio?token={token}")
        assert status == 303 and headers["location"] == "/portfolio"  # the token leaves the address bar
        cookie = headers["set-cookie"].split(";")[0]
        assert cookie == f"synth-ui-token-{port}={token}" and "HttpOnly" in headers["set-cookie"]
        assert get(port, "/", Cookie=cookie)[0] == 200
        assert get(port, "/", Authorization=f"token {token}")[0] == 200
        assert websocket(port, Origin=f"http://127.0.0.1:{port}", Cookie=cookie) == 101
        assert get(port, "/", host=f"{socket.gethostname()}:{port}", Cookie=cookie)[0] == 200  # the machine's name
        assert get(port, "/", host=f"attacker.example:{port}", Cookie=cookie)[0] == 403
    finally:
        stop_server(s.proc)


# --- uploads ---------------------------------------------------------------------------------------------------------
def _stream(port: int, url: str, total: int, limit: int, chunk: int = MB) -> dict:
    """Stream a ``total``-byte file (chunked: no length announced) until the server answers; when it crossed
    ``limit`` and when the answer came."""
    boundary = "synthtestboundary"
    head = (f"POST {url} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nOrigin: http://127.0.0.1:{port}\r\n"
            f"Content-Type: multipart/form-data; boundary={boundary}\r\nTransfer-Encoding: chunked\r\n\r\n")
    part = (f'--{boundary}\r\nContent-Disposition: form-data; name="file"; filename="big.csv"\r\n'
            "Content-Type: text/csv\r\n\r\n").encode()
    block = (b"application_id,pulley_diameter_mm\n" + b"A,62\n" * (chunk // 5))[:chunk]
    out = {"sent": 0, "crossed": None, "answered": None, "answer": b""}
    with socket.create_connection(("127.0.0.1", port)) as s:
        s.settimeout(0.2)
        s.sendall(head.encode() + f"{len(part):x}\r\n".encode() + part + b"\r\n")
        while out["sent"] < total:
            readable, _, _ = select.select([s], [], [], 0)
            if readable:
                break
            try:
                s.sendall(f"{len(block):x}\r\n".encode() + block + b"\r\n")
            except socket.timeout:
                pass
            except OSError:  # the server closed the connection: the refusal
                break
            out["sent"] += len(block)
            if out["crossed"] is None and out["sent"] > limit:
                out["crossed"] = time.perf_counter()
            if out["crossed"] is not None and time.perf_counter() - out["crossed"] > 3.0:
                return out  # no answer 3 s after the limit: still reading
        out["answered"] = time.perf_counter()
        s.settimeout(5)
        try:
            while len(out["answer"]) < 100000:
                got = s.recv(65536)
                if not got:
                    break
                out["answer"] += got
        except OSError:
            pass
    return out


def test_a_2gb_upload_is_refused_within_1s_of_crossing_the_limit_and_its_copy_removed(server):
    page = Page(server, "/")
    url = page.upload_url()
    port, limit = server.port, 16 * MB
    # announced: refused before a byte of it is read
    t = time.perf_counter()
    try:
        status, _, body = raw(port, [f"POST {url} HTTP/1.1", f"Host: 127.0.0.1:{port}",
                                     f"Origin: http://127.0.0.1:{port}", "Content-Type: multipart/form-data; boundary=x",
                                     f"Content-Length: {2 * 1024 ** 3}"], timeout=5)
    except socket.timeout:
        status, body = None, b"no answer in 5 s: the server waits for the 2 GB"
    assert status == 413 and time.perf_counter() - t < 1.0, body
    # streamed without a length: counted as it comes
    rss = server.peak_rss_mb()
    out = _stream(port, url, total=2 * 1024 ** 3, limit=limit)
    assert out["crossed"] is not None, out
    assert out["answered"] is not None, f"no answer 3 s after crossing the limit (sent {out['sent'] / MB:.0f} MB)"
    delay = out["answered"] - out["crossed"]
    print(f"\nupload refused {delay:.3f} s after crossing the limit, {out['sent'] / MB:.0f} MB sent")
    assert delay < 1.0
    assert out["sent"] < limit + 64 * MB
    assert out["answer"].startswith(b"HTTP/1.1 413") and b"at most 16 MB" in out["answer"]
    assert server.uploads_left() == [], "the refused upload's copy is still in the temporary folder"
    assert server.peak_rss_mb() - rss < 64, "the upload was held in memory"


def test_a_305_character_file_name_is_a_message_in_the_page_not_a_traceback(server):
    async def go():
        page = Page(server, "/")
        await page.connect()
        name = "n" * 300 + ".yaml"
        r = httpx.post(server.base + page.upload_url(), files={"file": (name, b"pulley_diameter_mm: 62\n")},
                       headers={"Origin": server.base}, timeout=60)
        await page.wait_for(lambda: any("file name" in n for n in page.notes()), 30, "the file name's message")
        await page.close()
        return r, page.notes()
    r, notes = run(go())
    assert r.status_code == 400
    assert any("input file name: got 'nnnn" in n and "(305 characters)" in n and "at most 200 characters" in n
               for n in notes), notes
    assert "Traceback" not in server.output()
    assert server.uploads_left() == []


# --- events the page could not send ------------------------------------------------------------------------------------
def test_crafted_socket_events_are_refused_with_a_message_never_a_traceback(server):
    async def go():
        page = Page(server, "/portfolio")
        await page.connect()
        number, table = page.find(label="applications"), page.find(tag="nicegui-table")
        await page.event(number, "update:modelValue", 5)
        await page.event(page.find(label="Synthetic sample"), "click", {})
        await page.wait_for(lambda: "5 applications from sample" in page.shown(), 120, "the sample")
        await page.event(page.find(**{"data-testid": "run"}), "click", {})
        await page.wait_for(lambda: "feasible share:" in page.shown(), 300, "the screening")
        crafted = [[{}, {"#": "abc"}, 0], [{}, {"#": 10 ** 9}, 0], [{}, {"#": -1}, 0], [{}, {"#": 1.5}, 0],
                   [{}, {"#": True}, 0], [{}, "row", 0], "garbage", [{}], None]
        for args in crafted:
            await page.event(table, "rowClick", *([args] if not isinstance(args, list) else args))
        await page.event(number, "update:modelValue", "abc")
        await page.event(page.find(label="fidelity"), "update:modelValue", {"value": 99})
        await page.sio.emit("event", {"id": table, "client_id": page.client_id, "listener_id": "nope", "args": []})
        await page.sio.emit("event", {"id": table, "client_id": page.client_id,
                                      "listener_id": page.elements[table]["events"][-1]["listener_id"],
                                      "args": ["{not json"]})
        await page.sio.emit("event", "garbage")
        await page.sio.emit("log", {"client_id": page.client_id, "level": "evil", "message": "x"})
        await page.sio.emit("handshake", {"client_id": page.client_id})
        await page.wait_for(lambda: sum("refused" in n or "row:" in n for n in page.notes()) >= len(crafted) + 5,
                            30, "a message for each crafted event")
        await page.event(table, "rowClick", {}, {"#": 3}, 3)  # a real click still opens its application
        await page.wait_for(lambda: any(e == "open" for e, _ in page.received), 30, "the design page opened")
        await page.close()
        return page.notes()
    notes = run(go())
    rows = [n for n in notes if "row: got" in n]
    assert len(rows) >= 7 and all("accepted: a row number of the table, an integer in [0, 4]" in n or
                                  "accepted: a row of the table" in n for n in rows), rows
    assert any("applications: got 'abc'; accepted: a finite number" in n for n in notes), notes
    assert any("fidelity: got {'value': 99}; accepted: an option of the drop-down" in n for n in notes), notes
    out = server.output()
    assert "Traceback" not in out and "IndexError" not in out and "Error: invalid literal" not in out, out[-3000:]


# --- rules -----------------------------------------------------------------------------------------------------------
def _ruled_input(tmp_path: Path) -> Path:
    import yaml

    from synth.ui.session import default_values
    d = default_values()
    d["rules"] = {"name": "ACME rev C", "min_margins": {"spring_yield": "50 %"}}
    path = tmp_path / "ruled.yaml"
    path.write_text(yaml.safe_dump(d), encoding="utf-8")
    return path


def test_an_input_with_rules_opened_in_the_page_is_judged_under_them_as_the_command_line_does(server, tmp_path):
    import synth
    path = _ruled_input(tmp_path)
    cli = synth.synthesise(path)  # the input file's rules, as synth design reads them
    assert cli.verdict == "fail" and cli.rules["name"] == "ACME rev C"

    async def go():
        page = Page(server, "/")
        await page.connect()
        r = httpx.post(server.base + page.upload_url(), files={"file": ("ruled.yaml", path.read_bytes())},
                       headers={"Origin": server.base}, timeout=60)
        assert r.status_code == 200
        await page.wait_for(lambda: "design rules: ACME rev C" in page.shown() and "verdict fail" in page.shown(),
                            120, "the verdict under the rules")
        await page.close()
        return page.shown()
    shown = run(go())
    assert "design rules: ACME rev C (ruled.yaml: rules): minimum margin spring_yield: 50 %" in shown
    assert f"{cli.status} design" in shown and "Verdict: PASS" not in shown
    assert server.uploads_left() == []  # read, then removed


def test_synth_ui_input_with_rules_opens_under_them(tmp_path):
    s = Server(tmp_path, str(_ruled_input(tmp_path)))
    try:
        html = httpx.get(s.base + "/", timeout=120).text
        els = elements_of(html)
        shown = [e.get("text", "") for e in els.values()]
        assert any(t.startswith("design rules: ACME rev C") for t in shown), shown
        assert any(t.endswith("verdict fail") for t in shown)
    finally:
        stop_server(s.proc)


# --- SIGTERM ---------------------------------------------------------------------------------------------------------
def test_sigterm_during_a_100000_application_screening_exits_143_within_5s(tmp_path):
    import pandas as pd

    from synth.bulk.sample import sample_portfolio
    base = sample_portfolio(50, seed=4)
    table = pd.concat([base] * 2000, ignore_index=True)
    table["application_id"] = [f"APP-{i:06d}" for i in range(len(table))]
    path = tmp_path / "fleet.csv"
    table.to_csv(path, index=False)
    s = Server(tmp_path)
    try:
        async def go():
            page = Page(s, "/portfolio")
            await page.connect()
            with open(path, "rb") as f:
                r = httpx.post(s.base + page.upload_url(), files={"file": ("fleet.csv", f)},
                               headers={"Origin": s.base}, timeout=120)
            assert r.status_code == 200, r.text
            await page.wait_for(lambda: "100000 applications from fleet.csv" in page.shown(), 120, "the portfolio")
            await page.event(page.find(**{"data-testid": "run"}), "click", {})
            await page.wait_for(lambda: " of 100000 applications" in page.shown(), 60, "the screening's progress")
            await asyncio.sleep(1.0)
            assert "feasible share:" not in page.shown()  # still screening
            await page.close()
        run(go())
        t = time.perf_counter()
        s.proc.send_signal(signal.SIGTERM)
        try:
            rc = s.proc.wait(10)
        except Exception:  # noqa: BLE001 - still running: the defect
            rc = None
        took = time.perf_counter() - t
        print(f"\nSIGTERM during the screening: exit {rc} after {took:.2f} s")
        assert rc == 143 and took < 5.0, s.output()[-2000:]
        assert "synth ui: terminated (SIGTERM)" in s.output()
        assert "Traceback" not in s.output()
    finally:
        stop_server(s.proc)
