"""Running the app: uvicorn on loopback unless another host is asked for."""
from __future__ import annotations

import threading
import warnings

from kinelab._memory import reuse_result_memory
from kinelab.errors import ModelError
from kinelab.web import _apart
from kinelab.web._limits import cache_bytes

__all__ = ["serve", "LOOPBACK"]

LOOPBACK = ("127.0.0.1", "localhost", "::1")


def serve(start: dict | None = None, *, host: str = "127.0.0.1", port: int = 8000,
          announce=print) -> None:
    """Serve the app until interrupted.  ``announce(address)`` is called once the server
    listens (default: print it).  A host other than loopback is served with a warning: the
    app has no accounts, and anyone who reaches the address can use it.  Requests must name
    the address served (its ``Host``), and come from the page itself (see
    :func:`~kinelab.web.create_app`)."""
    import uvicorn

    from kinelab.web._app import create_app

    if not (isinstance(port, int) and 0 <= port <= 65535):
        raise ModelError(f"port: expected a whole number from 0 to 65535, got {port!r}")
    if host not in LOOPBACK:
        warnings.warn(f"serving on {host}: anyone who can reach this address can use the app "
                      "(it has no accounts); serve on 127.0.0.1 unless you mean it",
                      stacklevel=2)
    # the memory of dropped results kept for the next ones (1 GiB by default, for long runs
    # of large sweeps) is, in a server, memory held between requests: as much as its cache
    kept = reuse_result_memory(0)
    reuse_result_memory(min(kept, cache_bytes()))
    app = create_app(start, host=host, port=port or None)
    config = uvicorn.Config(app, host=host, port=port, log_level="warning", lifespan="off",
                            http=_json_errors_protocol())
    server = uvicorn.Server(config)

    original = server.startup

    async def startup(sockets=None):
        await original(sockets=sockets)
        if server.started:
            bound = server.servers[0].sockets[0].getsockname()[:2] if server.servers else (host, port)
            app.state.served.port = bound[1]        # port 0: the one the system gave
            shown = f"[{bound[0]}]" if ":" in bound[0] else bound[0]
            announce(f"http://{shown}:{bound[1]}/")
    server.startup = startup
    # the first derivation need not wait for its worker process to start
    threading.Thread(target=_apart.prestart, name="kinelab-prestart", daemon=True).start()
    try:
        server.run()
    finally:
        reuse_result_memory(kept)


def _json_errors_protocol():
    """uvicorn's HTTP/1.1 protocol, whose own answer to a request it cannot read (400) is
    JSON like every answer of the app's, not plain text."""
    import json

    import h11
    from uvicorn.protocols.http.h11_impl import H11Protocol

    class JSONErrors(H11Protocol):
        def send_400_response(self, msg: str) -> None:
            body = json.dumps({"error": f"request: {msg}; send an HTTP/1.1 request"}).encode()
            headers = [(b"content-type", b"application/json"),
                       (b"content-length", str(len(body)).encode()), (b"connection", b"close")]
            for event in (h11.Response(status_code=400, headers=headers, reason=b"Bad Request"),
                          h11.Data(data=body), h11.EndOfMessage()):
                self.transport.write(self.conn.send(event))
            self.transport.close()
    return JSONErrors
