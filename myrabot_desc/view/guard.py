"""The viewer answers its own page only.

viser serves the page and its websocket on one port and accepts any ``Origin``: a page of another
site open in the same browser could read the scene and move the sliders. :func:`install` puts a
check in front of viser's request handler: a request whose ``Host`` is not this server's loopback
address (a DNS-rebinding name), or whose ``Origin`` is not the page's own, is answered 403, the
websocket handshake included. Malformed websocket frames (not viser's msgpack, wrong types) are
ignored instead of ending the connection with a traceback; :func:`quiet_loop` keeps an error in a
message handler to one line.

viser (1.x) builds its server inside ``viser.infra._infra``; the check is given to it by handing
that module a ``websockets`` whose ``serve`` wraps ``process_request``, and a message consumer that
skips frames it cannot read. Nothing else in the process is changed.
"""

from __future__ import annotations

import sys

LOOPBACK = ("127.0.0.1", "localhost", "[::1]", "::1")
_installed = False


def refusal(headers, bound_host: str, port: int) -> str | None:
    """Why a request with these headers is refused, or None (plain function: tested alone)."""
    host = (headers.get("Host") or "").strip().lower()
    origin = (headers.get("Origin") or "").strip().lower()
    loopback = bound_host in LOOPBACK or bound_host.startswith("127.")
    if loopback:
        allowed = {f"{h}:{port}" for h in LOOPBACK if not h == "::1"} | {f"{bound_host}:{port}"}
        if host not in allowed:
            return f"Host {host or '(none)'} is not this viewer"
    if origin and origin != f"http://{host}":
        return f"Origin {origin} is not this viewer's page"
    return None


class _Proxy:
    """A module seen through, with a few attributes replaced."""

    def __init__(self, real, **over):
        self._real, self._over = real, over

    def __getattr__(self, name):
        if name in self._over:
            return self._over[name]
        return getattr(self._real, name)


def install() -> None:
    """Give viser's server module the guarded ``serve`` and the tolerant consumer (once)."""
    global _installed
    if _installed:
        return
    import http

    import websockets
    import websockets.asyncio.server
    from viser.infra import _infra
    from websockets.datastructures import Headers
    from websockets.http11 import Response

    real_serve = websockets.asyncio.server.serve

    def serve(handler, host, port, **kwargs):
        inner = kwargs.get("process_request")

        def process_request(connection, request):
            try:
                bound = connection.local_address[1]
            except Exception:
                bound = port
            why = refusal(request.headers, str(host), bound)
            if why is not None:
                body = f"forbidden: {why}\n".encode("ascii", "replace")
                return Response(http.HTTPStatus.FORBIDDEN, "Forbidden",
                                Headers({"Content-Type": "text/plain", "Content-Length": str(len(body))}), body)
            return inner(connection, request) if inner is not None else None

        kwargs["process_request"] = process_request
        return real_serve(handler, host, port, **kwargs)

    server_mod = _Proxy(websockets.asyncio.server, serve=serve)
    _infra.websockets = _Proxy(websockets, asyncio=_Proxy(websockets.asyncio, server=server_mod))

    async def consumer(websocket, handle_message, message_class):
        """viser's consumer, skipping what is not a message (it raised, ending the connection with a
        traceback)."""
        while True:
            raw = await websocket.recv()
            if not isinstance(raw, bytes):
                continue
            try:
                message = message_class.deserialize(raw)
            except Exception:
                continue
            try:
                handle_message(message)
            except Exception:
                continue

    _infra._message_consumer = consumer
    _installed = True


def quiet_loop(server) -> None:
    """An exception in a message handler task (a well-formed message with values the handler cannot
    use) prints one line, not a traceback."""
    ws = getattr(server, "_websock_server", None)
    loop = getattr(ws, "_background_event_loop", None)
    if loop is None:
        return

    def handler(loop, context):
        exc = context.get("exception")
        what = f"{type(exc).__name__}: {exc}" if exc is not None else context.get("message", "error")
        print(f"myrabot-desc view: ignored a message the page could not have sent ({what})"[:300], file=sys.stderr)

    loop.call_soon_threadsafe(loop.set_exception_handler, handler)
