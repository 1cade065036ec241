"""The HMI end to end in a real headless Chromium (Debian's, driven by Playwright): the
overview loads with every axis, the scope receives data, a write is refused without the
token and accepted with it and shows in the event log, a fault is acknowledged (issue 17).
Each page's screenshot goes to docs/hmi/<page>.png (docs/hmi.md shows them).

The machine runs in `axisline serve MACHINE --http 127.0.0.1:0 --allow-writes` (a subprocess;
it prints `http HOST:PORT`, `token TOKEN`, `ready`); the device page's demo of every section
type runs behind tests/hmi/harness.py, which prints the same lines."""

from __future__ import annotations

import importlib.util
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from .conftest import FAULT_MACHINE, ROOT

CHROMIUM = Path("/usr/bin/chromium")
SHOTS = ROOT / "docs" / "hmi"
HARNESS = Path(__file__).with_name("harness.py")
ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
        "--no-first-run", "--disable-sync"]
WAIT = 10_000  # ms: the longest a page may take to show what it must (a loaded machine is slow)

pytestmark = pytest.mark.skipif(not CHROMIUM.exists(), reason="Debian's chromium is not installed at /usr/bin/chromium")


def start(log: Path, *args: str) -> tuple[subprocess.Popen, dict[str, str]]:
    """Start `python ARGS...`; return it once it printed "ready", with the lines before."""
    with open(log, "w") as err:  # a file: a pipe nobody reads would stall it once full
        proc = subprocess.Popen([sys.executable, *args], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                stderr=err, text=True, cwd=ROOT)
    lines: dict[str, str] = {}
    assert proc.stdout is not None
    for line in proc.stdout:
        kind, _, value = line.strip().partition(" ")
        if kind == "ready":
            return proc, lines
        lines[kind] = value
    proc.kill()
    raise AssertionError(f"the HMI did not start: {log.read_text()}")


def serve(log: Path, machine: Path) -> tuple[subprocess.Popen, dict[str, str]]:
    return start(log, "-m", "axisline.cli", "serve", str(machine), "--http", "127.0.0.1:0", "--allow-writes")


def stop(proc: subprocess.Popen) -> None:
    proc.terminate()  # serve: stops the axes with their ramps; the harness: stops
    proc.communicate(timeout=30)


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    proc, lines = serve(tmp_path_factory.mktemp("serve") / "stderr.txt", FAULT_MACHINE)
    yield f"http://{lines['http']}", lines["token"]
    stop(proc)


@pytest.fixture(scope="module")
def demo_device(tmp_path_factory):
    """The harness with the demo device of every section type (fake_devices.py)."""
    proc, lines = start(tmp_path_factory.mktemp("harness") / "stderr.txt", str(HARNESS), str(FAULT_MACHINE), "--fake-device")
    yield f"http://{lines['http']}", lines["token"]
    stop(proc)


@pytest.fixture(scope="module")
def browser():
    sync_api = pytest.importorskip("playwright.sync_api")
    with sync_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=str(CHROMIUM), args=ARGS)
        yield b
        b.close()


@pytest.fixture
def page(browser):
    context = browser.new_context(viewport={"width": 1200, "height": 760})
    pg = context.new_page()
    pg.set_default_timeout(WAIT)
    yield pg
    context.close()


def shot(page, name: str, full_page: bool = True) -> None:
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / f"{name}.png"), full_page=full_page)


def enter_token(page, token: str) -> None:
    page.fill("#token", token)


def test_overview_loads_with_every_axis(served, page):
    base, _ = served
    page.goto(base + "/")
    page.wait_for_selector("#axes tbody tr[data-axis='y']")
    assert page.locator("#axes tbody tr").count() == 2
    page.wait_for_selector("#axes tr[data-axis='x'] [data-state='ErrorStop']")
    assert "following error" in page.inner_text("#axes tr[data-axis='x']")
    assert "HMI test machine" in page.inner_text("#title")
    shot(page, "overview")


def test_scope_receives_data(served, page):
    base, _ = served
    page.goto(base + "/scope")
    page.wait_for_selector("#channels input[value='y.command_position']")
    for name in ("x.command_position", "x.actual_position"):  # the defaults: x is tripped, flat
        page.uncheck(f"#channels input[value='{name}']")
    for name in ("y.command_position", "y.actual_velocity", "y.following_error"):
        page.check(f"#channels input[value='{name}']")
    page.wait_for_function("Number(document.getElementById('plot').dataset.samples || 0) > 100")
    first = int(page.get_attribute("#plot", "data-samples"))
    page.wait_for_function(f"Number(document.getElementById('plot').dataset.samples) > {first}")
    page.click("#zoomin")
    assert page.get_attribute("#plot", "data-window") == "2.5"  # from the 5 s window
    page.click("#pause")  # the picture stands still while the samples keep coming
    frozen, seen = page.eval_on_selector("#plot", "c => c.toDataURL()"), int(page.get_attribute("#plot", "data-samples"))
    page.wait_for_function(f"Number(document.getElementById('plot').dataset.samples) > {seen}")
    assert page.eval_on_selector("#plot", "c => c.toDataURL()") == frozen
    page.click("#pause")
    page.click("#zoomout")
    page.wait_for_timeout(1500)  # a window worth seeing in the screenshot
    assert page.eval_on_selector("#plot", "c => c.toDataURL()") != frozen
    with page.expect_download() as download:
        page.click("#csv")
    header = Path(download.value.path()).read_text().splitlines()[0]
    assert header == "t[s],y.command_position[deg],y.actual_velocity[deg/s],y.following_error[deg]"
    shot(page, "scope")


def test_write_refused_without_token_accepted_with_it_and_logged(served, page):
    base, token = served
    page.goto(base + "/io")
    row = "#inputs tr[data-name='door_closed']"
    page.wait_for_selector(row)
    page.click(f"{row} button:text-is('1')")
    page.wait_for_selector("#msg.error:has-text('X-Axisline-Token')")
    assert "forced" not in page.inner_text(row)
    enter_token(page, token)
    page.click(f"{row} button:text-is('1')")
    page.wait_for_selector("#msg.info:has-text('door_closed: False -> forced True')")
    page.wait_for_selector(f"{row}:has-text('forced 1')")
    shot(page, "io")
    page.goto(base + "/events")
    page.wait_for_selector("#events tr[data-kind='write']:has-text('forced True')")
    assert page.locator("#events tr[data-kind='write']:has-text('refused')").count() >= 1
    shot(page, "events")


def test_device_page_renders_every_section_and_validates(demo_device, page):
    base, token = demo_device
    page.goto(base + "/device")
    page.wait_for_selector("section[data-type='text']")
    types = page.eval_on_selector_all("section", "s => s.map(e => e.dataset.type)")
    assert sorted(types) == ["bits", "diagnostics", "parameters", "plot", "table", "text"]
    assert "10 … 10000" in page.inner_text("section[data-type='parameters']")
    enter_token(page, token)
    field = "input[data-name='cutting_length']"
    page.fill(field, "5")
    page.press(field, "Enter")
    page.wait_for_selector("#msg.error:has-text('allowed 10..10000 mm')")
    assert page.locator(f"{field}.invalid").count() == 1
    page.fill(field, "1500")
    page.press(field, "Enter")
    page.wait_for_selector("#msg.info:has-text('1000 -> 1500')")
    page.wait_for_selector("section[data-type='parameters'] td.num:text-is('1500')")
    shot(page, "device")


def test_fault_is_acknowledged(served, page):
    base, token = served
    page.goto(base + "/")
    page.wait_for_selector("#axes tr[data-axis='x'] [data-state='ErrorStop']")
    page.click("#ack")
    page.wait_for_selector("#msg.error:has-text('X-Axisline-Token')")  # not without the token
    enter_token(page, token)
    page.click("#ack")
    page.wait_for_selector("#msg.info:has-text('acknowledged: axis x')")
    page.wait_for_selector("#axes tr[data-axis='x'] [data-state='Standstill']")
    page.goto(base + "/events")
    page.wait_for_selector("#events tr[data-kind='acknowledge']:has-text('axis x')")


def test_fs701_device_page(page, tmp_path):
    """The real FS701 device view (axisline.hmi.devices) on the generic page: a value out of
    the register's range is refused with the device's message, one inside it is written."""
    if importlib.util.find_spec("axisline.hmi.devices") is None:
        pytest.skip("axisline.hmi.devices (the device views) is not there yet")
    # a copy: the device may store what it accepts beside its machine file
    (tmp_path / "params").mkdir()
    shutil.copy(ROOT / "examples" / "flying_shear.toml", tmp_path)
    shutil.copy(ROOT / "examples" / "params" / "fs701_params.toml", tmp_path / "params")
    proc, lines = serve(tmp_path / "stderr.txt", tmp_path / "flying_shear.toml")
    try:
        base = f"http://{lines['http']}"
        page.goto(base + "/device")
        field = "input[data-name='cutting_length']"
        page.wait_for_selector(field)
        row = page.inner_text("tr[data-name='cutting_length']")
        assert "1 … 999999" in row and "LU" in row
        shot(page, "device-fs701", full_page=False)
        enter_token(page, lines["token"])
        page.fill(field, "9999999")
        page.press(field, "Enter")
        page.wait_for_selector("#msg.error:has-text('outside the allowed range 1..999999')")
        page.fill(field, "1200")
        page.press(field, "Enter")
        page.wait_for_selector("#msg.info:has-text('1000 -> 1200')")
        page.wait_for_selector("tr[data-name='cutting_length'] td.num:text-is('1200')")
    finally:
        stop(proc)
