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
    'bad_version': ('bad version', 'byte 4', edit(good, 4, 2)),
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
for name, (code, where, data) in files.items():
    open(os.path.join(here, name + '.stz'), 'wb').write(data)
    open(os.path.join(here, name + '.expect'), 'w').write(code + '\n' + where + '\n')
