"""The viewer answers its own page only: a foreign Origin or Host is refused (HTTP and the
websocket handshake), and malformed websocket frames are ignored without a traceback."""

from __future__ import annotations

import os
import subprocess
import sys
import time
import urllib.error
import urllib.request

import pytest

from myrabot_desc.view.guard import refusal


def test_refusal_rules():
    ok = {"Host": "127.0.0.1:8080", "Origin": "http://127.0.0.1:8080"}
    assert refusal(ok, "127.0.0.1", 8080) is None
    assert refusal({"Host": "localhost:8080", "Origin": "http://localhost:8080"}, "127.0.0.1", 8080) is None
    assert refusal({"Host": "127.0.0.1:8080"}, "127.0.0.1", 8080) is None        # no Origin: not a cross-site page
    assert "Origin" in refusal({**ok, "Origin": "http://evil.example"}, "127.0.0.1", 8080)
    assert "Origin" in refusal({**ok, "Origin": "http://127.0.0.1:9999"}, "127.0.0.1", 8080)
    assert "Origin" in refusal({**ok, "Origin": "null"}, "127.0.0.1", 8080)
    assert "Host" in refusal({"Host": "evil.example:8080", "Origin": "http://evil.example:8080"}, "127.0.0.1", 8080)
    # bound to every interface on purpose: any Host, but the Origin must be the page's own
    assert refusal({"Host": "10.0.0.5:8080", "Origin": "http://10.0.0.5:8080"}, "0.0.0.0", 8080) is None
    assert refusal({"Host": "10.0.0.5:8080", "Origin": "http://evil.example"}, "0.0.0.0", 8080) is not None


@pytest.fixture(scope="module")
def served():
    """A `myrabot-desc view` process (no check, no watch): (url, process)."""
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    p = subprocess.Popen([sys.executable, "-m", "myrabot_desc", "view", "--port", "0", "--no-watch", "--no-check"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    url = p.stdout.readline().strip()
    assert url.startswith("http://127.0.0.1:"), url
    yield url, p
    p.terminate()
    p.wait(timeout=30)


def _get(url, **headers):
    req = urllib.request.Request(url, headers=headers)
    try:
        with urllib.request.urlopen(req, timeout=30) as r:
            return r.status
    except urllib.error.HTTPError as e:
        return e.code


def _ws(url, origin, subprotocol=True):
    import viser
    from websockets.sync.client import connect

    return connect(url.replace("http://", "ws://"), origin=origin, open_timeout=30,
                   subprotocols=[f"viser-v{viser.__version__}"] if subprotocol else None)


def test_http_from_a_foreign_origin_is_refused(served):
    url, _ = served
    assert _get(url) == 200
    assert _get(url, Origin=url) == 200
    assert _get(url, Origin="http://evil.example") == 403
    host = url.split("//")[1]
    assert _get(url, Host=f"rebound.example:{host.split(':')[1]}") == 403       # DNS rebinding


def test_websocket_from_a_foreign_origin_is_refused(served):
    from websockets.exceptions import InvalidStatus

    url, _ = served
    with pytest.raises(InvalidStatus) as e:
        _ws(url, "http://evil.example")
    assert e.value.response.status_code == 403
    with _ws(url, url) as ws:                               # the page's own origin: the scene comes
        assert isinstance(ws.recv(timeout=30), bytes)


def test_malformed_frames_are_ignored_without_a_traceback(served):
    from msgspec.msgpack import encode as packb

    url, p = served
    with _ws(url, url) as ws:
        ws.recv(timeout=30)
        for frame in (b"\xff\x00garbage", "a text frame", packb({"type": "NoSuchMessage"}),
                      packb([1, 2, 3]), packb({"type": "GuiUpdateMessage", "uuid": "x",
                                                                "updates": {"value": 1}}), b""):
            ws.send(frame)
        time.sleep(1.0)
        ws.send(b"\x00")
    with _ws(url, url) as ws:                               # still serving
        assert isinstance(ws.recv(timeout=30), bytes)
    assert _get(url) == 200
    time.sleep(0.5)
    os.set_blocking(p.stderr.fileno(), False)
    err = p.stderr.read() or ""
    assert "Traceback" not in err, err[-2000:]
