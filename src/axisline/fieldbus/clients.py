"""Which network client the current request comes from ("modbus 127.0.0.1:50312").

The protocol servers set it per connection (a context variable: each serial connection has
its thread, each Modbus connection its asyncio task), so what a request leads to (the event
log's "who", the audit of a write in the cycle process) names the client without every call
carrying it. Unset outside a server: "".
"""

from __future__ import annotations

from contextvars import ContextVar
from typing import Any

__all__ = ["current_client", "peer_name", "set_client"]

_client: ContextVar[str] = ContextVar("axisline_client", default="")


def current_client() -> str:
    return _client.get()


def set_client(who: str) -> None:
    _client.set(who)


def peer_name(endpoint: str, peer: Any) -> str:
    """"modbus 127.0.0.1:50312" from a socket's peer address (or what a pty/unknown gives)."""
    if isinstance(peer, (tuple, list)) and len(peer) >= 2:
        return f"{endpoint} {peer[0]}:{peer[1]}"
    return f"{endpoint} {peer}" if peer else endpoint
