"""The explore server's gate: every request passes it before any route
(a route added later is covered without a word), so that neither another
web page in the user's browser nor another user of the machine can use
the server.

- ``Host`` must be the address the server listens on (``localhost``,
  ``127.0.0.1`` and ``[::1]`` with its port count as that address for a
  loopback server): a DNS-rebinding page, whose ``Host`` is its own name,
  gets 403;
- ``/api/`` needs the server's token (made at start, in the page's URL
  as ``?token=``, sent by the page as the header :data:`TOKEN_HEADER`, as
  Jupyter does): 403 without it;
- a request that changes state (POST) is refused (403) when its ``Origin``
  is not the server's own or the browser marks it cross-site
  (``Sec-Fetch-Site``), and answered 415 unless it is
  ``application/json`` (which a browser never sends across origins
  without a preflight this server does not answer);
- its body is read here, at most :data:`~acausal2d.explore.requests.
  MAX_BODY` bytes (413 past that, before the rest is read), each chunk
  within :data:`BODY_SECONDS` (408); a client that goes away mid-body is
  logged in one line.

Refusals are JSON ``{"error": message, "field": null}`` naming what to
change.
"""
import asyncio
import hmac
import json
import socket
import sys
from urllib.parse import parse_qs

from .requests import MAX_BODY

TOKEN_HEADER = "x-acausal2d-token"
BODY_SECONDS = 10.0
"""Longest wait for the next chunk of a request body (a client that
trickles its body holds no run and no memory beyond it)."""
HEADER_SECONDS = 10.0
"""Longest time a connection may take to send a request's headers."""
CHANGES_STATE = ("POST", "PUT", "PATCH", "DELETE")
_LOOPBACK = ("127.0.0.1", "localhost", "::1", "[::1]")


def log(message):
    """One line ``acausal2d explore: <message>`` on stderr."""
    print("acausal2d explore: " + message, file=sys.stderr, flush=True)


def allowed_hosts(host, port):
    """The ``Host`` header values of a server listening on ``host``:``port``."""
    names = {host, "[%s]" % host} if ":" in host else {host}
    if host in _LOOPBACK:
        names |= {"127.0.0.1", "localhost", "[::1]"}
    elif host in ("0.0.0.0", "::", ""):      # every address: this machine's names and loopback
        names |= {"127.0.0.1", "localhost", "[::1]", socket.gethostname(), socket.getfqdn()}
    values = {"%s:%d" % (n.lower(), port) for n in names}
    if port == 80:
        values |= {n.lower() for n in names}
    return values


class Guard:
    """ASGI middleware around the explore application (see the module
    docstring); ``hosts`` is a set of allowed ``Host`` values, filled in
    once the server knows its port (empty: every request is refused)."""

    def __init__(self, app, token, hosts):
        self.app, self.token, self.hosts = app, token, hosts

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        headers = {k.decode("latin-1").lower(): v.decode("latin-1")
                   for k, v in scope.get("headers", [])}
        refused = self.refusal(scope, headers)
        if refused is not None:
            return await answer(send, *refused)
        if scope["method"] in CHANGES_STATE:
            body = await self.body(scope, receive, send, headers)
            if body is None:
                return None
            receive = _replay(body)
        return await self.app(scope, receive, send)

    def refusal(self, scope, headers):
        """(status, message) of a request refused before its body, or None."""
        host = headers.get("host", "").lower()
        if host not in self.hosts:
            return 403, ("Host %r is not the address this server listens on (%s); open the "
                         "URL the server printed" % (host[:100], ", ".join(sorted(self.hosts))))
        if scope["path"].startswith("/api/") and not self._has_token(scope, headers):
            return 403, ("the API needs this server's token: open the URL the server printed "
                         "(with ?token=...), or send it as the header %s" % TOKEN_HEADER)
        if scope["method"] not in CHANGES_STATE:
            return None
        origin = headers.get("origin")
        if origin is not None and origin.lower() not in {"http://" + h for h in self.hosts}:
            return 403, ("a request from the web page %r is refused: only this server's own "
                         "page may run the model" % origin[:100])
        if headers.get("sec-fetch-site", "same-origin") not in ("same-origin", "none"):
            return 403, "a cross-site request is refused: only this server's own page may " \
                        "run the model"
        kind = headers.get("content-type", "").split(";")[0].strip().lower()
        if kind != "application/json":
            return 415, ("the body must be JSON, sent with Content-Type: application/json "
                         "(got %r)" % kind[:60])
        length = headers.get("content-length", "0").strip()
        if not length.isdigit() or int(length) > MAX_BODY:
            return 413, "the request has %s bytes, at most %d are accepted" % (length[:20],
                                                                               MAX_BODY)
        return None

    def _has_token(self, scope, headers):
        """True where the header or the query's ``token`` is the server's."""
        query = parse_qs(scope.get("query_string", b"").decode("latin-1"))
        given = [headers.get(TOKEN_HEADER, "")] + query.get("token", [])
        want = self.token.encode("utf-8")
        return any(hmac.compare_digest(g.encode("utf-8", "replace"), want) for g in given)

    async def body(self, scope, receive, send, headers):
        """The request body, read here within the limits, or None where it
        was answered (413, 408) or the client went away (one line logged)."""
        chunks, size, more = [], 0, True
        while more:
            try:
                message = await asyncio.wait_for(receive(), BODY_SECONDS)
            except asyncio.TimeoutError:
                log("a client sent no more of its request body to %s for %g s; it was "
                    "answered 408" % (scope["path"], BODY_SECONDS))
                await answer(send, 408, "the request body did not arrive within %g s"
                             % BODY_SECONDS)
                return None
            if message["type"] == "http.disconnect":
                log("a client went away before its request to %s was complete (%d bytes "
                    "read); nothing was run" % (scope["path"], size))
                return None
            part = message.get("body", b"")
            size += len(part)
            if size > MAX_BODY:
                await answer(send, 413, "the request has more than %d bytes, at most %d are "
                             "accepted" % (MAX_BODY, MAX_BODY))
                return None
            chunks.append(part)
            more = message.get("more_body", False)
        return b"".join(chunks)


def _replay(body):
    """A ``receive`` that gives ``body`` once, then waits as a client does."""
    sent = [False]

    async def receive():
        if not sent[0]:
            sent[0] = True
            return {"type": "http.request", "body": body, "more_body": False}
        await asyncio.Event().wait()        # a disconnect is never announced twice
    return receive


async def answer(send, status, message):
    """Send the JSON refusal ``{"error": message, "field": null}``."""
    data = json.dumps({"error": message, "field": None}).encode("utf-8")
    await send({"type": "http.response.start", "status": status,
                "headers": [(b"content-type", b"application/json"),
                            (b"content-length", str(len(data)).encode("ascii"))]})
    await send({"type": "http.response.body", "body": data})


def protocol():
    """uvicorn's HTTP/1.1 protocol with a deadline on each request's headers
    (:data:`HEADER_SECONDS`): a client that opens a connection and sends
    its headers slowly, or not at all, is disconnected (uvicorn waits for
    them without a limit)."""
    from uvicorn.protocols.http.h11_impl import H11Protocol

    class Deadlined(H11Protocol):
        def connection_made(self, transport):
            super().connection_made(transport)
            self._requests, self._deadline = 0, None
            self._arm()

        def _arm(self):
            seen = self._requests
            self._deadline = self.loop.call_later(HEADER_SECONDS, self._late, seen)

        def _late(self, seen):
            if self._requests == seen and not self.transport.is_closing():
                self.transport.close()

        def handle_events(self):
            before = self.cycle
            super().handle_events()
            if self.cycle is not None and self.cycle is not before:
                self._requests += 1

        def on_response_complete(self):
            super().on_response_complete()
            if not self.transport.is_closing():
                self._arm()

        def connection_lost(self, exc):
            if self._deadline is not None:
                self._deadline.cancel()
            super().connection_lost(exc)
    return Deadlined
