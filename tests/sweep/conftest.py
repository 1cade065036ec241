"""Helpers of the sweep tests: a sweep file beside the test slide, the CLI in a small Typer app."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest
import typer
from typer.testing import CliRunner

from axisline.sweep.cli import sweep

HERE = Path(__file__).parent
SLIDE = HERE / "slide.toml"


@pytest.fixture
def sweep_file(tmp_path):
    """write(body) -> a sweep file in tmp_path whose base is the test slide."""

    def write(body: str, name: str = "sweep.toml") -> Path:
        p = tmp_path / name
        p.write_text(textwrap.dedent(body).replace("@SLIDE@", str(SLIDE)), encoding="utf-8")
        return p

    return write


def cli_app() -> typer.Typer:
    app = typer.Typer(add_completion=False)
    app.command("sweep")(sweep)

    @app.callback()
    def _main() -> None:
        """test app"""

    return app


@pytest.fixture
def run_cli():
    runner = CliRunner()
    app = cli_app()

    def run(*args: str):
        return runner.invoke(app, ["sweep", *map(str, args)])

    return run
