"""The web HMI's HTTP side: pages, a JSON API and two WebSockets (FastAPI).

Runs in the endpoint process. It never touches the machine: every request is a
`call(method, args, who)` that the cycle runs at a boundary (`MachineView.call`), and the
answer comes back as a Future. The event log (`events`: emit / recent) is local.

    GET  /  /scope  /io  /device  /events          the pages (static HTML + vanilla JS)
    GET  /api/info                                  writes enabled? token needed?
    GET  /api/overview  /api/channels  /api/io  /api/device
    GET  /api/scope?channels=a,b&since=N&limit=M    samples N.. and the next N
    GET  /api/events?after=SEQ&limit=M              the event log after SEQ
    POST /api/write        {"target": "device"|"io", "name": ..., "value": ...}
    POST /api/acknowledge  fault reset of the axes and the device
    WS   /ws/scope         send {"channels": [...], "since": N|null}; receive sample blocks
    WS   /ws/events        receive the events as they come

Safety (issue 17): read-only unless the server was made with `writes_allowed`; a write or
acknowledge then also needs the token in the `X-Axisline-Token` header (403 with the reason
otherwise, and the refusal is an event). No CORS middleware: a page from another origin
cannot send that header (the browser's preflight fails), and a WebSocket whose Origin is not
this server is closed (browsers do not apply CORS to WebSockets). Errors are JSON
`{"error": "..."}` naming the field; no traceback reaches a client.

Decisions:

1. Issue 17 "writes then also need the token": a refused write is checked in this
   order: writes disabled (403), token header missing or wrong (403), body not JSON (400),
   a field missing or of the wrong type (422), then the machine's own validation (400). The
   permission comes first so a read-only HMI says "read-only" whatever was sent.
   Test: tests/hmi/test_api.py::test_write_refused_without_writes_allowed.
2. Issue 17 "no wildcard CORS": no CORS at all, and WebSockets check Origin against Host
   (a WebSocket is not subject to CORS, so a foreign page could otherwise read the scope).
   Test: tests/hmi/test_api.py::test_websocket_from_a_foreign_origin_is_closed.
"""

from __future__ import annotations

import asyncio
import json
import logging
import secrets
from concurrent.futures import Future
from pathlib import Path
from typing import Any, Callable, Literal, Union
from urllib.parse import urlparse

from fastapi import FastAPI, Query, Request, WebSocket, WebSocketDisconnect
from fastapi.exceptions import RequestValidationError
from fastapi.responses import FileResponse, JSONResponse
from fastapi.staticfiles import StaticFiles
from pydantic import BaseModel, ConfigDict, Field, StrictBool, StrictFloat, StrictInt, StrictStr, ValidationError
from starlette.exceptions import HTTPException as StarletteHTTPException

from .view import HmiRefused

__all__ = ["PAGES", "REPLY_TIMEOUT", "TOKEN_HEADER", "create_app"]

_log = logging.getLogger(__name__)

STATIC = Path(__file__).parent / "static"
TOKEN_HEADER = "X-Axisline-Token"
#: seconds a request waits for the cycle to take it (then 503, and it is withdrawn)
REPLY_TIMEOUT = 5.0
#: path -> page file (static/<name>.html)
PAGES = {"/": "overview", "/scope": "scope", "/io": "io", "/device": "device", "/events": "events"}
SCOPE_INTERVAL = 0.1  # s between the scope's sample blocks
EVENTS_INTERVAL = 0.25  # s between looks at the event log

Call = Callable[[str, dict[str, Any], str], "Future[Any]"]


class WriteRequest(BaseModel):
    """The body of POST /api/write."""

    model_config = ConfigDict(extra="forbid")
    target: Literal["device", "io"] = Field(description="'device': a device parameter; 'io': a digital input force")
    name: str = Field(min_length=1, max_length=200)
    value: Union[StrictBool, StrictInt, StrictFloat, StrictStr, None] = Field(description="null releases an input force")


def _who(conn: Request | WebSocket) -> str:
    c = conn.client
    return f"hmi {c.host}:{c.port}" if c is not None else "hmi"


def _field_errors(errors: Any) -> str:
    """pydantic's errors as one line naming each field: "body.value: Field required"."""
    parts = []
    for e in errors:
        loc = ".".join(str(x) for x in e.get("loc", ()))
        given = f" (got {e['input']!r})" if "input" in e and e.get("type") != "missing" else ""
        parts.append(f"{loc or 'body'}: {e.get('msg', 'invalid')}{given}")
    return "; ".join(parts)


def _short(value: Any, size: int = 60) -> str:
    text = repr(value)
    return text if len(text) <= size else text[: size - 3] + "..."


def _error(message: str, status: int) -> JSONResponse:
    return JSONResponse({"error": message}, status_code=status)


class _NoTraceback:
    """Outermost guard: a fault in the app answers a JSON 500 and logs one line, never a
    traceback to the client (Starlette's own guard would answer text and log the stack)."""

    def __init__(self, app: Any) -> None:
        self.app = app

    async def __call__(self, scope: Any, receive: Any, send: Any) -> None:
        started = False

        async def watch(message: Any) -> None:
            nonlocal started
            if message["type"] in ("http.response.start", "websocket.accept"):
                started = True
            await send(message)

        try:
            await self.app(scope, receive, watch)
        except Exception as e:
            _log.error("HMI %s %s: %s: %s", scope.get("method", "WS"), scope.get("path"), type(e).__name__, e)
            if scope["type"] == "http" and not started:
                await _error(f"internal error: {type(e).__name__}: {e}", 500)(scope, receive, send)


def create_app(call: Call, events: Any, *, writes_allowed: bool, token: str | None,
               allowed_hosts: list[str] | None = None) -> FastAPI:
    """The HMI application; `call(method, args, who)` returns a Future of MachineView.call.
    `allowed_hosts`: the Host headers answered (None: any; server.local_host_names)."""
    if writes_allowed and not token:
        raise ValueError("writes_allowed needs a token (the operator enters it in the HMI)")
    app = FastAPI(title="axisline HMI", docs_url=None, redoc_url=None, openapi_url=None)
    app.add_middleware(_NoTraceback)
    if allowed_hosts is not None:
        from starlette.middleware.trustedhost import TrustedHostMiddleware

        app.add_middleware(TrustedHostMiddleware, allowed_hosts=allowed_hosts)
    app.mount("/static", StaticFiles(directory=STATIC), name="static")

    @app.exception_handler(HmiRefused)
    async def refused(request: Request, exc: HmiRefused) -> JSONResponse:
        return _error(exc.message, exc.status)

    @app.exception_handler(RequestValidationError)
    async def invalid(request: Request, exc: RequestValidationError) -> JSONResponse:
        return _error(_field_errors(exc.errors()), 422)

    @app.exception_handler(StarletteHTTPException)
    async def http_error(request: Request, exc: StarletteHTTPException) -> JSONResponse:
        if exc.status_code == 404:
            return _error(f"no such page: {request.url.path} (pages: {', '.join(PAGES)})", 404)
        if exc.status_code == 405:
            return _error(f"{request.method} is not allowed on {request.url.path}", 405)
        return _error(str(exc.detail), exc.status_code)

    async def machine(method: str, args: dict[str, Any], who: str) -> Any:
        """`method` run by the cycle at its next boundary; its refusal raised as HmiRefused."""
        fut = call(method, args, who)
        waiter = asyncio.wrap_future(fut)
        done, _ = await asyncio.wait({waiter}, timeout=REPLY_TIMEOUT)
        # withdraw a request the cycle has not taken, so "no answer" means nothing was done
        if not done and fut.cancel():
            raise HmiRefused(f"the machine did not take the request within {REPLY_TIMEOUT:g} s (is it running?); nothing was done", 503)
        try:
            return await waiter
        except asyncio.CancelledError:
            if fut.cancelled():  # withdrawn by the machine (serve is stopping)
                raise HmiRefused("the machine is stopping; nothing was done", 503) from None
            raise
        except HmiRefused:
            raise
        except ConnectionError as e:  # the cycle process is gone (serve/link.py: LinkClosed)
            raise HmiRefused(f"the machine is not running: {e}", 503) from None
        except Exception as e:  # a fault in the machine's answer, not in the request
            _log.error("HMI request %s%r by %s: %s: %s", method, args, who, type(e).__name__, e)
            raise HmiRefused(f"the machine failed to answer {method}: {type(e).__name__}: {e}", 500) from None

    def permit(request: Request, what: str, fields: dict[str, Any]) -> str:
        """The caller of a write or acknowledge; 403 (and an event) unless it may."""
        who = _who(request)
        given = request.headers.get(TOKEN_HEADER)
        reason = None
        if not writes_allowed:
            reason = "writes are disabled: this machine is served read-only (start it with --allow-writes)"
        elif not given:
            reason = f"the {TOKEN_HEADER} header is missing: enter the token printed when the machine was started"
        elif not secrets.compare_digest(given.encode(), str(token).encode()):
            reason = f"the {TOKEN_HEADER} header does not match the token printed when the machine was started"
        if reason is not None:
            kind = "acknowledge" if what == "acknowledge" else "write"
            events.emit(kind, f"{who}: {what} refused: {reason}", endpoint="http", who=who, what=what,
                        accepted=False, reason=reason, **fields)
            raise HmiRefused(reason, 403)
        return who

    # -- pages ----------------------------------------------------------------------

    def page(name: str) -> Callable[[], Any]:
        async def serve_page() -> FileResponse:
            return FileResponse(STATIC / f"{name}.html", media_type="text/html")

        return serve_page

    for path, name in PAGES.items():
        app.add_api_route(path, page(name), methods=["GET"], include_in_schema=False)

    # -- read-outs ------------------------------------------------------------------

    @app.get("/api/info")
    async def info() -> dict[str, Any]:
        return {"writes_allowed": writes_allowed, "token_header": TOKEN_HEADER if writes_allowed else None}

    for method in ("overview", "channels", "io", "device"):

        def read(method: str = method) -> Callable[[Request], Any]:
            async def answer(request: Request) -> Any:
                return await machine(method, {}, _who(request))

            return answer

        app.add_api_route(f"/api/{method}", read(), methods=["GET"])

    @app.get("/api/scope")
    async def scope(request: Request, channels: str = "", since: int = Query(0, ge=0), limit: int = Query(1000, ge=1, le=5000)) -> Any:
        names = [c for c in channels.split(",") if c]
        return await machine("scope", {"channels": names, "since": since, "limit": limit}, _who(request))

    @app.get("/api/events")
    async def recent(after: int = Query(0, ge=0), limit: int = Query(200, ge=1, le=1000)) -> Any:
        return {"events": events.recent(after=after, limit=limit)}

    # -- writes ---------------------------------------------------------------------

    @app.post("/api/write")
    async def write(request: Request) -> Any:
        raw = await request.body()
        try:
            body = json.loads(raw) if raw else None
        except ValueError as e:
            body, bad = None, str(e)
        else:
            bad = None
        # what a refusal's event names: cut short, as a caller without the token sends anything
        fields = {k: _short(body.get(k)) for k in ("target", "name", "value")} if isinstance(body, dict) else {}
        what = f"write {fields.get('target')}.{fields.get('name')} = {fields.get('value')}" if fields else "write"
        who = permit(request, what, fields)
        if bad is not None:
            raise HmiRefused(f"body: not JSON ({bad}); send {{\"target\": ..., \"name\": ..., \"value\": ...}}", 400)
        try:
            req = WriteRequest.model_validate(body)
        except ValidationError as e:
            raise HmiRefused(_field_errors(e.errors()), 422) from None
        return await machine("write", req.model_dump(), who)

    @app.post("/api/acknowledge")
    async def acknowledge(request: Request) -> Any:
        who = permit(request, "acknowledge", {})
        return await machine("acknowledge", {}, who)

    # -- live data ------------------------------------------------------------------

    def same_origin(ws: WebSocket) -> bool:
        origin = ws.headers.get("origin")
        return origin is None or urlparse(origin).netloc == ws.headers.get("host")

    @app.websocket("/ws/scope")
    async def scope_socket(ws: WebSocket) -> None:
        if not same_origin(ws):
            await ws.close(code=1008, reason="cross-origin WebSocket refused")
            return
        await ws.accept()
        who = _who(ws)
        events.emit("connect", f"{who} connected (scope)", endpoint="http", who=who)
        # what the page asks for; `asked` counts its requests, so the answer to an older one
        # (channels changed while the cycle answered) does not move the new one's `since`
        want: dict[str, Any] = {"channels": [], "since": None, "limit": 1000, "asked": 0}
        changed = asyncio.Event()

        async def listen() -> None:
            while True:
                msg = await ws.receive_json()
                if not isinstance(msg, dict):
                    await ws.send_json({"error": "send {\"channels\": [...], \"since\": N or null}"})
                    continue
                want.update(channels=msg.get("channels") or [], since=msg.get("since"),
                            limit=msg.get("limit", 1000), asked=want["asked"] + 1)
                changed.set()

        listener = asyncio.create_task(listen())
        try:
            while not listener.done():
                changed.clear()
                if want["channels"]:
                    asked = want["asked"]
                    since = want["since"] if want["since"] is not None else 0
                    try:
                        block = await machine("scope", {"channels": want["channels"], "since": since, "limit": want["limit"]}, who)
                    except HmiRefused as e:
                        if asked == want["asked"]:
                            want["channels"] = []
                            await ws.send_json({"error": e.message})
                    else:
                        if asked == want["asked"]:
                            want["since"] = block["next"]
                            if block["t"] or block["skipped"]:
                                await ws.send_json(block)
                try:
                    await asyncio.wait_for(changed.wait(), SCOPE_INTERVAL)
                except asyncio.TimeoutError:
                    pass
        except (WebSocketDisconnect, RuntimeError):
            pass  # the page was closed or reloaded
        finally:
            events.emit("disconnect", f"{who} disconnected (scope)", endpoint="http", who=who)
            listener.cancel()
            await asyncio.gather(listener, return_exceptions=True)

    @app.websocket("/ws/events")
    async def events_socket(ws: WebSocket, after: int = 0) -> None:
        if not same_origin(ws):
            await ws.close(code=1008, reason="cross-origin WebSocket refused")
            return
        await ws.accept()
        closed = asyncio.create_task(_until_closed(ws))
        try:
            while not closed.done():
                new = events.recent(after=after, limit=200)
                if new:
                    after = new[-1]["seq"]
                    await ws.send_json({"events": new})
                await asyncio.wait({closed}, timeout=EVENTS_INTERVAL)
        except (WebSocketDisconnect, RuntimeError):
            pass
        finally:
            closed.cancel()
            await asyncio.gather(closed, return_exceptions=True)

    return app


async def _until_closed(ws: WebSocket) -> None:
    """Read (and ignore) what a client sends until it goes away."""
    try:
        while True:
            msg = await ws.receive()
            if msg["type"] == "websocket.disconnect":
                return
    except (WebSocketDisconnect, RuntimeError):
        return
