"""CLM mark search and registration (SRM L2598-2647, REP L2342-2365, SRP L2649-2735, RMI
L2367-2433; errata §1.16, §1.17) on the simulated plant: the feed axis of
examples/roll_feed_clm.toml carrying a strip with print marks (a [[marks]] carrier), a contrast sensor
at line position 0 wired to an ordinary input (I1.01.0 / I1.01.7) or to Raster 1 (I0.01.7)."""

from __future__ import annotations

import json
from pathlib import Path

from axisline.machine import Machine

from .clmrig import roll_feed_text

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"


def machine(tmp_path: Path, program: str, marks: list[float], inputs: tuple[str, ...] = ("I1.01.0",),
            params: dict[str, str] | None = None, b011: str | None = None) -> Machine:
    (tmp_path / "t.prg").write_text(program)
    par = (EXAMPLES / "clm" / "roll_feed.par").read_text()
    for pid, data in {**(params or {}), **({"B011": b011} if b011 else {})}.items():
        par = "\n".join(line if not line.startswith(pid + " ") else f"{pid} {data}" for line in par.splitlines()) + "\n"
    (tmp_path / "t.par").write_text(par)
    text = roll_feed_text(tmp_path / "t.prg", tmp_path / "t.par")
    wiring = "".join(f'"{name}" = "marks"\n' for name in inputs)
    text = text.replace('"I1.00.2" = true', wiring + '"I1.00.2" = true')
    text = text.replace('report_output = "Q1.00.0"\n', "")
    text += f"\n[[marks]]\nname = \"marks\"\ncarrier = \"feed\"\nsensor_position = 0.0\nwidth = 2.0\npositions = {marks!r}\n"
    (tmp_path / "m.toml").write_text(text)
    return Machine.from_file(tmp_path / "m.toml")


def run(m: Machine, seconds: float, done=lambda m: False) -> None:
    for _ in range(round(seconds / m.period)):
        m.scheduler.run_cycle()
        if done(m):
            return


def task1(m: Machine) -> int:
    return m.device.rt.tasks[0].pc


VMAX_200 = {"A106": "000200.000"}  # the example's "maximum velocity is 200 IU/s" (L2628)


def test_srm_accuracy_normal_input_and_raster(tmp_path):
    """L2628-2635: Vmax 200 IU/s, cycle 2 ms, SRM 1 +000000.000 +500: search at 100 IU/s; a
    normal input (debounced one cycle) latches within 100 x 2 x 0.002 = 0.4 IU, Raster 1
    (I0.01.7, about 0.1 ms) within 0.01 IU (registration decisions 1, 2)."""
    for bit, low, high in (("I1.01.0", 0.19, 0.41), ("I0.01.7", 0.0, 0.0125)):
        d = tmp_path / bit
        d.mkdir()
        m = machine(d, f"0000 SRM 1 +000000.000 +500 {bit}\n0001 AKN M2.00.0 1\n0002 JST 0002\n", [50.0], (bit,), VMAX_200)
        reg = m.device.rt.registration
        run(m, 3.0, lambda m: task1(m) == 1)
        assert task1(m) == 1
        assert abs(m.axis("feed").actual_velocity - 100.0) < 2.0  # still searching at 100 IU/s
        assert low <= reg.latch41 - 50.0 <= high, (bit, reg.latch41)  # the latch lags the mark
        run(m, 1.0)
        clm = m.device.rt.axes[1]
        assert abs(clm.actual_position - reg.latch41) < 0.06  # offset 0: back onto the mark


def test_srm_offset_example(tmp_path):
    """Fig. 5-27 (L2643): SRM 1 +000200.000 +500 I1.01.0 moves to 200 IU past the mark; with
    Raster 1 the strip stops 200 IU past the mark within the raster and Ax27 accuracy."""
    m = machine(tmp_path, "0000 SRM 1 +000200.000 +500 I0.01.7\n0001 AKN M2.00.0 1\n0002 JST 0002\n", [50.0], ("I0.01.7",), VMAX_200)
    run(m, 6.0)
    assert abs(m.axis("feed").actual_position - 250.0) < 0.06
    assert m.device.rt.modes.fault_error is None


REP_PROGRAM = "0030 SRM 1 +000000.000 +050 I1.01.0\n0031 REP 0900 1 000500.000\n0032 JST 0032\n0900 AEA Q1.00.1 1\n0901 JST 0901\n"


def test_rep_limit_jumps_and_brakes(tmp_path):
    """L2346-2348, L2362-2365: SRM + REP 0900 1 500: no mark within 500 IU -> the drive
    decelerates to a stop and the program jumps to 0900 (decision 3: REP right after SRM)."""
    m = machine(tmp_path, "0000 JMP 0030\n" + REP_PROGRAM, [])  # 050 of 500 IU/s: 25 IU/s
    run(m, 22.0, lambda m: task1(m) >= 900)
    pos = m.axis("feed").actual_position
    assert task1(m) == 900 and 500.0 < pos < 501.5
    run(m, 1.0)
    assert m.device.rt.memory.image.get(__import__("axisline.devices.clm.operands", fromlist=["x"]).parse_operand("Q1.00.1", bit=True)) == 1
    assert abs(m.axis("feed").actual_velocity) < 0.5 and m.axis("feed").actual_position < 502.0
    # a mark inside the limit: found, REP is then passed as a one-cycle command
    d = tmp_path / "found"
    d.mkdir()
    m = machine(d, "0000 JMP 0030\n" + REP_PROGRAM, [100.0])
    run(m, 6.0, lambda m: task1(m) == 32)
    assert task1(m) == 32 and abs(m.device.rt.registration.latch41 - 100.0) < 0.2


def test_rep_persists_until_the_next_rep(tmp_path):
    """Errata §1.17 / L2350-2354: a REP defined earlier stays for later SRMs until another REP."""
    program = ("0000 REP 0900 1 000010.000\n0001 WAI 00.010\n0002 SRM 1 +000000.000 +500 I1.01.0\n"
               "0003 JST 0003\n0900 SRM 1 +000000.000 +500 I1.01.0\n0901 JST 0901\n")
    m = machine(tmp_path, program, [], params=VMAX_200)
    run(m, 2.0, lambda m: task1(m) >= 900)
    assert task1(m) == 900 and 10.0 < m.axis("feed").actual_position < 11.5
    assert m.device.rt.registration.limits[1][1] == 10  # still set: the SRM at 0900 is limited too
    run(m, 0.02)
    assert task1(m) == 900 and isinstance(m.device.rt.tasks[0].wait, object) and m.device.rt.tasks[0].wait.data[0] == (900, 10)


def test_rep_other_axis_is_1a(tmp_path):
    """Error 1A (L8486): REP directly after SRM with another axis number."""
    m = machine(tmp_path, "0000 SRM 1 +000000.000 +050 I1.01.0\n0001 REP 0900 2 000500.000\n0002 JST 0002\n", [])
    run(m, 0.5)
    fault = m.device.rt.modes.fault_error
    assert fault is not None and fault.code == "1A"


SRP = ("0000 SET V601 = +00000020.000000\n0001 SET V602 = +00000010.000000\n0002 SET V604 = +00000000.000000\n"
       "0003 SRP 1 {mode} 0 V600 M2.02\n0004 WAI 00.100\n"
       "0005 PSI 1 +000100.000 999\n0006 SET V700 = +V600\n0007 PSI 1 +000100.000 999\n0008 SET V701 = +V600\n"
       "0009 PSI 1 +000100.000 999\n0010 SET V702 = +V600\n0011 JST 0011\n")


def test_srp_mode_1_corrects_the_next_psi(tmp_path):
    """Fig. 5-29 (L2700-2714; desired distance V601 = 20, max correction V602 = 10): the first
    PSI after SRP is not corrected (L2655); the next one by desired - measured, limited to
    +-V602 (decision 4). Mark 1 at 73: measured 27 -> the 2nd feed 93, then 20 on."""
    for first, ends, measured in ((73.0, (100, 193, 293), (27, 20, 20)), (65.0, (100, 190, 285), (35, 25, 20))):
        d = tmp_path / str(first)
        d.mkdir()
        m = machine(d, SRP.format(mode=1), [first, first + 100, first + 200], ("I0.01.7",))
        targets = []
        rt = m.device.rt
        for _ in range(round(3.0 / m.period)):
            m.scheduler.run_cycle()
            t = rt.axes[1].exact_target
            if t is not None and (not targets or targets[-1] != t):
                targets.append(t)
        v = rt.memory.variables
        got = [v[n] / 1e6 for n in (700, 701, 702)]
        assert [abs(g - w) < 0.06 for g, w in zip(got, measured)] == [True] * 3, got
        assert abs(float(targets[-1]) - ends[-1]) < 0.06 and any(abs(float(t) - ends[1]) < 0.06 for t in targets), targets
        assert rt.memory.image.get(__import__("axisline.devices.clm.operands", fromlist=["x"]).parse_operand("M2.02.4", bit=True)) == 1


def test_srp_mode_3_only_detects(tmp_path):
    """Fig. 5-30 mode 3 (L2695-2697): V600 and M2.xx.4 set, no correction: feeds stay 100."""
    m = machine(tmp_path, SRP.format(mode=3), [73.0, 173.0, 273.0], ("I0.01.7",))
    run(m, 3.0)
    v = m.device.rt.memory.variables
    assert [round(v[n] / 1e6) for n in (700, 701, 702)] == [27, 27, 27]
    assert abs(m.axis("feed").actual_position - 300.0) < 0.06


def test_srp_search_window_jump(tmp_path):
    """L2683-2686: no raster between V603 and V604 -> the PSI completes, the program goes to V605."""
    program = ("0000 SET V604 = +00000050.000000\n0001 SET V605 = +00000900.000000\n0002 SRP 1 1 0 V600 M2.02\n"
               "0003 PSI 1 +000100.000 999\n0004 JST 0004\n0900 JST 0900\n")
    m = machine(tmp_path, program, [80.0], ("I0.01.7",))  # the mark comes after the end of search
    run(m, 2.0)
    assert task1(m) == 900 and abs(m.axis("feed").actual_position - 100.0) < 0.06


def test_status_41_is_the_last_latch(tmp_path):
    """L7066-7093: Status 41 = axis 1's position at the last raster."""
    from axisline.devices.clm.status import status_body

    m = machine(tmp_path, "0000 SRM 1 +000000.000 +500 I0.01.7\n0001 JST 0001\n", [50.0], ("I0.01.7",), VMAX_200)
    run(m, 3.0)
    body = status_body(m.device.rt, 41, [])
    assert body.startswith("41  +000050.0") and abs(float(body[4:-1]) - 50.0) < 0.0125


RMI = ("0000 PSI 1 +000050.000 999\n0001 JSR 0005\n0002 PSI 1 +000025.000 999\n0003 JSR 0009\n0004 JMP 0000\n"
       "0005 AEA Q1.00.0 1\n0006 WAI 00.200\n0007 AEA Q1.00.0 0\n0008 RTS\n"
       "0009 AEA Q1.00.1 1\n0010 WAI 00.200\n0011 AEA Q1.00.1 0\n0012 RTS\n"
       "0200 RMI 1 0 I1.01.7\n0201 PSI 1 +000015.500 500\n0202 JSR 0210\n0203 RMI 1 1 I1.01.7\n0204 JMP 0200\n"
       "0210 AEA Q1.00.2 1\n0211 WAI 00.250\n0212 AEA Q1.00.2 0\n0213 WAI 00.250\n0214 RTS\n")


def test_rmi_fig_5_20_suspends_and_resumes_the_feed(tmp_path):
    """Fig. 5-20 (L2404-2431, errata §1.16: I1.01.7 an ordinary input): a hole at 52 interrupts
    the 2nd feed (50 -> 75); Task 2 moves 15.5 past the hole at 50 %, cuts (Q1.00.2) while Task 1
    stands on its PSI, and RMI 1 1 resumes the feed to 75; then Task 1 goes on (decision 5)."""
    m = machine(tmp_path, RMI, [52.0], ("I1.01.7",), b011="0200 0000 0")
    rt = m.device.rt
    seen = []
    for _ in range(round(3.0 / m.period)):
        m.scheduler.run_cycle()
        seen.append((rt.tasks[0].pc, rt.tasks[1].pc, m.axis("feed").actual_position, rt.registration.suspended_task))
    cut = [i for i, s in enumerate(seen) if s[1] == 211]
    assert cut, "Task 2 never reached its tool program"
    mark = rt.registration.latch41
    assert 52.0 <= mark < 52.0 + 2 * 0.002 * 500  # an ordinary input: within two cycles at 500 IU/s
    assert abs(seen[cut[0]][2] - (mark + 15.5)) < 0.1  # the offset from the raster position (Ax27 0.05 + settling)
    held = [s for s in seen if s[3] == 1]
    assert held and all(s[0] == 2 for s in held)  # Task 1 held on its PSI 1 +25 while suspended
    resumed = next(i for i, s in enumerate(seen) if i > cut[0] and s[3] is None)
    after = next(i for i, s in enumerate(seen) if i > resumed and s[0] == 3)  # Task 1: PSI done, JSR 0009
    assert abs(seen[after][2] - 75.0) < 0.06


def test_registration_feed_example_runs(tmp_path):
    """examples/registration_feed_clm.toml with `axisline run` (SRP mode 1 on a strip printed
    every 100.4): 12 products; the first corrections are limited to V602 = 10, then the mark
    stays within 0.5 of the desired 20 (the one-product delay of mode 1 leaves pitch - feed)."""
    from typer.testing import CliRunner

    from axisline.cli import app

    r = CliRunner().invoke(app, ["run", str(EXAMPLES / "registration_feed_clm.toml"), "--json", str(tmp_path / "r.json"),
                                 "--report", str(tmp_path / "out"), "--quiet"])
    assert r.exit_code == 0, r.output[-2000:]
    products = json.loads((tmp_path / "r.json").read_text())["device"]["registration"]
    assert len(products) == 12
    assert [round(p["correction"], 3) for p in products[:2]] == [-10.0, -10.0]
    assert all(abs(p["measured"] - 20.0) < 0.8 and abs(p["correction"]) <= 10.0 for p in products[3:])
    assert "Registration (SRP) per product" in (tmp_path / "out" / "report.md").read_text()


def test_rmi_outside_task_2_is_0a(tmp_path):
    """Decision 7 (L2393 "The raster program must be programmed in Task 2"): RMI in Task 1 is
    fault 0A when it runs."""
    m = machine(tmp_path, "0000 RMI 1 0 I1.01.7\n0001 PSI 1 +000015.500 500\n0002 JST 0002\n", [52.0], ("I1.01.7",))
    run(m, 0.5, lambda m: m.device.rt.modes.fault_error is not None)
    e = m.device.rt.modes.fault_error
    assert e is not None and e.code == "0A" and "Task 2" in str(e)


def test_rmi_twice_without_resume_is_0a(tmp_path):
    """Decision 7 (L2403 "Detecting an additional raster before the command RMI_1_1 is not
    possible"): a Task 2 that waits for a second raster before its RMI 1 1 is fault 0A."""
    task2 = "0200 RMI 1 0 I1.01.7\n0201 PSI 1 +000005.000 500\n0202 RMI 1 0 I1.01.7\n0203 JMP 0203\n"
    m = machine(tmp_path, "0000 PSI 1 +000200.000 500\n0001 JST 0001\n" + task2, [52.0, 70.0], ("I1.01.7",), b011="0200 0000 0")
    run(m, 2.0, lambda m: m.device.rt.modes.fault_error is not None)
    e = m.device.rt.modes.fault_error
    assert e is not None and e.code == "0A" and "RMI 1 1" in str(e)


def test_rmi_short_offset_reverses(tmp_path):
    """Decision 7 (L2405 "The offset feed must be longer than the braking distance, or the axis
    will reverse"): at 499.5 mm/s the braking distance is 499.5^2 / (2 x 5000) = 25 mm; an
    offset of 0.5 mm past the hole overshoots and comes back to hole + 0.5."""
    task2 = "0200 RMI 1 0 I1.01.7\n0201 PSI 1 +000000.500 000\n0202 JMP 0202\n"
    m = machine(tmp_path, "0000 PSI 1 +000300.000 999\n0001 JMP 0001\n" + task2, [150.0], ("I1.01.7",), b011="0200 0000 0")
    peak = 0.0
    for _ in range(round(2.0 / m.period)):
        m.scheduler.run_cycle()
        peak = max(peak, m.axis("feed").actual_position)
    mark = m.device.rt.registration.latch41
    assert 150.0 <= mark < 152.5
    assert peak > mark + 20.0  # it ran on by about the braking distance ...
    assert abs(m.axis("feed").actual_position - (mark + 0.5)) < 0.06  # ... and came back


def test_srp_x_1_and_rmi_without_offset_are_check_warnings():
    """Decisions 7 and 9: `axisline clm check` warns about SRP x = 1 (no meaning in the manual)
    and about RMI 1 0 without the offset feed right after it (L2375)."""
    from axisline.devices.clm.check import check_program
    from axisline.devices.clm.files import read_program_text

    prog, findings = read_program_text("0000 SRP 1 1 1 V600 M2.02\n0001 JST 0001\n0200 RMI 1 0 I1.01.7\n0201 WAI 00.100\n0202 RMI 1 1 I1.01.7\n0203 JMP 0200\n")
    assert not [f for f in findings if f.is_error]
    found = {(f.where, f.severity) for f in check_program(prog) if f.code == "0A"}
    assert ("N0000", "warning") in found and ("N0200", "warning") in found
    clean, _ = read_program_text("0000 SRP 1 1 0 V600 M2.02\n0001 JST 0001\n0200 RMI 1 0 I1.01.7\n0201 PSI 1 +000015.500 500\n0202 RMI 1 1 I1.01.7\n0203 JMP 0200\n")
    assert not [f for f in check_program(clean) if f.code == "0A"]


def test_srp_end_of_search_is_compared_exactly():
    """SRP (L2683-2686): the search ends when the axis has moved more than the end of search
    (variable +4) from where the positioning started - compared in exact IU, so a float rounding
    of the difference never ends a search early or late: 500.1 - 0.1 is 500.0 as floats, but the
    float 500.1 is 2.3e-14 above 500.1, so the axis is past an end of 500."""
    from fractions import Fraction
    from types import SimpleNamespace

    from axisline.devices.clm.registration import _beyond

    def watch(actual: float, start: Fraction) -> SimpleNamespace:
        return SimpleNamespace(axis=SimpleNamespace(actual_position=actual), start=start, start_of=None, start_f=0.0)

    assert abs(500.1 - 0.1) == 500.0  # what a float comparison would see
    assert _beyond(watch(500.1, Fraction(1, 10)), 500_000_000)
    assert not _beyond(watch(500.1, Fraction(1, 10)), 500_000_001)
    assert not _beyond(watch(-499.9, Fraction(1, 10)), 500_000_000)  # 2.3e-14 less than 500 back (-500.0 as floats)
    assert _beyond(watch(-600.0, Fraction(1, 10)), 500_000_000) and not _beyond(watch(100.0, Fraction(1, 10)), 500_000_000)
