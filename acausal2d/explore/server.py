"""The explore web application (Starlette on uvicorn) and :func:`serve`.

Routes (the page uses nothing else)::

    GET  /             the page
    GET  /api/params   the model: parameters (unit, rule, value, slider range;
                       not those read while compiling, listed as "structural"),
                       signals with units, figures, default and largest stop time
    POST /api/run      a run: {"time", "signals", "elapsed_s", "stopped", ...}
    POST /api/csv      the same run as CSV (every column), for the export button
    POST /api/start    a run request with "drag": {"x", "y", "to"}: the start values
                       ({"start": {unknown: value}}) that put that point at "to"

Every request passes :class:`~acausal2d.explore.guard.Guard` first: the
``Host`` of the listening address, the server's token (in the printed URL,
``?token=``) on ``/api/``, the server's own ``Origin`` and JSON on a POST,
a bounded body (403, 415, 413, 408 otherwise).

Answers: 200 with the run (its "run" number counts the server's runs in
the order they came); 400 ``{"error", "field"}`` for a bad request
(:mod:`acausal2d.explore.requests`); 409 ``{"error"}`` for a run overtaken
by a newer one of its session; 422 ``{"error"}`` with the run's own message
when the model cannot run with these values (a geometry that cannot
assemble, an integrator failure).  The server writes nothing to disk.
"""
import asyncio
import importlib.resources
import json
import secrets

from ..errors import Acausal2dError
from ..io.output import interrupt_is_the_end
from .guard import Guard, allowed_hosts, protocol
from .requests import BadRequest
from .runner import Superseded


def _json(data, status=200):
    from starlette.responses import Response
    return Response(json.dumps(data, allow_nan=False, separators=(",", ":")), status,
                    media_type="application/json")


def _asset(name):
    return (importlib.resources.files("acausal2d.explore") / "assets" / name).read_text("utf-8")


def page_html():
    """The explore page: its HTML with the CSS and script inlined."""
    return (_asset("explore.html").replace("%%CSS%%", _asset("explore.css"))
            .replace("%%JS%%", _asset("explore.js")).replace("%%DIAGRAM_JS%%", _asset("diagram.js")))


def make_app(explorer, token, hosts):
    """The application serving ``explorer`` (an
    :class:`~acausal2d.explore.runner.Explorer`): Starlette's routes behind
    :class:`~acausal2d.explore.guard.Guard` (``token``: the API's token;
    ``hosts``: the allowed ``Host`` values, a set filled in once the port
    is known)."""
    from starlette.applications import Starlette
    from starlette.responses import HTMLResponse, Response
    from starlette.routing import Route
    page = page_html()

    async def index(request):
        return HTMLResponse(page)

    async def params(request):
        return _json(explorer.describe())

    async def run(request):
        return await _run(request, explorer.answer, _json)

    async def csv(request):
        def text(spec, res, elapsed):
            return explorer.csv_text(res)
        return await _run(request, text, lambda body: Response(
            body, media_type="text/csv",
            headers={"Content-Disposition": 'attachment; filename="%s.csv"' % (
                type(explorer.compiled.model).__name__)}))

    async def _run(request, render, respond):
        try:
            spec = explorer.parse(await request.body())
        except BadRequest as exc:
            return _json({"error": str(exc), "field": exc.field}, 400)
        future = explorer.submit(spec, lambda res, elapsed: render(spec, res, elapsed))
        try:
            return respond(await asyncio.wrap_future(future))
        except Superseded as exc:
            return _json({"error": str(exc), "superseded": True, "run": exc.run}, 409)
        except Acausal2dError as exc:
            return _json({"error": str(exc)}, 422)

    async def start(request):
        try:
            spec = explorer.parse(await request.body(), drag=True)
        except BadRequest as exc:
            return _json({"error": str(exc), "field": exc.field}, 400)
        try:
            return _json(await asyncio.wrap_future(explorer.submit_drag(spec)))
        except Acausal2dError as exc:
            return _json({"error": str(exc)}, 422)

    routes = [Route("/", index), Route("/api/params", params),
              Route("/api/run", run, methods=["POST"]), Route("/api/csv", csv, methods=["POST"]),
              Route("/api/start", start, methods=["POST"])]
    return Guard(Starlette(routes=routes), token, hosts)


def serve(explorer, host="127.0.0.1", port=8765, open_browser=False, announce=print):
    """Serve ``explorer`` on ``host``:``port`` (0: a free port) until
    Ctrl-C; ``announce(url)`` is called once the server accepts
    connections (the URL carries the token the API needs), then the page is opened in a browser if ``open_browser``.
    Returns 0 after Ctrl-C (the run in progress finished, nothing written)."""
    import uvicorn

    class _Server(uvicorn.Server):
        async def startup(self, sockets=None):
            await super().startup(sockets=sockets)
            if self.should_exit or not self.servers:
                return
            bound = self.servers[0].sockets[0].getsockname()[1]
            hosts.update(allowed_hosts(host, bound))
            url = "http://%s:%d/?token=%s" % (host if ":" not in host else "[%s]" % host, bound,
                                               token)
            announce(url)
            if open_browser:
                import webbrowser
                webbrowser.open(url)

    token, hosts = secrets.token_urlsafe(24), set()
    config = uvicorn.Config(make_app(explorer, token, hosts), host=host, port=port,
                            log_level="warning", access_log=False, lifespan="off",
                            http=protocol(), timeout_keep_alive=5, limit_concurrency=64)
    server = _Server(config)
    try:
        server.run()
    except KeyboardInterrupt:    # uvicorn shut down cleanly, then raised Ctrl-C again
        pass
    finally:
        interrupt_is_the_end()   # Ctrl-C is how the server ends: the command's code stands
        explorer.close()
    return 0 if server.started else 2
