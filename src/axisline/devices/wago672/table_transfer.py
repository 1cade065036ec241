"""Downloading and uploading tables through the mailbox (DLD_START, DLD_CONT, DLD_END; tables.py
describes them and lists the decisions): a layer of `TableManager` over `TableStore`.
"""

from __future__ import annotations

from axisline.devices.wago672.config_table import CONF_VERSION, TABLE_SIZE, ConfigValueError
from axisline.devices.wago672.table_store import (
    _RAM_KINDS,
    INVALID_POSITION,
    MAX_DATA_SETS,
    RUN_COMMANDS,
    TRC,
    Storage,
    Table,
    TableKind,
    TableStatus,
    TableStore,
    _reply,
    _s24,
    _s32,
    _Transfer,
)

__all__ = ["TableTransfers"]


class TableTransfers(TableStore):
    """Table downloads and uploads (see the module docstring)."""

    # ================================================================== download / upload

    def dld_start(self, location: int, kind: int, count: int, transfer: int) -> tuple[int, bytes]:
        """DLD_START: MB2 location, MB3 kind, count 0..4095, transfer 0..3 (T1)."""
        if self._transfer is not None and not self._transfer.upload:
            self._abort_transfer()
        self._transfer = None

        def refuse(rc: int = TRC.FAULT) -> tuple[int, bytes]:
            return _reply(rc, 1, 0, 0, CONF_VERSION)

        try:
            kind = TableKind(kind)
        except ValueError:
            return refuse()
        if transfer not in (0, 1, 2, 3):
            return refuse()
        upload = transfer in (1, 3)
        wide = transfer in (2, 3)
        if kind in (TableKind.CONFIG, TableKind.TRACE):
            if location not in (0, 1):
                return refuse()
            location = 1
        elif location not in (1, 2):
            return refuse()
        if not 1 <= count <= MAX_DATA_SETS[kind]:
            return refuse()
        if kind in (TableKind.POSITION, TableKind.CONFIG) and not wide:
            return refuse()  # "Only 32-bit data exists for the position tables and the configuration"
        if kind == TableKind.TRACE and not upload:
            return refuse()
        if kind == TableKind.CONFIG and not upload and count != MAX_DATA_SETS[kind]:
            return refuse()  # "A complete table, with 128 data values, 32 bit each, is always expected"
        tr = _Transfer(kind, location, count, upload, wide)
        if upload:
            blocks = self._upload_blocks(kind, location, count, wide)
            if blocks is None:
                return refuse()
            tr.blocks = blocks
        else:
            if kind == TableKind.PROGRAM and self.active[kind] == location:
                return refuse(TRC.TABLE_USED)
            if kind in _RAM_KINDS:
                tr.table = Table.default(kind, TableStatus.INVALID)
                if self.active.get(kind) != location:
                    self.ram[(kind, location)] = Table.default(kind, TableStatus.INVALID)
            else:
                tr.raw = bytearray()
        self._transfer = tr
        return _reply(TRC.OK, 0, 0, count & 0xFF, CONF_VERSION)

    def _upload_blocks(self, kind: TableKind, location: int, count: int, wide: bool) -> list[bytes] | None:
        if kind == TableKind.TRACE:
            data = self.trace_source() if self.trace_source is not None else None
            if not data or count > len(data):
                return None
            return [(v & 0xFFFFFFFF).to_bytes(4, "little") for v in data[:count]]
        if kind == TableKind.CONFIG:
            raw = self.device.config.to_bytes()
            return [raw[4 * i : 4 * i + 4] for i in range(count)]
        t = self.ram[(kind, location)]
        if not t.valid or count > t.size:
            return None
        blocks: list[bytes] = []
        for e in t.entries[:count]:
            if kind == TableKind.POSITION:
                blocks.append((e & 0xFFFFFFFF).to_bytes(4, "little"))
                continue
            head, value = e  # (command | sample, data | position)
            if wide:
                blocks.append(bytes([head, 0, 0, 0]))
                blocks.append((value & 0xFFFFFFFF).to_bytes(4, "little"))
            else:
                blocks.append(bytes([head]) + (value & 0xFFFFFF).to_bytes(3, "little"))
        return blocks

    def _abort_transfer(self) -> None:
        """A previous, incomplete download is cancelled and becomes invalid."""
        tr = self._transfer
        self._transfer = None
        if tr is None or tr.upload or tr.kind not in _RAM_KINDS:
            return
        self._invalidate(tr.kind, tr.location, tr.table)

    def _invalidate(self, kind: TableKind, location: int, content: Table | None) -> None:
        t = content.copy() if content is not None else Table.default(kind)
        t.status = TableStatus.INVALID
        self.ram[(kind, location)] = t
        if self.active.get(kind) == location:
            self._activate(kind, 0)

    def dld_cont(self, data: bytes) -> tuple[int, bytes]:
        """DLD_CONT: one 4-byte block (download) or the next 4 bytes of an upload."""
        d = bytes(data).ljust(4, b"\x00")[:4]
        tr = self._transfer
        if tr is None:
            return _reply(TRC.FAULT)
        if tr.upload:
            if tr.done >= len(tr.blocks):
                return _reply(TRC.FAULT)
            block = tr.blocks[tr.done]
            tr.done += 1
            tr.checksum = (tr.checksum + sum(block)) & 0xFFFFFFFF
            return TRC.OK, block
        if tr.done >= tr.count:
            return _reply(TRC.FAULT)
        tr.checksum = (tr.checksum + sum(d)) & 0xFFFFFFFF
        bad = False
        if tr.kind == TableKind.CONFIG:
            tr.raw += d
            tr.done += 1
        elif tr.kind == TableKind.POSITION:
            value = _s32(int.from_bytes(d, "little"))  # 0x80000000: an entry without position
            assert tr.table is not None
            tr.table.entries[tr.done] = value
            tr.done += 1
        else:
            if tr.wide and tr.half is None:
                tr.half = d[0]  # step n.1: command / bit sample, MB3..MB5 ignored
                return _reply(TRC.OK, *d)
            if tr.wide:
                head = tr.half
                assert head is not None
                tr.half = None
                value = _s32(int.from_bytes(d, "little"))
                if tr.kind == TableKind.PROGRAM and d[3] not in (0x00, 0xFF):
                    bad = True  # T5
            else:
                head = d[0]
                value = _s24(int.from_bytes(d[1:4], "little"))
            assert tr.table is not None
            if tr.kind == TableKind.PROGRAM:
                bad = bad or head not in RUN_COMMANDS
                tr.table.entries[tr.done] = (head, value)
            else:
                if value != INVALID_POSITION:
                    if tr.last_position is not None and value <= tr.last_position:
                        bad = True
                    tr.last_position = value
                tr.table.entries[tr.done] = (head, value)
            tr.done += 1
        if bad:
            tr.corrupt = True
            return _reply(TRC.CORRUPT, *d)
        return _reply(TRC.OK, *d)

    def dld_end(self, checksum: int) -> tuple[int, bytes]:
        """DLD_END: compare the checksum, validate (or not) the table; configuration: EEPROM, warm start."""
        tr = self._transfer
        self._transfer = None
        if tr is None:
            return _reply(TRC.FAULT)
        stored = tr.checksum.to_bytes(4, "little")
        if tr.upload:
            return TRC.OK, stored
        ok = not tr.corrupt and tr.done == tr.count and tr.half is None and (checksum & 0xFFFFFFFF) == tr.checksum
        if tr.kind == TableKind.CONFIG:
            return self._config_download(bytes(tr.raw), ok, stored)
        assert tr.table is not None
        if not ok:
            self._invalidate(tr.kind, tr.location, tr.table)
            return TRC.FAULT, stored
        table = tr.table
        table.status = TableStatus.VALID
        self.ram[(tr.kind, tr.location)] = table
        if self.active.get(tr.kind) == tr.location:
            self._activate(tr.kind, tr.location)  # an active camshaft/position table: new content now
        elif tr.kind == TableKind.PROGRAM and tr.location == Storage.RAM1 and not self.active[tr.kind]:
            self._activate(tr.kind, 1)  # "automatically activated (only when no other table is active)"
        return TRC.OK, stored

    def _config_download(self, data: bytes, ok: bool, stored: bytes) -> tuple[int, bytes]:
        rc = TRC.FAULT
        if ok and len(data) == TABLE_SIZE:
            probe = self.device.config.copy()
            try:
                probe.load_bytes(data)  # T2: ConfVersion, ranges, rules
            except ConfigValueError:
                pass
            else:
                self.config_user = probe.to_bytes()
                self._job(lambda: None)  # saved; the warm start completes the write
                rc = TRC.OK
        self.device.warm_start()  # "with a subsequent warm start (even if the transfer was faulted)"
        return rc, stored
