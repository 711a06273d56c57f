"""stepzip: lossless compression of unit-step chains by reverse interpolation.

Chain files (freeman text, point lists, binary STEP/DIR logs) in any
bytes-like object go to `.stz` frames and back with :func:`compress` and
:func:`decompress`, or piece by piece with :class:`Compressor` and
:class:`Decompressor`. Step arrays are either packed STEP/DIR words (1-D,
uint16: bit 2i = axis i moved, bit 2i+1 = in the negative direction) or
moves, an ``(n, axes)`` integer array of -1/0/+1 per axis and step;
:func:`segment` takes both, :func:`to_moves` and :func:`from_moves` convert.

Defaults follow the command line (``stepzip compress``: level 3, profile
``"auto"``; ``stepzip segment``: profile ``"auto"``, greedy cut). Every call
that can take long releases the GIL. Errors raise :class:`Error` (a
ValueError) with ``.code`` (the library's error code) and a one-line message
that names the place (line and column, byte offset, step or row index) and
never repeats the data.
"""
from __future__ import annotations

import decimal
import math
import numbers
import threading
from typing import Any, BinaryIO, List, NamedTuple, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _stepzip
from ._stepzip import FORMAT_VERSION, MAX_AXES, PROFILES, TIMED_MOVE_TOLERANCE, Error

__version__: str = _stepzip.__version__

__all__ = [
    "Error", "FORMAT_VERSION", "MAX_AXES", "PROFILES", "TIMED_MOVE_TOLERANCE", "SEGMENTERS", "Segmentation",
    "compress", "decompress", "Compressor", "Decompressor", "segment", "expand",
    "interpolate", "freeman_to_steps", "steps_to_freeman", "to_moves", "from_moves",
    "to_steps_file", "from_steps_file", "StreamingSegmenter", "TimedAxis", "TimedMove", "TimedChain",
    "timed_moves",
]

SEGMENTERS: Tuple[str, ...] = ("greedy", "optimal", "patent")

Steps = npt.NDArray[np.uint16]   # packed STEP/DIR words
Moves = npt.NDArray[np.int8]     # (n, axes) of -1/0/+1
Ints = npt.NDArray[np.int64]     # segment totals and phases

# Errc values (include/stepzip/error.hpp) used for argument errors.
_INVALID_ARGUMENT = 10


def _error(message: str, code: int = _INVALID_ARGUMENT) -> Error:
    err = Error(message)
    err.code = code
    return err


def _str(name: str, value: Any) -> str:
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a str, not {type(value).__name__}")
    return value


def _opt_str(name: str, value: Any) -> Optional[str]:
    return None if value is None else _str(name, value)


def _int(name: str, value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name} must be an int, not {type(value).__name__}")
    return int(value)


def _text(name: str, value: Any) -> str:
    """str as it is; a bytes-like object read as Latin-1 (every byte one character)."""
    if isinstance(value, str):
        return value
    try:
        return memoryview(value).tobytes().decode("latin-1")
    except TypeError:
        raise TypeError(f"{name} must be a str or a bytes-like object, "
                        f"not {type(value).__name__}") from None


def _integer_array(name: str, value: Any) -> npt.NDArray[Any]:
    arr = np.asarray(value)
    if arr.size == 0:
        return arr.astype(np.int64)
    if arr.dtype.kind not in "iub":
        raise TypeError(f"{name} must hold integers, not {arr.dtype}")
    return arr


def _packed(steps: Any, axes: Optional[int]) -> Tuple[Steps, int]:
    """Packed uint16 steps and the axis count from packed steps or moves."""
    arr = _integer_array("steps", steps)
    if arr.ndim == 2:
        if axes is not None and axes != arr.shape[1]:
            raise _error(f"axes={axes} but the moves have {arr.shape[1]} columns")
        return from_moves(arr), int(arr.shape[1])
    if arr.ndim != 1:
        raise _error("steps must be packed words (1-D) or moves of shape (n, axes)")
    if arr.size and (int(arr.min()) < 0 or int(arr.max()) > 0xFFFF):
        raise _error("packed steps must be 0..65535 (use an (n, axes) array for moves)")
    return arr.astype(np.uint16, copy=False), 2 if axes is None else _int("axes", axes)


# ------------------------------------------------------------------ frames

def compress(data: Any, *, profile: str = "auto", segmenter: Optional[str] = None,
             level: int = 3, format: Optional[str] = None, source: str = "<input>",
             threads: int = 1) -> bytes:
    """Compresses a chain file (freeman, points or steps; any bytes-like object)
    into one .stz frame, as `stepzip compress`: every block's round trip is
    proved first. ``format`` None detects it; ``threads`` 0 uses every core
    (the output does not depend on it)."""
    return _stepzip.compress(data, _str("profile", profile), _opt_str("segmenter", segmenter),
                             _int("level", level), _opt_str("format", format),
                             _str("source", source), _int("threads", threads))


def decompress(frame: Any) -> bytes:
    """Decodes .stz frames (any bytes-like object) to the original bytes; the
    content checksum is verified."""
    return _stepzip.decompress(frame)


class _Stream:
    """A stream handle of the C API fed piece by piece; calls are serialized,
    so an object may be shared between threads."""

    def __init__(self, stream: Union[_stepzip.CStream, _stepzip.DStream]) -> None:
        self._stream = stream
        self._lock = threading.Lock()

    def _feed(self, data: Any) -> bytes:
        with self._lock:
            return self._stream.feed(data, False)

    def flush(self) -> bytes:
        with self._lock:
            return self._stream.feed(b"", True)

    def copy_stream(self, ifh: BinaryIO, ofh: BinaryIO, read_size: int = 1 << 20) -> Tuple[int, int]:
        """Reads ``ifh`` to its end and writes the output to ``ofh``; returns
        (bytes read, bytes written)."""
        read = written = 0
        while True:
            chunk = ifh.read(_int("read_size", read_size))
            if not chunk:
                break
            read += len(chunk)
            out = self._feed(chunk)
            written += len(out)
            ofh.write(out)
        out = self.flush()
        written += len(out)
        ofh.write(out)
        return read, written


class Compressor(_Stream):
    """Compresses piece by piece, as python-zstandard's compressobj():
    ``compress(data)`` returns the frame bytes ready so far, ``flush()`` ends
    the frame and returns the rest; ``copy_stream(ifh, ofh)`` does both for a
    file. After flush() the next compress() starts a new frame. Memory stays
    bounded by the block size."""

    def __init__(self, *, level: int = 3, profile: str = "auto",
                 segmenter: Optional[str] = None, format: Optional[str] = None,
                 source: str = "<input>") -> None:
        super().__init__(_stepzip.CStream(_str("profile", profile),
                                          _opt_str("segmenter", segmenter), _int("level", level),
                                          _opt_str("format", format), _str("source", source)))

    def compress(self, data: Any) -> bytes:
        return self._feed(data)


class Decompressor(_Stream):
    """Decompresses piece by piece: ``decompress(data)`` returns the original
    bytes ready so far, ``flush()`` says the input is complete and returns
    the rest (bytes after a frame, or a frame cut short, raise Error there);
    ``copy_stream(ifh, ofh)`` does both for a file. After an error or flush()
    the object takes a new input."""

    def __init__(self) -> None:
        super().__init__(_stepzip.DStream())

    def decompress(self, data: Any) -> bytes:
        return self._feed(data)


# ---------------------------------------------------- reverse interpolation

class Segmentation(NamedTuple):
    """Segments of one chain: ``deltas`` (n, axes) int64 totals, ``phases``
    (n, phase_count) int64 initial values of the evaluation functions, and the
    ``profile`` they were cut under. Unpacks as ``deltas, phases, profile``."""
    deltas: Ints
    phases: Ints
    profile: str


def segment(steps: Any, profile: str = "auto", *, axes: Optional[int] = None,
            segmenter: str = "greedy") -> Segmentation:
    """Reverse interpolation of one chain: packed steps (1-D) or moves
    ((n, axes) of -1/0/+1) -> exact segments. ``profile`` "auto" (the
    default, as `stepzip segment`) keeps the profile with the fewest
    segments; ``axes`` defaults to 2 for packed steps and to the column count
    of moves."""
    packed, n_axes = _packed(steps, axes)
    deltas, phases, chosen = _stepzip.segment(packed, _str("profile", profile), n_axes,
                                              _str("segmenter", segmenter))
    return Segmentation(deltas, phases, chosen)


def expand(deltas: Any, phases: Any = None, profile: Optional[str] = None, *,
           axes: Optional[int] = None, moves: bool = False) -> npt.NDArray[Any]:
    """Forward interpolation: segments -> the steps they stand for, packed
    (uint16) or, with ``moves=True``, as an (n, axes) int8 array. Takes a
    Segmentation, or deltas, phases and the profile they were cut under."""
    if isinstance(deltas, Segmentation):
        seg = deltas
        deltas, phases = seg.deltas, seg.phases
        profile = seg.profile if profile is None else profile
    if phases is None or profile is None:
        raise TypeError("expand() takes a Segmentation, or deltas, phases and the profile")
    d = _integer_array("deltas", deltas).astype(np.int64, copy=False)
    p = _integer_array("phases", phases).astype(np.int64, copy=False)
    if d.ndim == 1 and d.size == 0:
        d = d.reshape(0, 2 if axes is None else axes)
    n_axes = int(d.shape[1]) if axes is None and d.ndim == 2 else (2 if axes is None else axes)
    if p.ndim == 1 and p.size == 0:
        p = p.reshape(0, 0)
    out = _stepzip.expand(d, p, _str("profile", profile), _int("axes", n_axes))
    if moves:
        return to_moves(out, n_axes)
    return out


def interpolate(text: Any, profile: str, *, format: Optional[str] = None,
                step_size: Union[None, str, int, float, decimal.Decimal] = None,
                moves: bool = False) -> List[Tuple[Tuple[int, int], npt.NDArray[Any]]]:
    """Vectors (G-code or HP-GL, as str or bytes) -> one chain per pen-down
    path, [((x0, y0), steps)], as `stepzip interpolate --profile P`.
    ``step_size`` (millimetres per step) is exact: give a str or Decimal, or
    an int or float (a float is read as its shortest decimal form, 0.1 is
    "0.1")."""
    chains = _stepzip.interpolate(_text("text", text), _str("profile", profile),
                                  _opt_str("format", format), _step_size(step_size))
    if moves:
        return [(start, to_moves(steps, 2)) for start, steps in chains]
    return chains


def _step_size(value: Any) -> Optional[str]:
    if value is None or isinstance(value, str):
        return value
    if isinstance(value, bool):
        raise TypeError("step_size must be a number or a str, not bool")
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, float):
        value = decimal.Decimal(repr(value))
    if isinstance(value, decimal.Decimal):
        if not value.is_finite():
            raise _error("step_size must be a finite number")
        return format(value, "f")
    raise TypeError(f"step_size must be a number or a str, not {type(value).__name__}")


def freeman_to_steps(codes: str, *, moves: bool = False) -> npt.NDArray[Any]:
    """Freeman-8 digits -> two-axis steps, packed or (with moves=True) (n, 2)."""
    steps = _stepzip.freeman_to_steps(_str("codes", codes))
    if moves:
        return to_moves(steps, 2)
    return steps


def steps_to_freeman(steps: Any) -> str:
    """Two-axis steps (packed, or moves of shape (n, 2)) -> Freeman-8 digits."""
    packed, _ = _packed(steps, None)
    return _stepzip.steps_to_freeman(packed)


def to_moves(steps: Any, axes: int = 2) -> Moves:
    """Packed steps -> an (n, axes) int8 array of -1/0/+1."""
    packed, n_axes = _packed(steps, axes)
    return _stepzip.steps_to_moves(packed, n_axes)


def from_moves(moves: Any) -> Steps:
    """An (n, axes) array of -1/0/+1 (every row moving at least one axis) ->
    packed uint16 steps."""
    arr = _integer_array("moves", moves)
    if arr.ndim != 2:
        raise _error("moves must have shape (n, axes)")
    if arr.size and (int(arr.min()) < -1 or int(arr.max()) > 1):
        bad = int(np.argmax((arr < -1) | (arr > 1)) // arr.shape[1])
        raise _error(f"moves row {bad}: a step moves each axis by -1, 0 or +1")
    return _stepzip.moves_to_steps(arr.astype(np.int8, copy=False))


class TimedMove(NamedTuple):
    """A move read out of a timed log: its step totals per axis, the ticks of
    its first and last step, its length, and its speeds along the path in
    steps/s (entry, cruise, exit) with the ramps' acceleration in steps/s^2
    (0 when neither ramp has 6 steps) and the leading-axis steps it was
    fitted on, as `stepzip segment --format timed --to json` gives them
    (docs/cli.md)."""
    delta: Tuple[int, ...]
    ticks: Tuple[int, int]
    length: float
    entry: float
    cruise: float
    exit: float
    acceleration: float
    ramp_steps: int


class TimedAxis(NamedTuple):
    """What one axis of a timed log says about the controller: its steps,
    its fastest step rate (steps/s) and its ramps' acceleration (steps/s^2,
    0 when no window of its steps fitted), read from ``windows`` windows of
    its steps (``estimate_axis_motion`` of include/stepzip/timed.hpp)."""
    steps: int
    max_rate: float
    acceleration: float
    windows: int


class TimedChain(NamedTuple):
    """One chain of a timed log: its path's start (per axis), its step
    count, what each axis says (TimedAxis) and its moves."""
    start: Tuple[int, ...]
    steps: int
    axes: List[TimedAxis]
    moves: List[TimedMove]


def timed_moves(log: Any, tick_us: float, *,
                tolerance: Optional[float] = None) -> List[TimedChain]:
    """A controller's moves read out of a timed STEP/DIR log (any bytes-like
    object, one byte per tick, idle ticks included; docs/formats.md
    "timed"), ``tick_us`` microseconds a tick: per chain, each axis's
    fastest rate and acceleration, and the moves, straight within
    ``tolerance`` steps (default TIMED_MOVE_TOLERANCE, 1.5), with their
    entry, cruise and exit speeds and acceleration, as `stepzip segment LOG
    --format timed --tick-us US --to json`."""
    tick = float(tick_us)
    if not (math.isfinite(tick) and tick > 0):
        raise _error(f"tick_us must be a positive number of microseconds, not {tick_us!r}")
    tol = TIMED_MOVE_TOLERANCE if tolerance is None else float(tolerance)
    if not (math.isfinite(tol) and tol > 0):
        raise _error(f"tolerance must be a positive number of steps, not {tolerance!r}")
    return [TimedChain(start, steps, [TimedAxis(*a) for a in axes], [TimedMove(*m) for m in moves])
            for start, steps, axes, moves in _stepzip.timed_moves(log, tick, tol)]


def to_steps_file(steps: Any, axes: Optional[int] = None) -> bytes:
    """Steps (packed, or moves of shape (n, axes)) as a `steps` chain file:
    one STEP/DIR byte per step, up to 4 axes (docs/formats.md). Compress it
    with ``compress(data, format="steps")``."""
    packed, n_axes = _packed(steps, axes)
    if n_axes > 4:
        raise _error(f"a steps file holds up to 4 axes, not {n_axes}")
    return packed.astype(np.uint8).tobytes()


def from_steps_file(data: Any, *, moves: bool = False,
                    axes: Optional[int] = None) -> npt.NDArray[Any]:
    """The steps of a `steps` chain file (any bytes-like object): packed, or
    with ``moves=True`` an (n, axes) array, ``axes`` defaulting to
    max(2, highest axis that steps + 1). Idle ticks and DIR bits of resting
    axes (the file's layout, docs/formats.md) are not steps and are left out."""
    ticks = np.frombuffer(memoryview(data).cast("B"), dtype=np.uint8)
    step_bits = ticks & 0x55
    ticks = ticks[step_bits != 0]
    step_bits = step_bits[step_bits != 0]
    packed = (step_bits | (((ticks >> 1) & step_bits) << 1)).astype(np.uint16)
    if not moves:
        return packed
    if axes is None:
        seen = int(np.bitwise_or.reduce(step_bits)) if step_bits.size else 0
        axes = max(2, max((a + 1 for a in range(4) if seen >> (2 * a) & 1), default=0))
    return to_moves(packed, axes)


class StreamingSegmenter:
    """Online greedy reverse interpolation of one chain at a time: push steps
    (packed or moves) as they arrive, receive each segment when it is final;
    at most ``max_held`` steps wait. ``finish()`` ends the chain."""

    def __init__(self, profile: str = "eval8", axes: int = 2,
                 max_held: int = _stepzip.DEFAULT_MAX_HELD) -> None:
        self._seg = _stepzip.StreamingSegmenter(_str("profile", profile), _int("axes", axes),
                                                _int("max_held", max_held))
        self._axes = axes

    def push(self, steps: Any) -> Tuple[Ints, Ints]:
        """Pushes steps; returns the (deltas, phases) that became final."""
        packed, _ = _packed(steps, self._axes)
        return self._seg.push(packed)

    def push_step(self, step: int) -> Tuple[Ints, Ints]:
        """Pushes one packed step."""
        return self._seg.push_step(_int("step", step))

    def finish(self) -> Tuple[Ints, Ints]:
        """Ends the chain: returns the remaining segments and resets."""
        return self._seg.finish()

    @property
    def held(self) -> int:
        return self._seg.held

    @property
    def max_held(self) -> int:
        return self._seg.max_held

    @property
    def pushed(self) -> int:
        return self._seg.pushed

    @property
    def forced_cuts(self) -> int:
        return self._seg.forced_cuts
