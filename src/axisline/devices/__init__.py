"""Device personalities: each industrial controller on top of the one motion kernel."""
