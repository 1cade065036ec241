"""Simulated cut-to-length line for the FS701 cutter tests (no tests here: the rig).

    rig = CutterRig(settings, line=[SpeedChange(0, 10000, 5000)], period=0.001)
    rig.cutter.inputs.control_enable = True; rig.run(0.01)
    rig.cutter.inputs.start_stop = True; rig.run(5.0)
    rig.recorder.records   # one CutRecord per piece, measured on the simulated material

One cycle c (the order of the Machine's stages):
    cutter.tick(c); axis.update_setpoint(c)              LOGIC, SETPOINTS
    volts = cutter.position_loop(carriage counts / kC)   POSITION_LOOP (Ana-Out 2)
    drive.command_voltage(volts); drive.step; material.step; encoders and sensors sample
The tool (a shear): when Ready to Cut rises the blade needs `blade_delay` to pass the material
(the cut instant, recorded by the CutRecorder) and signals Cut completed after `cut_time`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axisline.devices.fs701.cutter import Cutter, CutRecorder, CutterSettings
from axisline.motion.axis import Axis, AxisConfig
from axisline.plant import IncrementalEncoder, MaterialLine, PrintMarks, PrintMarkSensor, ServoDrive, SpeedChange

__all__ = ["CutterRig", "Tool", "demo_settings", "SpeedChange"]


def demo_settings(**kw) -> CutterSettings:
    """LU = 0.1 mm, 1 m pieces, 60 m/min class line (the `make demo` line)."""
    base = dict(
        cutting_length=10000,  # 1 m
        test_cut_length=5000,
        pulses_line_1000=4000,  # 40 increments / mm (x4 of 10 lines / mm)
        pulses_cut_1000=2000,
        mode_counter_1=2,
        mode_counter_2=2,
        acceleration_1=50000,  # 5 m/s^2
        acceleration_2=100000,
        deceleration_1=80000,
        deceleration_2=100000,
        ramp_form=0,
        return_speed=2.0,
        synchron_time=1,
        cut_window=6,
        sync_samples=1,
        home_window=20,
        p_gain=3000,
        i_time=0.0,
        max_correction=9999,
        max_line_speed=1_000_000,  # 100 m/min
        sampling_time=1,
        ana_out_gain_2=10.0,
    )
    base.update(kw)
    return CutterSettings(**base)


@dataclass
class Tool:
    """A shear: the blade passes the material `blade_delay` after Ready to Cut, Cut completed
    follows after `cut_time` and stays HIGH `pulse` (edge sense 0: rising edge)."""

    blade_delay: float = 0.02
    cut_time: float = 0.06
    pulse: float = 0.02
    enabled: bool = True


class CutterRig:
    def __init__(
        self,
        settings: CutterSettings | None = None,
        *,
        line: list | tuple = (),
        line_speed: float = 0.0,
        period: float = 0.001,
        drive: dict | None = None,
        tool: Tool | None = None,
        marks: PrintMarks | None = None,
        sensor_position: float = 0.0,
        sensor_invert: bool = False,
        sensor_delay: float = 0.0,
        encoder_line: bool = True,
        carriage_start: float = 0.0,
        seed: int = 0,
    ) -> None:
        self.s = s = settings if settings is not None else demo_settings()
        self.period = period
        self.rng = np.random.default_rng(seed)
        self.material = MaterialLine(list(line), speed=line_speed)
        self.line_encoder = IncrementalEncoder(self.material, s.line_lines_per_lu, s.line_multiplier)
        dk = dict(
            loop="first_order",
            time_constant=0.004,
            velocity_per_volt=s.v_max_line / 10.0,  # matched to Ana-Out Gain 10 V
            max_velocity=4.0 * s.v_max_line,
            max_acceleration=400000.0,
            position=carriage_start,
            enabled=False,
        )
        if drive:
            dk.update(drive)
        self.drive = ServoDrive(**dk)
        self.car_encoder = IncrementalEncoder(self.drive, s.cut_lines_per_lu, s.cut_multiplier)
        kc = s.cut_counts_per_lu
        self.kc = kc
        cfg = AxisConfig(
            name="carriage",
            unit="LU",
            counts_per_unit=kc,
            v_max=10.0 * s.v_max_line,
            a_max=1e7,
            following_error_limit=1e9,
        )
        self.axis = Axis(cfg, period)
        self.cutter = Cutter(self.axis, s, line=self.line_encoder if encoder_line else None)
        self.recorder = CutRecorder(self.cutter)
        self.tool = tool if tool is not None else Tool()
        self.sensor = None
        self.sensor_delay = sensor_delay  # photocell dead time: edges reach the input this late
        self._late_edges: list = []
        if marks is not None:
            self.sensor = PrintMarkSensor(self.material, marks, sensor_position=sensor_position, invert=sensor_invert)
        self.cycle = 0
        self.volts = 0.0
        # tool state
        self._rtc_prev = False
        self._blade_at: int | None = None
        self._cc_on_at: int | None = None
        self._cc_off_at: int | None = None
        # traces (optional)
        self.trace: list[tuple] | None = None
        self.hooks: list = []

    # ------------------------------------------------------------------ one cycle

    def step(self) -> None:
        c = self.cycle
        cut = self.cutter
        for h in self.hooks:
            h(self, c)
        cut.tick(c)
        self.axis.update_setpoint(c)
        actual = self.car_encoder.counts / self.kc
        self.volts = cut.position_loop(actual)
        self._tool(c)
        d = self.drive
        if self.axis.powered != d.enabled:
            d.enable(self.axis.powered)
        d.command_voltage(self.volts)
        T = self.period
        t0 = c * T
        d.step(T)
        self.material.step(T)
        self.line_encoder.sample()
        self.car_encoder.sample()
        if self.sensor is not None:
            self._late_edges.extend(self.sensor.sample(t0, T))
            t1 = t0 + T
            keep = []
            for e in self._late_edges:
                t = e.time + self.sensor_delay
                if t <= t1 + 1e-12:
                    cut.print_mark_edge(e._replace(time=t, fraction=min(1.0, max(0.0, (t - t0) / T))))
                else:
                    keep.append(e)
            self._late_edges = keep
        if self.trace is not None:
            self.trace.append(
                (c, self.material.position, self.material.velocity, d.position, d.velocity,
                 self.axis.command_position, cut.position_error, int(cut.cut_state), cut.outputs.ready_to_cut, self.volts)
            )
        self.cycle = c + 1

    def _tool(self, c: int) -> None:
        tool = self.tool
        rtc = self.cutter.outputs.ready_to_cut
        inp = self.cutter.inputs
        if tool.enabled:
            T = self.period
            if rtc and not self._rtc_prev:
                self._blade_at = c + int(round(tool.blade_delay / T))
                self._cc_on_at = c + int(round(tool.cut_time / T))
                self._cc_off_at = self._cc_on_at + int(round(tool.pulse / T))
            if self._blade_at is not None and c >= self._blade_at:
                self._blade_at = None
                # the cut instant: end of this cycle's set point, material/carriage at the cycle boundary
                self.recorder.cut(c, self.material.position, self.drive.position)
            if self._cc_on_at is not None and c >= self._cc_on_at:
                inp.cut_completed = self.s.edge_sense == 0
                self._cc_on_at = None
            if self._cc_off_at is not None and c >= self._cc_off_at:
                inp.cut_completed = self.s.edge_sense != 0
                self._cc_off_at = None
        self._rtc_prev = rtc

    def run(self, seconds: float, until=None) -> None:
        n = int(round(seconds / self.period))
        for _ in range(n):
            self.step()
            if until is not None and until(self):
                return

    def run_until(self, cond, timeout: float) -> bool:
        n = int(round(timeout / self.period))
        for _ in range(n):
            self.step()
            if cond(self):
                return True
        return False

    # ------------------------------------------------------------------ helpers

    def enable(self, settle: float = 0.01) -> None:
        self.cutter.inputs.control_enable = True
        self.run(settle)

    def start(self) -> None:
        self.cutter.inputs.start_stop = True

    @property
    def time(self) -> float:
        return self.cycle * self.period

    def pieces(self) -> list:
        return [r for r in self.recorder.records if not math.isnan(r.actual_length)]
