#!/usr/bin/env python3
"""Regenerates the damaged .stz files of this directory from
tests/golden/plotter.fc.stz (one segment-model block; docs/FORMAT.md gives
the offsets). Usage: python3 tests/golden-errors/make_errors.py"""
import os
import struct

M = (1 << 64) - 1
P1, P2, P3 = 11400714785074694791, 14029467366897019727, 1609587929392839161
P4, P5 = 9650029242287828579, 2870177450012600261


def rotl(x, r):
    return ((x << r) | (x >> (64 - r))) & M


def xxh64(data, seed=0):
    """XXH64 (the reference algorithm by Yann Collet), written out here."""
    n, i = len(data), 0

    def rnd(acc, lane):
        return (rotl((acc + lane * P2) & M, 31) * P1) & M

    if n >= 32:
        v = [(seed + P1 + P2) & M, (seed + P2) & M, seed, (seed - P1) & M]
        while i + 32 <= n:
            for k in range(4):
                v[k] = rnd(v[k], struct.unpack_from('<Q', data, i + 8 * k)[0])
            i += 32
        h = (rotl(v[0], 1) + rotl(v[1], 7) + rotl(v[2], 12) + rotl(v[3], 18)) & M
        for k in range(4):
            h = ((h ^ rnd(0, v[k])) * P1 + P4) & M
    else:
        h = (seed + P5) & M
    h = (h + n) & M
    while i + 8 <= n:
        h = (rotl(h ^ rnd(0, struct.unpack_from('<Q', data, i)[0]), 27) * P1 + P4) & M
        i += 8
    if i + 4 <= n:
        h = (rotl(h ^ (struct.unpack_from('<I', data, i)[0] * P1 & M), 23) * P2 + P3) & M
        i += 4
    while i < n:
        h = (rotl(h ^ (data[i] * P5 & M), 11) * P1) & M
        i += 1
    h = ((h ^ (h >> 33)) * P2) & M
    h = ((h ^ (h >> 29)) * P3) & M
    return h ^ (h >> 32)

here = os.path.dirname(os.path.abspath(__file__))
good = open(os.path.join(here, '..', 'golden', 'plotter.fc.stz'), 'rb').read()


def check32(b):
    return xxh64(b) & 0xFFFFFFFF


def block_end(frame, at=10):
    csize = struct.unpack_from('<I', frame, at + 2)[0]
    return at + 10 + csize + 4


def reseal(frame, at=10):
    """Recomputes the checksum of the block at `at` after an edit."""
    csize = struct.unpack_from('<I', frame, at + 2)[0]
    body = bytes(frame[at:at + 10 + csize])
    return frame[:at + 10 + csize] + struct.pack('<I', check32(body)) + frame[at + 10 + csize + 4:]


def edit(frame, pos, value):
    f = bytearray(frame)
    f[pos] = value
    return bytes(f)


assert check32(good[10:block_end(good) - 4]) == struct.unpack_from('<I', good, block_end(good) - 4)[0]
assert good[10] == 3, 'plotter.fc.stz should hold a segment-model block'
end = block_end(good)       # offset of the end mark
csize = struct.unpack_from('<I', good, 12)[0]
trailer_check = end + 1 + 8 * 4  # the end mark's type byte and statistics, then check32
# name: (error code, where the decoder must report it, bytes). The place is
# worked out from the edit and docs/FORMAT.md, not taken from the decoder.
files = {
    'bad_magic': ('bad magic', 'byte 0', edit(good, 0, 0x37)),
    'bad_version': ('bad version', 'byte 4', edit(good, 4, 99)),
    'reserved_header': ('reserved bits', 'byte 9', edit(good, 9, 1)),
    'reserved_segmenter': ('reserved bits', 'byte 8', edit(good, 8, good[8] | 0x80)),
    'reserved_block_flags': ('reserved bits', 'byte 11', edit(good, 11, good[11] | 4)),
    'unknown_block_type': ('corrupt', 'byte 10', edit(good, 10, 7)),
    'block_over_limit': ('limit', 'byte 12', good[:12] + struct.pack('<I', 2 << 30) + good[16:]),
    # A payload bit flipped: the block checksum (at the block's end) fails.
    'block_checksum': ('checksum', 'byte %d' % (end - 4), edit(good, 30, good[30] ^ 0x10)),
    # The stored block checksum itself changed, the block intact: it decodes
    # to the original and the content checksum holds, so only the block
    # check can reject this file.
    'block_checksum_only': ('checksum', 'byte %d' % (end - 4), edit(good, end - 4, good[end - 4] ^ 1)),
    'truncated_block': ('truncated', 'byte 40', good[:40]),
    'truncated_trailer': ('truncated', 'byte %d' % (end + 20), good[:end + 20]),
    'trailer_checksum': ('checksum', 'byte %d' % trailer_check, edit(good, end + 9, good[end + 9] ^ 1)),
    'content_checksum': ('checksum', 'byte %d' % (trailer_check + 4), edit(good, len(good) - 1, good[-1] ^ 1)),
    'trailing_bytes': ('corrupt', 'byte %d' % len(good), good + b'\0'),
    'empty_file': ('truncated', 'byte 0', b''),
    # A modeled block whose decoded size differs from its stored size.
    'model_sizes_differ': ('corrupt', 'byte 16', good[:16] + struct.pack('<I', csize + 1) + good[20:]),
    # A segment-model block whose range-coded stream lost its last byte
    # (sizes and block checksum made consistent again): the decoder must
    # notice, at the payload's end, that the stream does not end there.
    'model_stream_short': ('corrupt', 'byte 10 (block 0) payload byte %d' % (csize - 1), reseal(
        good[:12] + struct.pack('<II', csize - 1, struct.unpack_from('<I', good, 16)[0] - 1)
        + good[20:end - 5] + good[end - 4:])),
}
# Version 2 (docs/FORMAT.md 1.1-1.8), from tests/golden/v2/plotter.fc.stz:
# one segment-model block, window 2^22 declared.
good2 = open(os.path.join(here, '..', 'golden', 'v2', 'plotter.fc.stz'), 'rb').read()


def header2(frame, b5=None, b6=None):
    """`frame` with header bytes 5 and 6 replaced and the header check redone."""
    f = bytearray(frame)
    if b5 is not None:
        f[5] = b5
    if b6 is not None:
        f[6] = b6
    f[7] = (xxh64(bytes(f[:7])) >> 8) & 0xFF
    return bytes(f)


def varint_at(frame, at):
    v, shift = 0, 0
    while True:
        b = frame[at]
        at += 1
        v |= (b & 0x7F) << shift
        shift += 7
        if b < 0x80:
            return v, at


def block2(frame, at=8):
    """(payload end, checksum end) of the version-2 modeled block at `at`."""
    csize, p = varint_at(frame, at + 1)
    return p + csize, p + csize + 4


def reseal2(frame, at=8):
    end, _ = block2(frame, at)
    return frame[:end] + struct.pack('<I', check32(frame[at:end])) + frame[end + 4:]


assert good2[4] == 2 and good2[8] & 7 == 3, 'v2/plotter.fc.stz should hold a segment-model block'
assert check32(good2[8:block2(good2)[0]]) == struct.unpack_from('<I', good2, block2(good2)[0])[0]
end2 = block2(good2)[1]  # offset of the end mark
files.update({
    'v2_header_check': ('checksum', 'byte 7', edit(good2, 6, good2[6] ^ 0x08)),
    'v2_reserved_descriptor': ('reserved bits', 'byte 5', header2(good2, b5=good2[5] | 0x80)),
    'v2_window_over_limit': ('limit', 'byte 6', header2(good2, b6=(good2[6] & 7) | (24 << 3))),
    'v2_window_undeclared': ('corrupt', 'byte 8', reseal2(edit(header2(good2, b6=good2[6] & 7), 8, good2[8] | 0x20))),
    'v2_reserved_block_flags': ('reserved bits', 'byte 8', edit(good2, 8, good2[8] | 0x40)),
    'v2_trailer_flags': ('reserved bits', 'byte %d' % (len(good2) - 9), edit(good2, len(good2) - 9, 2)),
    'v2_content_checksum': ('checksum', 'byte %d' % (len(good2) - 8), edit(good2, len(good2) - 1, good2[-1] ^ 1)),
    'v2_partial_second_magic': ('corrupt', 'byte %d' % len(good2), good2 + good2[:3]),
    'v2_truncated_second_frame': ('truncated', 'byte %d' % (len(good2) + end2), good2 + good2[:end2]),
})


def put_varint(v):
    """A varint as the format writes it (docs/FORMAT.md 1.1)."""
    out = bytearray()
    while v >= 0x80:
        out.append((v & 0x7F) | 0x80)
        v >>= 7
    out.append(v)
    return bytes(out)


# The segment-model block of v2/plotter.fc.stz with start grid 0 (at least
# 1; section 1.5: nchains, nsegments, nsteps, then the grid): at the grid
# field.
g_csize, g_pay = varint_at(good2, 9)
g_payload = good2[g_pay:g_pay + g_csize]
g_at = 0
for _ in range(3):
    _, g_at = varint_at(g_payload, g_at)
g_new = g_payload[:g_at] + put_varint(0) + g_payload[varint_at(g_payload, g_at)[1]:]
g_body = good2[8:9] + put_varint(len(g_new)) + g_new
files.update({
    'v2_segment_grid': ('corrupt', 'byte 8 (block 0) payload byte %d' % g_at,
                        good2[:8] + g_body + struct.pack('<I', check32(g_body)) + good2[g_pay + g_csize + 4:]),
})


# Block type 6 (docs/FORMAT.md 1.11), from tests/golden/v2/strong_hershey.fc.stz:
# one mixed-model block of the segment model, no window.
strong = open(os.path.join(here, '..', 'golden', 'v2', 'strong_hershey.fc.stz'), 'rb').read()
assert strong[8] == 6, 'v2/strong_hershey.fc.stz should hold a mixed-model block'
s_csize, s_payload = varint_at(strong, 9)
assert strong[s_payload] == 0, 'v2/strong_hershey.fc.stz should hold a mixed segment model'
s_end = s_payload + s_csize
short = strong[:9] + put_varint(s_csize - 1) + strong[s_payload:s_end - 1]
short += struct.pack('<I', check32(short[8:])) + strong[s_end + 4:]
files.update({
    # The model byte names no model (0-3 do: model and curvature flag; 4 the
    # context-mixing step model, 5 and 7 its light version, 6 it with the DSS).
    'v2_mixed_unknown_model': ('corrupt', 'byte 8 (block 0) payload byte 0', reseal2(edit(strong, s_payload, 8))),
    # The range-coded stream lost its last byte (size and checksum redone):
    # the decoder notices at the payload's end.
    'v2_mixed_stream_short': ('corrupt', 'byte 8 (block 0) payload byte %d' % (s_csize - 1), short),
})
# Version 2, table block (docs/FORMAT.md 1.10), from tests/golden/v2/table.fc.stz:
# two table blocks (the second flagged `window`) and a step-model block.
def first_table_block(name):
    """tests/golden/v2/NAME, whose first block is a table block: the frame,
    that block's payload, a function giving the frame with the payload
    replaced (size and checksum redone), and the offset of the payload's
    table set (section 1.10: nchains, nsegments, nsteps, grid, layout)."""
    good = open(os.path.join(here, '..', 'golden', 'v2', name), 'rb').read()
    assert good[4] == 2 and good[8] & 7 == 5, 'v2/%s should start with a table block' % name
    csize, pay = varint_at(good, 9)
    end = pay + csize
    payload = good[pay:end]

    def rebuild(new):
        body = good[8:9] + put_varint(len(new)) + new
        return good[:8] + body + struct.pack('<I', check32(body)) + good[end + 4:]

    at = 0
    for _ in range(4):  # nchains, nsegments, nsteps, grid
        _, at = varint_at(payload, at)
    _, at = varint_at(payload, at)  # layout size
    stored, at = varint_at(payload, at)
    return good, payload, rebuild, at + stored


_, payloadT, table_block, set_at = first_table_block('table.fc.stz')
at = set_at
table_set, at = varint_at(payloadT, at)
for t in range(50):
    if not (table_set >> t) & 1:
        continue
    n1, at = varint_at(payloadT, at)
    if n1 == 0:
        _, at = varint_at(payloadT, at)  # the one symbol
        continue
    at += 1  # precision
    for _ in range(n1 + 1):
        _, at = varint_at(payloadT, at)  # gap
        _, at = varint_at(payloadT, at)  # frequency - 1
rans_at = at
rans_size, after = varint_at(payloadT, rans_at)
assert after + rans_size < len(payloadT)
whereT = 'byte 8 (block 0) payload byte %d'
files.update({
    # Bit 50 of the table set: no such table.
    'v2_table_set': ('corrupt', whereT % set_at,
                     table_block(payloadT[:set_at] + put_varint(table_set | (1 << 50)) +
                                 payloadT[set_at + len(put_varint(table_set)):])),
    # A rANS stream size past the payload's end.
    'v2_table_rans_size': ('corrupt', whereT % rans_at,
                           table_block(payloadT[:rans_at] + put_varint(len(payloadT)) + payloadT[after:])),
    # A byte after the extra bits: every bit is read where the payload ended.
    'v2_table_extra_byte': ('corrupt', whereT % len(payloadT), table_block(payloadT + b'\x00')),
})
grid_at = 0
for _ in range(3):  # nchains, nsegments, nsteps: the start grid follows
    _, grid_at = varint_at(payloadT, grid_at)
grid_end = varint_at(payloadT, grid_at)[1]
files.update({
    # Start grid 0 (at least 1): at the grid field.
    'v2_table_grid': ('corrupt', whereT % grid_at,
                      table_block(payloadT[:grid_at] + put_varint(0) + payloadT[grid_end:])),
})
# Block type 7 subtype 0, the timed block (docs/FORMAT.md 1.12), from
# tests/golden/v2/timed.steps.stz: its first block is a timed block.
timed = open(os.path.join(here, '..', 'golden', 'v2', 'timed.steps.stz'), 'rb').read()
assert timed[8] & 7 == 7, 'v2/timed.steps.stz should start with a timed block'
t_csize, t_payload = varint_at(timed, 9)
assert timed[t_payload] == 0 and timed[t_payload + 1] in (0, 1)
files.update({
    # A subtype that names no block (1 and up; the timed block is 0).
    'v2_timed_unknown_subtype': ('corrupt', 'byte 8 (block 0) payload byte 0', reseal2(edit(timed, t_payload, 9))),
    # A coding that is neither 0 (plain) nor 1 (mixed predictions).
    'v2_timed_unknown_coding': ('corrupt', 'byte 8 (block 0) payload byte 1', reseal2(edit(timed, t_payload + 1, 2))),
})


def first_extended_block(name, subtype, second):
    """The bytes of tests/golden/v2/NAME and where its first block's payload
    starts; that block must be of type 7 with SUBTYPE and payload byte 1
    SECOND."""
    data = open(os.path.join(here, '..', 'golden', 'v2', name), 'rb').read()
    assert data[8] & 7 == 7, 'v2/%s should start with an extended block' % name
    _, at = varint_at(data, 9)
    assert data[at] == subtype and data[at + 1] == second, 'v2/%s: subtype %d, byte 1 %d' % (name, subtype, second)
    return data, at


# Block type 7 subtype 2, the tick block (docs/FORMAT.md 1.13), from
# tests/golden/v2/tick.steps.stz: its first block is a tick block.
tick, k_payload = first_extended_block('tick.steps.stz', 2, 0)
files.update({
    # A coding that is none of 0 (plain), 1 (mixed predictions) and 2 (mixed but the sure bits).
    'v2_tick_unknown_coding': ('corrupt', 'byte 8 (block 0) payload byte 1', reseal2(edit(tick, k_payload + 1, 3))),
    # Subtype 9 names no block (0 timed, 1 interrupt, 2 tick, 4 table).
    'v2_tick_unknown_subtype': ('corrupt', 'byte 8 (block 0) payload byte 0', reseal2(edit(tick, k_payload, 9))),
})
# Block type 7 subtype 1, the interrupt block (docs/FORMAT.md 1.14), from
# tests/golden/v2/interrupt.steps.stz: its first block is an interrupt block.
irq, i_payload = first_extended_block('interrupt.steps.stz', 1, 0)
i_csize, _ = varint_at(irq, 9)
i_end = i_payload + i_csize
i_short = irq[:9] + put_varint(i_csize - 1) + irq[i_payload:i_end - 1]
i_short += struct.pack('<I', check32(i_short[8:])) + irq[i_end + 4:]
files.update({
    # A coding that is neither 0 (plain) nor 1 (mixed predictions).
    'v2_interrupt_unknown_coding': ('corrupt', 'byte 8 (block 0) payload byte 1', reseal2(edit(irq, i_payload + 1, 7))),
    # Read as a tick block (subtype 2), its followers B[a] read other letters:
    # the decoded ticks differ and the stream runs out before the last one.
    'v2_interrupt_as_tick': ('corrupt', 'byte 8 (block 0) payload byte %d' % i_csize, reseal2(edit(irq, i_payload, 2))),
    # The range-coded stream lost its last byte (size and checksum redone):
    # the decoder notices at the payload's end.
    'v2_interrupt_stream_short': ('corrupt', 'byte 8 (block 0) payload byte %d' % (i_csize - 1), i_short),
})


def damaged_layout(frame, pay, at):
    """`frame` whose first block's payload starts at PAY and has its layout
    field at payload byte AT: that field replaced by one declaring a
    compressed layout (size 100, 4 stored bytes) whose bytes are no zstd
    frame, the payload size and block checksum redone."""
    csize, _ = varint_at(frame, 9)
    payload = frame[pay:pay + csize]
    size, p = varint_at(payload, at)
    stored, p = varint_at(payload, p)
    new = payload[:at] + put_varint(100) + put_varint(4) + b'\x00' * 4 + payload[p + stored:]
    body = frame[8:9] + put_varint(len(new)) + new
    return frame[:8] + body + struct.pack('<I', check32(body)) + frame[pay + csize + 4:]


_, k_at = varint_at(tick, k_payload + 2)  # nchains
_, k_at = varint_at(tick, k_at)           # nsteps: the layout field follows
files.update({
    # A compressed layout that is no zstd frame: at the layout field.
    'v2_tick_layout': ('corrupt', 'byte 8 (block 0) payload byte %d' % (k_at - k_payload),
                       damaged_layout(tick, k_payload, k_at - k_payload)),
})
# Arc items (docs/FORMAT.md 1.10.1), from tests/golden/v2/arcs_eval.fc.stz:
# one table block that codes arcs (table-set bit 53, then the method byte).
_, payloadA, arc_block, set_atA = first_table_block('arcs_eval.fc.stz')
table_setA, method_atA = varint_at(payloadA, set_atA)
assert (table_setA >> 53) & 1 and payloadA[method_atA] == 0, 'arcs_eval: an arc block of method evaluation'
files.update({
    # Arc method 5: no such method.
    'v2_arc_method': ('corrupt', whereT % method_atA,
                      arc_block(payloadA[:method_atA] + b'\x05' + payloadA[method_atA + 1:])),
    # The arc flag (bit 53) cleared: the arc tables (bits 50-52) without it.
    'v2_arc_flag': ('corrupt', whereT % set_atA,
                    arc_block(payloadA[:set_atA] + put_varint(table_setA & ~(1 << 53)) + payloadA[method_atA:])),
})
# Block type 7 subtype 4, the table block with unpredicted minor totals
# (docs/FORMAT.md 1.10.2), from tests/golden/v2/table_raw.fc.stz: its first
# block is one (subtype 4, flags 1).
raw, r_payload = first_extended_block('table_raw.fc.stz', 4, 1)
files.update({
    # Flags 3: bit 1 names nothing (1, unpredicted minor totals, is the only value).
    'v2_table_raw_flags': ('corrupt', 'byte 8 (block 0) payload byte 1', reseal2(edit(raw, r_payload + 1, 3))),
})
# The context-mixing step model (docs/FORMAT.md 1.11.2), from
# tests/golden/v2/cm_glyphs.fc.stz: its first block is a type 6 block of
# model byte 4 (not flagged `window`).
cm = open(os.path.join(here, '..', 'golden', 'v2', 'cm_glyphs.fc.stz'), 'rb').read()
assert cm[8] & 7 == 6 and not cm[8] & 0x20, 'v2/cm_glyphs.fc.stz should start with a mixed-model block'
c_csize, c_payload = varint_at(cm, 9)
assert cm[c_payload] == 4, 'v2/cm_glyphs.fc.stz should start with a context-mixing step model'
c_end = c_payload + c_csize


def first_payload_replaced(frame, end, new):
    """A version-2 frame whose first block ends at `end` (before its
    checksum), with that block's payload replaced (size and block checksum
    redone)."""
    body = frame[8:9] + put_varint(len(new)) + new
    return frame[:8] + body + struct.pack('<I', check32(body)) + frame[end + 4:]


def cm_block(new):
    """cm_glyphs.fc.stz with its first block's payload replaced."""
    return first_payload_replaced(cm, c_end, new)


files.update({
    # The range-coded stream lost its last byte: the decoder reads past the
    # payload's end (at its new end).
    'v2_cm_stream_short': ('corrupt', 'byte 8 (block 0) payload byte %d' % (c_csize - 1),
                           cm_block(cm[c_payload:c_end - 1])),
    # A byte after the stream's end: the stream does not end at the
    # payload's end (at the added byte).
    'v2_cm_extra_byte': ('corrupt', 'byte 8 (block 0) payload byte %d' % c_csize,
                         cm_block(cm[c_payload:c_end] + b'\x00')),
})
_, c_at = varint_at(cm, c_payload + 1)  # nchains
_, c_at = varint_at(cm, c_at)           # nsteps: the layout field follows
files.update({
    # A compressed layout that is no zstd frame: at the layout field.
    'v2_cm_layout': ('corrupt', 'byte 8 (block 0) payload byte %d' % (c_at - c_payload),
                     damaged_layout(cm, c_payload, c_at - c_payload)),
})
# The light context-mixing step model (docs/FORMAT.md 1.11.3), from
# tests/golden/v2/light_glyphs.fc.stz: its first block is a type 6 block of
# model byte 5 (not flagged `window`).
light = open(os.path.join(here, '..', 'golden', 'v2', 'light_glyphs.fc.stz'), 'rb').read()
assert light[8] & 7 == 6 and not light[8] & 0x20, 'v2/light_glyphs.fc.stz should start with a mixed-model block'
l_csize, l_payload = varint_at(light, 9)
assert light[l_payload] == 5, 'v2/light_glyphs.fc.stz should start with a light context-mixing step model'
l_end = l_payload + l_csize


files.update({
    # The range-coded stream lost its last byte (at the payload's new end).
    'v2_light_stream_short': ('corrupt', 'byte 8 (block 0) payload byte %d' % (l_csize - 1),
                              first_payload_replaced(light, l_end, light[l_payload:l_end - 1])),
    # A byte after the stream's end (at the added byte).
    'v2_light_extra_byte': ('corrupt', 'byte 8 (block 0) payload byte %d' % l_csize,
                            first_payload_replaced(light, l_end, light[l_payload:l_end] + b'\x00')),
})
# The guess bit of the tick block's coding byte (docs/FORMAT.md 1.13,
# "Guess") goes with codings 1 and 2 only: on tick.steps.stz's first block
# (coding 0) it makes an unknown coding.
files.update({
    'v2_tick_guess_plain': ('corrupt', 'byte 8 (block 0) payload byte 1', reseal2(edit(tick, k_payload + 1, 8))),
})
# The guided bit (16, "Guided mixing") likewise.
files.update({
    'v2_tick_guided_plain': ('corrupt', 'byte 8 (block 0) payload byte 1', reseal2(edit(tick, k_payload + 1, 16))),
    # The match bit (32) needs a mixed coding too (FORMAT.md 1.13 "Match").
    'v2_tick_match_plain': ('corrupt', 'byte 8 (block 0) payload byte 1', reseal2(edit(tick, k_payload + 1, 32))),
})
# The window bit (64, FORMAT.md 1.13 "Match"), from
# tests/golden/v2/tick_window.steps.stz: an interrupt block of coding byte
# 62, then one of coding byte 126 flagged `window`.
twin, w_payload = first_extended_block('tick_window.steps.stz', 1, 62)
w_second = block2(twin)[1]
_, w_payload2 = varint_at(twin, w_second + 1)
assert twin[w_second] & 0x20 and twin[w_payload2 + 1] == 126, 'v2/tick_window.steps.stz: second block'
files.update({
    # The bit without the match bit (coding byte 94): an unknown coding.
    'v2_tick_window_no_match': ('corrupt', 'byte 8 (block 0) payload byte 1', reseal2(edit(twin, w_payload + 1, 94))),
    # The second block's window flag cleared: its match has no window to read.
    'v2_tick_window_unflagged': ('corrupt', 'byte %d (block 1) payload byte 1' % w_second,
                                 reseal2(edit(twin, w_second, twin[w_second] & ~0x20), w_second)),
})
# The refine bit (128, FORMAT.md 1.13 "Match"), from
# tests/golden/v2/tick_refine.steps.stz: a tick block of coding byte 132
# (coding 0 with the restart and refine bits), then one of 196 (and the
# window bit) flagged `window`.
tref, f_payload = first_extended_block('tick_refine.steps.stz', 2, 132)
files.update({
    # The bit with a mixed coding (tick_window's first block, 62 + 128): an unknown coding.
    'v2_tick_refine_mixed': ('corrupt', 'byte 8 (block 0) payload byte 1', reseal2(edit(twin, w_payload + 1, 190))),
    # Coding 0 with the window bit but neither the match nor the refine bit (68).
    'v2_tick_window_plain': ('corrupt', 'byte 8 (block 0) payload byte 1', reseal2(edit(tref, f_payload + 1, 68))),
})
# Block type 7 subtypes 5 and 6, the tick and interrupt blocks with a model
# byte (docs/FORMAT.md 1.16), from tests/golden/v2/tick_planner.steps.stz:
# its first block is an interrupt block (subtype 6) of coding byte 62 and
# model byte 1, the planner model.
tplan, p_payload = first_extended_block('tick_planner.steps.stz', 6, 62)
assert tplan[p_payload + 2] == 1, 'v2/tick_planner.steps.stz: model byte'
files.update({
    # A model byte no version names (255, at the model byte; 2 is the
    # slot lines of FORMAT.md 1.17 on this mixed interrupt block).
    'v2_tick_planner_unknown_model': ('corrupt', 'byte 8 (block 0) payload byte 2',
                                      reseal2(edit(tplan, p_payload + 2, 255))),
})
# Model byte 2, the planner model with slot lines (docs/FORMAT.md 1.17),
# from tests/golden/v2/tick_slots.steps.stz: its first block is an
# interrupt block (subtype 6) of coding byte 62 and model byte 2; and from
# tests/golden/v2/tick_planner_plain.steps.stz, whose first block is a
# plain interrupt block (coding byte 132) of model byte 1.
tslot, s_payload = first_extended_block('tick_slots.steps.stz', 6, 62)
assert tslot[s_payload + 2] == 2, 'v2/tick_slots.steps.stz: model byte'
tplain, q_payload = first_extended_block('tick_planner_plain.steps.stz', 6, 132)
assert tplain[q_payload + 2] == 1, 'v2/tick_planner_plain.steps.stz: model byte'
files.update({
    # Slot lines on a tick block: subtype 6 set to 5 (at the model byte).
    'v2_tick_slots_tick_block': ('corrupt', 'byte 8 (block 0) payload byte 2', reseal2(edit(tslot, s_payload, 5))),
    # Slot lines with the plain coding: model byte 1 set to 2.
    'v2_tick_slots_plain': ('corrupt', 'byte 8 (block 0) payload byte 2', reseal2(edit(tplain, q_payload + 2, 2))),
})
# Block type 7 subtype 3, the CM raw block (docs/FORMAT.md 1.15), from
# tests/golden/v2/raw_cm.hpgl.stz: its first block is one (coding 0).
rcm, r_payload = first_extended_block('raw_cm.hpgl.stz', 3, 0)
r_csize, _ = varint_at(rcm, 9)
r_end = r_payload + r_csize
_, r_stream = varint_at(rcm, r_payload + 2)  # D: the stream follows
files.update({
    # A coding other than 0.
    'v2_raw_cm_unknown_coding': ('corrupt', 'byte 8 (block 0) payload byte 1', reseal2(edit(rcm, r_payload + 1, 1))),
    # D above 256 MiB + 20: at D's field, before anything is decoded.
    'v2_raw_cm_size_limit': ('limit', 'byte 8 (block 0) payload byte 2',
                             first_payload_replaced(rcm, r_end, rcm[r_payload:r_payload + 2] +
                                                    put_varint((256 << 20) + 21) + rcm[r_stream:r_end])),
    # The range-coded stream lost its last byte (at the payload's new end).
    'v2_raw_cm_stream_short': ('corrupt', 'byte 8 (block 0) payload byte %d' % (r_csize - 1),
                               first_payload_replaced(rcm, r_end, rcm[r_payload:r_end - 1])),
    # A byte after the stream's end (at the added byte).
    'v2_raw_cm_extra_byte': ('corrupt', 'byte 8 (block 0) payload byte %d' % r_csize,
                             first_payload_replaced(rcm, r_end, rcm[r_payload:r_end] + b'\x00')),
})
for name, (code, where, data) in files.items():
    open(os.path.join(here, name + '.stz'), 'wb').write(data)
    open(os.path.join(here, name + '.expect'), 'w').write(code + '\n' + where + '\n')
