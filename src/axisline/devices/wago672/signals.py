"""The signals the 750-672 consumes, read through their links once per tick (manual §4.5).

    s = Signals(bits.word(group), True)   # bit i: the i-th signal of SIGNALS
    if s.start and not prev.start: ...

Why an object and not a dict by name: the tick asks 60 questions of them, and in compiled code
(compiled_modules.txt) an attribute of a native class is read without a lookup. `Signals()` is
the state before the first tick: every signal 0 (`known` False).
"""

from __future__ import annotations

from axisline.devices.wago672.bits import Bit

__all__ = ["SIGNALS", "SIGNAL_BITS", "Signals"]

# name (the attribute) -> the bit it is read from; the order of the levels `Signals` takes
SIGNALS: tuple[tuple[str, int], ...] = (
    ("enable", Bit.Enable),
    ("stop2_n", Bit.Stop2_N),
    ("start", Bit.Start),
    ("cmd1", Bit.Command_1),
    ("cmd2", Bit.Command_2),
    ("cmd3", Bit.Command_3),
    ("cmd4", Bit.Command_4),
    ("cmd5", Bit.Command_5),
    ("enable_drive", Bit.Enable_Drive),
    ("reset_quit", Bit.Reset_Quit),
    ("dir_pos", Bit.Direction_Pos),
    ("dir_neg", Bit.Direction_Neg),
    ("set_reference", Bit.Set_Reference),
    ("precalc", Bit.PreCalc),
    ("setup_active", Bit.SetupSpeed_Active),
    ("error_quit", Bit.Error_Quit),
    ("ls_pos", Bit.LimitSwitch_Pos),
    ("ls_neg", Bit.LimitSwitch_Neg),
    ("stop1_n", Bit.Stop1_N),
    ("brake_manual", Bit.Brake_Manual),
    ("freq_sel_0", Bit.Freq_Range_Sel_0),
    ("freq_sel_1", Bit.Freq_Range_Sel_1),
    ("acc_sel_0", Bit.Acc_Range_Sel_0),
    ("acc_sel_1", Bit.Acc_Range_Sel_1),
    ("set_actual", Bit.Set_Actual_Pos),
    ("jog_pos", Bit.Jog_Pos),
    ("jog_neg", Bit.Jog_Neg),
    ("error_set", Bit.Error_Set),
)
SIGNAL_BITS: tuple[int, ...] = tuple(int(bit) for _, bit in SIGNALS)


class Signals:
    """One tick's consumed signals (see the module docstring)."""

    known: bool  # read from the bit table (False: before the first tick, all 0)
    enable: bool
    stop2_n: bool
    start: bool
    cmd1: bool
    cmd2: bool
    cmd3: bool
    cmd4: bool
    cmd5: bool
    enable_drive: bool
    reset_quit: bool
    dir_pos: bool
    dir_neg: bool
    set_reference: bool
    precalc: bool
    setup_active: bool
    error_quit: bool
    ls_pos: bool
    ls_neg: bool
    stop1_n: bool
    brake_manual: bool
    freq_sel_0: bool
    freq_sel_1: bool
    acc_sel_0: bool
    acc_sel_1: bool
    set_actual: bool
    jog_pos: bool
    jog_neg: bool
    error_set: bool

    def __init__(self, word: int = 0, known: bool = False) -> None:
        if not 0 <= word < 1 << len(SIGNALS):
            raise ValueError(f"signal word {word:#x} has bits beyond the {len(SIGNALS)} signals")
        self.known = known
        self.enable = word & 0x1 != 0
        self.stop2_n = word & 0x2 != 0
        self.start = word & 0x4 != 0
        self.cmd1 = word & 0x8 != 0
        self.cmd2 = word & 0x10 != 0
        self.cmd3 = word & 0x20 != 0
        self.cmd4 = word & 0x40 != 0
        self.cmd5 = word & 0x80 != 0
        self.enable_drive = word & 0x100 != 0
        self.reset_quit = word & 0x200 != 0
        self.dir_pos = word & 0x400 != 0
        self.dir_neg = word & 0x800 != 0
        self.set_reference = word & 0x1000 != 0
        self.precalc = word & 0x2000 != 0
        self.setup_active = word & 0x4000 != 0
        self.error_quit = word & 0x8000 != 0
        self.ls_pos = word & 0x10000 != 0
        self.ls_neg = word & 0x20000 != 0
        self.stop1_n = word & 0x40000 != 0
        self.brake_manual = word & 0x80000 != 0
        self.freq_sel_0 = word & 0x100000 != 0
        self.freq_sel_1 = word & 0x200000 != 0
        self.acc_sel_0 = word & 0x400000 != 0
        self.acc_sel_1 = word & 0x800000 != 0
        self.set_actual = word & 0x1000000 != 0
        self.jog_pos = word & 0x2000000 != 0
        self.jog_neg = word & 0x4000000 != 0
        self.error_set = word & 0x8000000 != 0

    def as_dict(self) -> dict[str, bool]:
        """name -> level (for displays and tests)."""
        return {name: bool(getattr(self, name)) for name, _ in SIGNALS}
