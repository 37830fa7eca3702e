"""Running the app: uvicorn on loopback unless another host is asked for."""
from __future__ import annotations

import warnings

from kinelab.errors import ModelError

__all__ = ["serve", "LOOPBACK"]

LOOPBACK = ("127.0.0.1", "localhost", "::1")


def serve(start: dict | None = None, *, host: str = "127.0.0.1", port: int = 8000,
          announce=print) -> None:
    """Serve the app until interrupted.  ``announce(address)`` is called once the server
    listens (default: print it).  A host other than loopback is served with a warning: the
    app has no accounts, and anyone who reaches the address can use it."""
    import uvicorn

    from kinelab.web._app import create_app

    if not (isinstance(port, int) and 0 <= port <= 65535):
        raise ModelError(f"port: expected a whole number from 0 to 65535, got {port!r}")
    if host not in LOOPBACK:
        warnings.warn(f"serving on {host}: anyone who can reach this address can use the app "
                      "(it has no accounts); serve on 127.0.0.1 unless you mean it",
                      stacklevel=2)
    config = uvicorn.Config(create_app(start), host=host, port=port, log_level="warning",
                            lifespan="off")
    server = uvicorn.Server(config)

    original = server.startup

    async def startup(sockets=None):
        await original(sockets=sockets)
        if server.started:
            bound = server.servers[0].sockets[0].getsockname()[:2] if server.servers else (host, port)
            shown = f"[{bound[0]}]" if ":" in bound[0] else bound[0]
            announce(f"http://{shown}:{bound[1]}/")
    server.startup = startup
    server.run()
