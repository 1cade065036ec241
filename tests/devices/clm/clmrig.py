"""A CLM runtime without a plant, for the NC task and mode tests: axes that arrive in a set
number of cycles, the system inputs set as a healthy machine has them."""

from __future__ import annotations

from axisline.devices.clm.files import read_program_text
from axisline.devices.clm.memory import ClmMemory
from axisline.devices.clm.operands import parse_operand
from axisline.devices.clm.runtime import ClmRuntime


class FakeAxis:
    """Arrives `travel_cycles` after a move; records the moves (target in 1/1000 IU)."""

    def __init__(self, number: int, travel_cycles: int = 3) -> None:
        self.number = number
        self.travel_cycles = travel_cycles
        self.moves: list[tuple[str, int, int]] = []
        self.target = 0
        self._arrive = 0
        self._now = 0
        self.homed = False
        self.actual_position = 0.0
        self.lag = 0.0
        self.actual_velocity = 0.0
        self.remaining_distance = 0.0
        self.stops: list[str] = []
        self.acceleration = (999, 999)
        self.factor = 1_000_000
        self.jogging = 0

    def configure(self, params) -> None:
        pass

    def position_absolute(self, target: int, per_mille: int) -> None:
        self.moves.append(("abs", target, per_mille))
        self.target = target * self.factor // 1_000_000
        self._arrive = self._now + self.travel_cycles

    def position_incremental(self, distance: int, per_mille: int) -> None:
        self.moves.append(("inc", distance, per_mille))
        self.target += distance * self.factor // 1_000_000
        self._arrive = self._now + self.travel_cycles

    def continuous(self, on: bool, signed_per_mille: int) -> None:
        self.moves.append(("con", int(on), signed_per_mille))

    def stop_motion(self) -> None:
        self.stops.append("pbk")

    def set_acceleration(self, accel: int, decel: int) -> None:
        self.acceleration = (accel, decel)

    def set_factor(self, factor: int) -> None:
        self.factor = factor

    def clear_lag(self) -> None:
        self.stops.append("cpl")

    @property
    def motion_done(self) -> bool:
        return self._now >= self._arrive

    @property
    def in_position(self) -> bool:
        return self._now >= self._arrive

    def immediate_stop(self) -> None:
        self.stops.append("immediate")
        self._arrive = 10**12

    def resume(self) -> None:
        self.stops.append("resume")
        self._arrive = self._now + self.travel_cycles

    def jog(self, direction: int) -> None:
        self.jogging = direction

    def reset_defaults(self) -> None:
        self.acceleration, self.factor = (999, 999), 1_000_000

    def tick(self, mode: str, enable_input: bool, estop_ok: bool):
        self._now += 1
        self.actual_position = self.target / 1000 if self.in_position else self.actual_position
        return None

    def fault_stop(self) -> None:
        self.stops.append("fault")

    def clear_fault(self) -> None:
        self.stops.append("clear")

    def interface_enable(self, on: bool) -> None:
        self.stops.append("on" if on else "off")

    def set_actual(self, position: float) -> None:
        self.actual_position = position
        self.target = round(position * 1000)


class Rig:
    """A CLM in Automatic with its inputs healthy; `run(cycles)`, `start()`, `bit('Q1.00.4')`."""

    def __init__(self, program: str, *, params: dict[str, str] | None = None, logic: dict[int, str] | None = None,
                 cycle_s: float = 0.002, axes: int = 1, mode: str = "automatic", travel_cycles: int = 3) -> None:
        memory = ClmMemory()
        prog, findings = read_program_text(program)
        assert not [f for f in findings if f.is_error], findings
        memory.program = prog
        for pid, data in (params or {}).items():
            memory.parameters.set(pid, data)
        memory.logic = dict(logic or {})
        self.axes = {n: FakeAxis(n, travel_cycles) for n in range(1, axes + 1)}
        self.rt = ClmRuntime(memory, self.axes, cycle_s)
        for name in ("I0.00.2", "I0.00.4", "I0.00.5", "I0.00.6"):  # E-Stop, Immediate Stop closed; enables
            self.set(name, 1)
        self.set_mode(mode)

    def set(self, name: str, value: int) -> None:
        self.rt.image.set(parse_operand(name, bit="." in name[3:], code="1D"), value)

    def bit(self, name: str) -> int:
        return self.rt.image.get(parse_operand(name, bit=True))

    def set_mode(self, mode: str) -> None:
        self.set("I0.00.0", int(mode == "parameter"))
        self.set("I0.00.1", int(mode == "automatic"))

    def run(self, cycles: int = 1) -> None:
        for _ in range(cycles):
            self.rt.step()

    def start(self) -> None:
        self.set("I0.00.3", 1)
        self.run()
        self.set("I0.00.3", 0)

    def var(self, n: int) -> float:
        return self.rt.memory.variables[n] / 1e6

    @property
    def fault(self) -> str | None:
        e = self.rt.modes.fault_error
        return None if e is None else e.code


# -- the roll feed machine as a base for plant tests ----------------------------------------

from pathlib import Path  # noqa: E402

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"


def with_parameters(par_text: str, params: dict[str, str]) -> str:
    """A parameter listing with `params` (id -> data) in place of its own lines for them."""
    for pid, data in params.items():
        lines = [line for line in par_text.splitlines() if not line.startswith(pid + " ") and line != pid]
        par_text = "\n".join(lines + [f"{pid} {data}"]) + "\n"
    return par_text


def roll_feed_text(program: Path, parameters: Path) -> str:
    """examples/roll_feed_clm.toml running `program` with `parameters`, no Logic Task, no variables."""
    text = (EXAMPLES / "roll_feed_clm.toml").read_text()
    text = text.replace('program = "clm/roll_feed.prg"', f'program = "{program.as_posix()}"')
    text = text.replace('parameters = "clm/roll_feed.par"', f'parameters = "{parameters.as_posix()}"')
    return text.replace('logic = "clm/roll_feed.lt"\n', "").replace('variables = "clm/roll_feed.var"\n', "")


def run_to(m, until_s: float) -> None:
    """Run the machine's cycles until the CLM's simulated time reaches `until_s` seconds."""
    while m.device.rt.cycle * m.period < until_s - 1e-9:
        m.scheduler.run_cycle()
