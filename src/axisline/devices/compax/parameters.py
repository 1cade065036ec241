"""The COMPAX XX70 `Parameters` store (compax.md §3, manual §23); the parameters themselves, as
data, are in parameter_table.py.

    from axisline.devices.compax.parameters import Parameters, PARAMETERS
    params = Parameters()              # defaults (the state after RESETP)
    params[36] = 2.0                   # write: range-checked, not yet effective
    params.written[36], params[36]     # 2.0 written, 1.0 still valid (params[n] is the valid value)
    params.make_valid("VP")            # P36 is now armed ...
    params.make_valid("SETC")          # ... and valid at SETC or the next curve zero point
    params[36]                         # 2.0

Every parameter of compax.md §3 is a `ParamSpec` in `PARAMETERS`: number, meaning, unit,
min, default, max, "valid from", allowed values, resolution. Parameters of the standard
COMPAX that the supplement only references (§3.5: P1, P6, P13, P21, P40...P49, ...) are
there too, marked ``documented=False``: their ranges are in the standard User Guide, which
we do not have, so only what the supplement says about them is checked.

Written, armed, valid
---------------------
A value written (``params[n] = v``) is range-checked at once and kept as the *written*
value (``params.written[n]``: what the operator and the interface read back). It becomes
*valid* - ``params[n]`` and ``params.valid[n]``, what the drive works with - as the
parameter's "valid from" says:

==========================  ======================================================  =========
valid from                  becomes valid                                           params
==========================  ======================================================  =========
immediately                 at once                                                 P93, P210
VP                          with the command VP                                     most
VC                          with VC (valid configuration; drive disabled)           P80...P98, P143, P144
VP & SETC                   VP arms it, the next SETC makes it valid                P34
VP & curve zero / SETC      VP arms it; next curve zero point or SETC (footnote 5)  P36
VP & next curve             VP arms it; the next LOOP (the start of a curve);        P33
                            values 10...12 also at the end of the current cycle
VP & end of cycle           VP arms it; the end of the current curve cycle or LOOP  P32
VP (P35)                    with VP; but if P30 >= 10 and the slave is synchronous  P35
                            (O16 = 1) only at the end of the master cycle (§17)
==========================  ======================================================  =========

`Parameters.make_valid(event)` takes the events "VP", "VC", "SETC", "LOOP",
"curve_zero" and "cycle_end" and returns the numbers whose valid value changed
(`accept` is the same and also takes "CYCLE" for "cycle_end"). The cam operation sends
"SETC" / "LOOP" when it executes those commands and "cycle_end" at every master cycle
wrap. ``params.synchronous`` (O16) delays a P35 accepted with P30 >= 10 to the cycle end;
it stays False unless the owner sets it (the master chain may do that transfer itself).

Cross-parameter rules are checked when the values become valid, so the order of writing
does not matter: at VP, P79 < P13 and the HEDA rules (P243 bit 0/1 needs P250 = 1 and
P245 = P246 = 0); at VC, the roller-feed ranges (P80 = 32: P83 30...3000 mm, P83/P85 <=
300 mm) and the "Increments" resolution (P80 = 16, P90 = 0: P83 = 2^n, n = 4...16). A
failed VP or VC raises `CompaxError` and makes nothing valid.

Decisions (spec line -> choice, why)
------------------------------------
1. [see valueranges.py] the formulas' "P93" read as P90 (`scaled_slave_cycle`).
2. §2.3 / §3.2 [CONFLICT] P82 max 7000 (text §4.3) vs 70 000 kgcm² (table §23): the
   parameter table, 70 000, because it is the manual's list of accepted ranges.
3. §2.16 [CONFLICT] P179 "2^23 ... ca. 5.8 hours" vs table max "4Mio": the table,
   4 000 000 ms; 2^23 ms (2.33 h, not 5.8 h) is rejected.
4. §3.1 P180 default "0 (ParameterEditor) / 100 (after RESETP)": 100 - we are the
   device, and RESETP is the device's own reset.
5. §3.1 P180 has no maximum ("or >100": unlimited); none is imposed. Its "valid from" is
   not given [GAP]: VP like the other label parameters.
6. [see valueranges.py] P36 keeps its table range; `drift_free_problems` checks P83 = 2^a only.
7. §3.1 P33 values: the table lists 0, 1, 2, 11, 12; §15.3.2 says "=10...12 ... The single
   digit indicates the label synchronization operation mode", so 10 (none, triggered) is
   allowed too.
8. §3.1 P32 min 0.000000, although §14.2 writes |P32|: the table's minimum (0) is
   enforced; the upper limit 10·M_T (10·S_T) depends on the curve and is checked by
   `check_label_sensor_distance`.
9. §2.10 [CONFLICT] P31 table wording vs §19.1: the meanings below are §19.1's.
10. §3.5 / ambiguity 8: P76 "0...16", P77 "0...18", yet §13.2 adds D/A signals 20...24:
    the quantity (pre-comma part) of P73, P74, P76, P77 may be 0...18 or 20...24.
    The password protection of P76/P77 is not modelled.
11. "cycle_end" and "curve_zero" are the same instant (the master cycle wrap is the
    curve zero point of the next cycle); both names are accepted and do the same.
12. P35 triggered transfer (§17): "Triggered transfer is only done in synchronous mode,
    i.e. with O16=1. Otherwise P35 is always transferred immediately." A P35 armed while
    synchronous is transferred at once when ``synchronous`` becomes False.
13. VC validates the VC parameters only and VP the VP parameters only (the supplement
    does not say that one implies the other).
14. RESETP sets every parameter's written and valid value to its default and clears
    everything pending (a reset, not a write).
15. [GAP] defaults the supplement does not give: P80 = 16 (universal drive, the only
    drive type with the drift-free "Increments" unit), P90 = 1 (mm), P144 = 4 (the only
    documented value), P13 = 10 (units; keeps the default P79 = 1 < P13). Standard
    parameters without a documented default start at 0 (P21 at 1, the neutral factor).
16. Values are stored at the parameter's resolution (e.g. 6 decimals for P35/P36 as the
    table prints "1.000000"); integer parameters accept integral numbers only.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from fractions import Fraction
from typing import Any

from axisline.devices.compax import E_UNKNOWN, E_VALUE, CompaxError, UnknownNumberError
from axisline.devices.compax.parameter_table import _DA_QUANTITIES, PARAMETERS, ParamSpec, Validity, _fmt
from axisline.devices.compax.valueranges import (  # the value-range rules, importable from here too
    AUX_VALENCES,
    MAX_SCALED_CYCLE,
    aux_mask,
    check_label_sensor_distance,
    check_master_cycle_range,
    check_slave_cycle_range,
    drift_free_problems,
    max_travel_revolutions,
    p35_ramp_error_percent,
    scaled_master_cycle,
    scaled_slave_cycle,
)

__all__ = [
    "AUX_VALENCES",
    "EVENTS",
    "MAX_SCALED_CYCLE",
    "PARAMETERS",
    "ParamSpec",
    "Parameters",
    "Validity",
    "aux_mask",
    "check_label_sensor_distance",
    "check_master_cycle_range",
    "check_slave_cycle_range",
    "drift_free_problems",
    "max_travel_revolutions",
    "p35_ramp_error_percent",
    "scaled_master_cycle",
    "scaled_slave_cycle",
]



#: Events `Parameters.make_valid` accepts.
EVENTS = ("VP", "VC", "SETC", "LOOP", "curve_zero", "cycle_end")

_ARMED_BY_VP = {
    Validity.VP_SETC,
    Validity.VP_CURVE_ZERO,
    Validity.VP_NEXT_CURVE,
    Validity.VP_CYCLE_END,
}


def _spec(number: Any) -> ParamSpec:
    if isinstance(number, bool) or not isinstance(number, int):
        raise UnknownNumberError(f"parameter number {number!r} must be an int (e.g. 31 for P31)",
                                 code=E_UNKNOWN, field="parameter", value=number)
    spec = PARAMETERS.get(number)
    if spec is None:
        raise UnknownNumberError(
            f"P{number} is not a parameter of the COMPAX XX70 model (known: "
            f"{', '.join(f'P{n}' for n in sorted(PARAMETERS))})",
            code=E_UNKNOWN, field="parameter", value=number,
        )
    return spec


def _check_value(spec: ParamSpec, value: Any) -> float | int:
    """The value as stored (int for integer parameters), or CompaxError naming P, value, range."""
    name = f"P{spec.number}"
    if isinstance(value, bool):
        raise CompaxError(f"{name} = {value!r} is not a number; allowed is {spec.range_text()}",
                          code=E_VALUE, field=name, value=value, allowed=spec.range_text())
    if not isinstance(value, (int, float, Fraction)):
        try:
            value = float(value)
        except (TypeError, ValueError):
            raise CompaxError(f"{name} = {value!r} is not a number; allowed is {spec.range_text()}",
                              code=E_VALUE, field=name, value=value, allowed=spec.range_text()) from None
    number = float(value)
    if not math.isfinite(number):
        raise CompaxError(f"{name} = {value!r} not allowed; allowed is {spec.range_text()}",
                          code=E_VALUE, field=name, value=value, allowed=spec.range_text())
    if spec.integer:
        if number != math.floor(number):
            raise CompaxError(f"{name} = {value!r} not allowed; allowed is {spec.range_text()}",
                              code=E_VALUE, field=name, value=value, allowed=spec.range_text())
        stored: float | int = int(number)
    else:
        stored = round(number, spec.decimals) + 0.0
    bad = False
    if spec.allowed is not None and stored not in spec.allowed:
        bad = True
    if spec.bitmask is not None and (stored < 0 or int(stored) & ~spec.bitmask):
        bad = True
    if spec.minimum is not None and stored < spec.minimum:
        bad = True
    if spec.maximum is not None and stored > spec.maximum:
        bad = True
    if spec.number in (73, 74, 76, 77) and int(stored) not in _DA_QUANTITIES:
        bad = True  # decision 10: quantity 19 does not exist
    if bad:
        raise CompaxError(f"{name} = {value!r} out of range; allowed is {spec.range_text()}",
                          code=E_VALUE, field=name, value=value, allowed=spec.range_text())
    return stored


class _View(Mapping[int, float]):
    """Read-only mapping of one value layer (written or valid) by parameter number."""

    __slots__ = ("_values",)

    def __init__(self, values: dict[int, Any]) -> None:
        self._values = values

    def __getitem__(self, number: int) -> Any:
        _spec(number)
        return self._values[number]

    def __iter__(self) -> Iterator[int]:
        return iter(sorted(self._values))

    def __len__(self) -> int:
        return len(self._values)


class Parameters:
    """All parameters with their written, armed and valid values (see the module doc).

    ``params[n]`` reads the valid value (in effect), ``params[n] = v`` writes one
    (range-checked; immediately-valid parameters become valid at once).
    ``params.written[n]`` is the value last written; ``params.pending()`` lists what is
    written or armed but not yet valid. Unknown numbers raise `UnknownNumberError`
    (a CompaxError and a KeyError).
    """

    def __init__(self) -> None:
        self._written: dict[int, Any] = {}
        self._valid: dict[int, Any] = {}
        self._armed: dict[int, Any] = {}
        self._unsent: set[int] = set()  # written since the last VP / VC
        self._synchronous = False
        self.valid: Mapping[int, Any] = _View(self._valid)
        self.written: Mapping[int, Any] = _View(self._written)
        #: the valid values as a plain dict (every number present, values checked when written):
        #: what the cam operation reads in its 1 ms cycle without the number check of ``params[n]``.
        #: The same dict for the life of the object (RESETP and `restore` change it in place).
        self.valid_values: dict[int, Any] = self._valid
        self.resetp()

    # -- access --------------------------------------------------------------------------

    @staticmethod
    def spec(number: int) -> ParamSpec:
        return _spec(number)

    def __getitem__(self, number: int) -> Any:
        _spec(number)
        return self._valid[number]

    def __setitem__(self, number: int, value: Any) -> None:
        spec = _spec(number)
        stored = _check_value(spec, value)
        self._written[number] = stored
        if spec.valid_from is Validity.IMMEDIATE:
            self._valid[number] = stored
            self._unsent.discard(number)
        else:
            self._unsent.add(number)

    def __contains__(self, number: object) -> bool:
        return number in PARAMETERS

    def __iter__(self) -> Iterator[int]:
        return iter(sorted(PARAMETERS))

    def format(self, number: int, *, valid: bool = False) -> str:
        """The value as the device prints it (integer parameters without decimals)."""
        spec = _spec(number)
        value = (self._valid if valid else self._written)[number]
        return _fmt(value, spec.decimals)

    def pending(self) -> dict[int, str]:
        """Numbers not yet valid: 'written' (waits for VP / VC) or 'armed' (waits for its trigger)."""
        out = {n: "armed" for n in self._armed}
        out.update({n: "written" for n in self._unsent})
        return dict(sorted(out.items()))

    def resetp(self) -> None:
        """RESETP: every parameter to its default, written and valid; nothing pending."""
        for number, spec in PARAMETERS.items():
            value = int(spec.default) if spec.integer else float(spec.default)
            self._written[number] = value
            self._valid[number] = value
        self._armed.clear()
        self._unsent.clear()

    def snapshot(self) -> Parameters:
        """A copy of the written, armed and valid values, for `restore`."""
        other = Parameters.__new__(Parameters)
        other._written, other._valid, other._armed = dict(self._written), dict(self._valid), dict(self._armed)
        other._unsent, other._synchronous = set(self._unsent), self._synchronous
        other.valid, other.written = _View(other._valid), _View(other._written)
        other.valid_values = other._valid
        return other

    def restore(self, snapshot: Parameters) -> None:
        """Put back the values of ``snapshot`` in place (undoes a line whose data could not be
        stored); O16 (`synchronous`) is the cam operation's and stays."""
        for mine, theirs in ((self._written, snapshot._written), (self._valid, snapshot._valid),
                             (self._armed, snapshot._armed)):
            mine.clear()
            mine.update(theirs)
        self._unsent.clear()
        self._unsent.update(snapshot._unsent)

    # -- synchronous operation (P35 triggered transfer) --------------------------------------

    @property
    def synchronous(self) -> bool:
        """O16, set by the cam operation; a P35 armed for the cycle end is taken when it drops."""
        return self._synchronous

    @synchronous.setter
    def synchronous(self, value: bool) -> None:
        self._synchronous = bool(value)
        if not self._synchronous and 35 in self._armed:
            self._valid[35] = self._armed.pop(35)

    # -- acceptance --------------------------------------------------------------------------

    def accept(self, event: str) -> list[int]:
        """`make_valid` with the event names any case, "CYCLE" meaning "cycle_end"."""
        name = str(event)
        aliases = {"cycle": "cycle_end", "cycle_end": "cycle_end", "curve_zero": "curve_zero",
                   "vp": "VP", "vc": "VC", "setc": "SETC", "loop": "LOOP"}
        return self.make_valid(aliases.get(name.lower(), name))

    def make_valid(self, event: str) -> list[int]:
        """Apply an acceptance event; returns the numbers whose valid value changed.

        "VP" / "VC": written values of VP / VC parameters become valid (or armed for the
        triggered ones); cross-parameter rules are checked first and a violation raises
        CompaxError with nothing changed. "SETC", "LOOP", "curve_zero" / "cycle_end":
        armed values whose trigger this is become valid.
        """
        if event not in EVENTS:
            raise CompaxError(f"event {event!r} unknown; allowed: {', '.join(EVENTS)}",
                              field="event", value=event, allowed=", ".join(EVENTS))
        before = dict(self._valid)
        if event == "VP":
            self._accept_vp()
        elif event == "VC":
            self._accept_vc()
        else:
            for number in sorted(self._armed):
                if self._fires(number, event):
                    self._valid[number] = self._armed.pop(number)
        return [n for n in sorted(self._valid) if self._valid[n] != before[n]]

    def _fires(self, number: int, event: str) -> bool:
        kind = PARAMETERS[number].valid_from
        cycle_end = event in ("cycle_end", "curve_zero")
        if kind is Validity.VP_SETC:
            return event == "SETC"
        if kind is Validity.VP_CURVE_ZERO:
            return event == "SETC" or cycle_end
        if kind is Validity.VP_NEXT_CURVE:
            return event == "LOOP" or (cycle_end and self._armed[number] >= 10)
        if kind is Validity.VP_CYCLE_END:
            return event == "LOOP" or cycle_end
        if kind is Validity.VP_P35:
            return cycle_end
        return False

    def _accept_vp(self) -> None:
        numbers = sorted(n for n in self._unsent if PARAMETERS[n].valid_from is not Validity.VC)
        after = dict(self._valid)
        after.update({n: self._written[n] for n in numbers})
        self._check_vp_rules(after)
        for number in numbers:
            kind = PARAMETERS[number].valid_from
            value = self._written[number]
            if kind in _ARMED_BY_VP:
                self._armed[number] = value
            elif kind is Validity.VP_P35 and self._valid[30] >= 10 and self._synchronous:
                self._armed[number] = value  # P30 is accepted first (sorted), so its new value counts
            else:
                self._armed.pop(number, None)
                self._valid[number] = value
            self._unsent.discard(number)

    def _accept_vc(self) -> None:
        numbers = sorted(n for n in self._unsent if PARAMETERS[n].valid_from is Validity.VC)
        after = dict(self._valid)
        after.update({n: self._written[n] for n in numbers})
        self._check_vc_rules(after)
        for number in numbers:
            self._valid[number] = self._written[number]
            self._unsent.discard(number)

    @staticmethod
    def _check_vp_rules(v: Mapping[int, Any]) -> None:
        if not v[79] < v[13]:
            raise CompaxError(f"P79 = {v[79]} must be smaller than P13 = {v[13]} (§23: P79 < P13)",
                              code=E_VALUE, field="P79", value=v[79], allowed=f"< P13 = {v[13]}")
        if v[243] in (1, 2):
            if v[250] != 1:
                raise CompaxError(
                    f"P243 = {v[243]} (HEDA master / passive slave) needs P250 = 1, got P250 = {v[250]} (§6)",
                    code=E_VALUE, field="P250", value=v[250], allowed="1 with P243 = 1 or 2")
            for n in (245, 246):
                if v[n] != 0:
                    raise CompaxError(
                        f"P{n} = {v[n]} must be 0 in the HEDA modes master / passive slave (P243 = {v[243]}, §6)",
                        code=E_VALUE, field=f"P{n}", value=v[n], allowed="0 with P243 = 1 or 2")

    @staticmethod
    def _check_vc_rules(v: Mapping[int, Any]) -> None:
        if v[80] == 32:  # roller feed (§4.3)
            if not 30 <= v[83] <= 3000:
                raise CompaxError(f"P83 = {v[83]} out of range for the roller feed (P80 = 32): allowed 30 ... 3000 mm",
                                  code=E_VALUE, field="P83", value=v[83], allowed="30 ... 3000 mm")
            if v[83] / v[85] > 300:
                raise CompaxError(
                    f"roller feed restriction P83/P85 <= 300 mm violated: P83 = {v[83]}, P85 = {v[85]} "
                    f"(P83/P85 = {v[83] / v[85]:.3f} mm, §4.3)",
                    code=E_VALUE, field="P83/P85", value=v[83] / v[85], allowed="<= 300 mm")
        if v[80] == 16 and v[90] == 0:  # universal drive in increments (§4.2.2)
            p83 = v[83]
            if not (p83 == int(p83) and int(p83) in {1 << n for n in range(4, 17)}):
                raise CompaxError(
                    f"P83 = {p83} not allowed for the unit 'Increments' (P90 = 0, P80 = 16): "
                    "P83 must be 2^n with n = 4 ... 16 (16 ... 65536)",
                    code=E_VALUE, field="P83", value=p83, allowed="2^n, n = 4 ... 16")

    def __repr__(self) -> str:
        pending = self.pending()
        return f"Parameters({len(PARAMETERS)} parameters, pending={pending})"
