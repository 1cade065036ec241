"""The 12-byte process image: bit positions, data layouts, little-endian codecs (manual §3.7, wago.md §3)."""

from __future__ import annotations

import pytest

from axisline.devices.wago672.image import (
    C0,
    C1,
    C2,
    C3,
    S0,
    S1,
    S2,
    S3,
    ImageError,
    InputImage,
    OutputImage,
    PositioningActuals,
    PositioningSetpoints,
    ProgramActuals,
    ProgramSetpoints,
    SpeedSetpoints,
    decode_int24,
    encode_int24,
)


def test_control_and_status_bits_sit_where_the_manual_draws_them():
    # §3.7.2: C1 = Command(7..3) Start Stop2_N Enable; S1 = Command_Ack Start_ACK Stop_N_ACK Ready
    assert (C1.Enable, C1.Stop2_N, C1.Start, C1.M_Positioning, C1.M_DriveByMbx) == (1, 2, 4, 8, 0x80)
    assert (S1.Ready, S1.Stop_N_ACK, S1.Start_ACK, S1.M_Reference_ACK, S1.M_Jog_ACK) == (1, 2, 4, 0x20, 0x40)
    # C2 = Error_Quit PreCalc X X Acc_Range_Sel(2) Freq_Range_Sel(2)
    assert (C2.Freq_Range_Sel_0, C2.Acc_Range_Sel_1, C2.PreCalc, C2.Error_Quit) == (1, 8, 0x40, 0x80)
    # S2 = Error PreCalc_ACK Reference_OK Direction On_Speed StandStill Busy On_Target
    assert [S2.On_Target, S2.Busy, S2.StandStill, S2.On_Speed, S2.Direction, S2.Reference_OK, S2.PreCalc_ACK, S2.Error] == [
        1 << i for i in range(8)
    ]
    # C3 = Reset_Quit 0 0 0 Direction_Neg Direction_Pos 0 SetActual_Pos; S3 = Reset Warning Input6..Input1
    assert (C3.SetActual_Pos, C3.Direction_Pos, C3.Direction_Neg, C3.Reset_Quit) == (1, 4, 8, 0x80)
    assert (S3.Input1, S3.Input6, S3.Warning, S3.Reset) == (1, 0x20, 0x40, 0x80)
    assert (C0.MBX, S0.MBX, S0.ERR) == (0x20, 0x20, 0x40)


def test_output_image_byte_order_c0_reserved_d0_d6_c3_c2_c1():
    img = OutputImage(c0=0x20, c1=0x0B, c2=0x81, c3=0x84, data=bytes(range(1, 8)))
    raw = img.to_bytes()
    assert raw == bytes([0x20, 0x00, 1, 2, 3, 4, 5, 6, 7, 0x84, 0x81, 0x0B])
    assert OutputImage.from_bytes(raw) == img
    assert img.command == 1 and img.mailbox


def test_positioning_setpoints_little_endian_and_24_bit_signed_target():
    # wago.md §9.12: Velocity 20000, Acceleration 3000, Target 65065 -> 20 4E B8 0B 29 FE 00
    sp = PositioningSetpoints(20000, 3000, 65065)
    assert sp.encode() == bytes([0x20, 0x4E, 0xB8, 0x0B, 0x29, 0xFE, 0x00])
    assert PositioningSetpoints.decode(sp.encode()) == sp
    # a negative target -1000 is 0xFFFC18: 18 FC FF
    assert encode_int24(-1000) == bytes([0x18, 0xFC, 0xFF])
    assert decode_int24(bytes([0x18, 0xFC, 0xFF])) == -1000
    assert decode_int24(bytes([0xFF, 0xFF, 0x7F])) == 8388607
    assert decode_int24(bytes([0x00, 0x00, 0x80])) == -8388608


def test_out_of_range_fields_name_the_field_and_range():
    with pytest.raises(ImageError, match=r"Target position = 8388608 is outside -8388608 \.\. 8388607"):
        PositioningSetpoints(1, 1, 8388608).encode()
    with pytest.raises(ImageError, match="C1"):
        OutputImage(c1=256)
    with pytest.raises(ImageError, match="12 bytes"):
        OutputImage.from_bytes(bytes(11))


def test_mode_data_layouts():
    # speed control: signed velocity, acceleration, D4..D6 reserved (§3.11.1.11.1)
    assert SpeedSetpoints(-1000, 500).encode() == bytes([0x18, 0xFC, 0xF4, 0x01, 0, 0, 0])
    # run program: D2..D3 starting value of the command counter (§3.11.1.7.1)
    assert ProgramSetpoints(0x0102).encode() == bytes([0, 0, 0x02, 0x01, 0, 0, 0])
    assert ProgramActuals.decode(ProgramActuals(-5, 7, -2).encode()) == ProgramActuals(-5, 7, -2)
    # actuals: velocity D0..D1, D2..D3 reserved, position D4..D6
    assert PositioningActuals(-1, 65065).encode() == bytes([0xFF, 0xFF, 0, 0, 0x29, 0xFE, 0x00])


def test_mailbox_overlays_bytes_2_to_7():
    img = OutputImage.build(c1=0x83, mailbox_request=bytes([0x40, 0x80, 0x02, 0x29, 0xFE, 0x00]))
    raw = img.to_bytes()
    # wago.md §9.12: C0 = 0x20, MB0 = 0x40, MB1 = 0x80, MB2.. = 02 29 FE 00, C1 = 0x83
    assert raw == bytes([0x20, 0, 0x40, 0x80, 0x02, 0x29, 0xFE, 0x00, 0, 0, 0, 0x83])
    assert img.mailbox_request == bytes([0x40, 0x80, 0x02, 0x29, 0xFE, 0x00])
    reply = InputImage(s0=0x20, data=bytes([0x40, 0x80, 2, 0, 0, 0, 0]))
    assert reply.mailbox and reply.mailbox_reply[:2] == bytes([0x40, 0x80])
