/*
 * stepzip.h — the C interface of stepzip: lossless compression of unit-step
 * chains by reverse interpolation, and the reverse interpolation itself.
 *
 * Conventions (as in libdeflate):
 *  - Objects are opaque handles made by stepzip_alloc_*() and released by the
 *    matching stepzip_free_*(); freeing NULL does nothing.
 *  - Every fallible call returns an enum stepzip_result; STEPZIP_OK is 0.
 *    Its values are fixed and equal the C++ stepzip::Errc values; the
 *    C-only results start at 80. No C++ exception crosses this interface:
 *    a failed allocation is STEPZIP_NO_MEMORY, anything unexpected
 *    STEPZIP_INTERNAL.
 *  - Output goes to caller buffers with the capacity given; when it does not
 *    fit, the call returns STEPZIP_SHORT_BUFFER and stores the size needed,
 *    so the caller can grow the buffer and call again.
 *  - After a failure, stepzip_*_error() on the same object returns one line
 *    naming the problem (and, for input errors, the line and column or byte
 *    offset). The text stays valid until the next call on that object.
 *
 * Thread safety: a handle is used by one thread at a time; distinct handles
 * share nothing, so several threads may each use their own. The free
 * functions without a handle (stepzip_version_string, stepzip_result_name,
 * stepzip_profile_from_name, stepzip_profile_name, stepzip_segment_steps,
 * stepzip_expand_segments) are thread-safe.
 *
 * What is not promised: the compressed bytes may change between versions of
 * the library (only the round trip is guaranteed, and every version decodes
 * the frames older versions wrote, see docs/FORMAT.md); the cut of a chain
 * into segments may change too, except that it always expands back to the
 * exact steps.
 */
#ifndef STEPZIP_H
#define STEPZIP_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(_WIN32) && defined(STEPZIP_SHARED)
#  ifdef STEPZIP_BUILDING
#    define STEPZIP_API __declspec(dllexport)
#  else
#    define STEPZIP_API __declspec(dllimport)
#  endif
#elif defined(__GNUC__)
#  define STEPZIP_API __attribute__((visibility("default")))
#else
#  define STEPZIP_API
#endif

/* Library version, as in the C++ stepzip::version_string(). */
#define STEPZIP_VERSION_MAJOR 0
#define STEPZIP_VERSION_MINOR 1
#define STEPZIP_VERSION_PATCH 0
#define STEPZIP_VERSION_STRING "0.1.0"

/* Largest number of axes of a chain; a segment has as many totals. */
#define STEPZIP_MAX_AXES 6

/* Result codes (the C++ stepzip::Errc values, plus C-only ones from 80). */
enum stepzip_result {
    STEPZIP_OK = 0,
    STEPZIP_INVALID_ARGUMENT = 10, /* the caller asked for something undefined */
    STEPZIP_UNSUPPORTED = 11,      /* a valid request this build or format cannot do */
    STEPZIP_SYNTAX = 20,           /* input text that cannot be read */
    STEPZIP_NOT_A_STEP = 21,       /* consecutive points more than one step apart */
    STEPZIP_CONNECTIVITY = 22,     /* a diagonal step under a 4-connected profile */
    STEPZIP_BAD_MAGIC = 30,        /* not a .stz frame */
    STEPZIP_BAD_VERSION = 31,      /* a .stz format version this library cannot read */
    STEPZIP_CORRUPT = 32,
    STEPZIP_TRUNCATED = 33,
    STEPZIP_RESERVED_BITS = 34,
    STEPZIP_CHECKSUM = 40,         /* decoded data differ from what was compressed */
    STEPZIP_LIMIT = 50,            /* beyond a documented limit */
    STEPZIP_OVERFLOW = 51,
    STEPZIP_IO = 60,
    STEPZIP_MISMATCH = 70,         /* a round-trip proof failed (internal error) */
    STEPZIP_NO_MEMORY = 80,        /* allocation failed */
    STEPZIP_SHORT_BUFFER = 81,     /* the output does not fit; the size needed is stored */
    STEPZIP_INTERNAL = 99          /* an unexpected failure inside the library */
};

/* A short fixed name for a result ("ok", "syntax", "short_buffer", ...);
 * "unknown" for a value not listed above. Never NULL. Thread-safe. */
STEPZIP_API const char *stepzip_result_name(enum stepzip_result result);

/* The library version ("0.1.0"); may differ from STEPZIP_VERSION_STRING
 * when the program was built against other headers. Thread-safe. */
STEPZIP_API const char *stepzip_version_string(void);

/* Profiles (forward interpolator + default phase; the values are stored in
 * .stz files). STEPZIP_PROFILE_AUTO lets the compressor choose. */
enum stepzip_profile {
    STEPZIP_PROFILE_AUTO = -1,
    STEPZIP_PROFILE_EVAL4 = 0,  /* evaluation function, 4-connected */
    STEPZIP_PROFILE_EVAL8 = 1,  /* leading-axis method, 8-connected */
    STEPZIP_PROFILE_PATENT = 2, /* SU 1089551 forward mode, 4-connected */
    STEPZIP_PROFILE_GRBL = 3,   /* leading-axis method at GRBL's phase */
    STEPZIP_PROFILE_MARLIN = 4  /* leading-axis method at Marlin's phase */
};

/* How a chain is cut into segments. DEFAULT: implied by the level. */
enum stepzip_segmenter_kind {
    STEPZIP_SEGMENTER_DEFAULT = -1,
    STEPZIP_SEGMENTER_GREEDY = 0,  /* longest exact segment at each point */
    STEPZIP_SEGMENTER_OPTIMAL = 1, /* fewest exact segments */
    STEPZIP_SEGMENTER_PATENT = 2   /* SU 1089551 approximation mode, made exact */
};

/* Chain file formats (the input of the compressor). AUTO: detected. */
enum stepzip_format {
    STEPZIP_FORMAT_AUTO = -1,
    STEPZIP_FORMAT_FREEMAN = 0, /* "X0 Y0 CODES" per line */
    STEPZIP_FORMAT_POINTS = 1,  /* "x y" per line, blank line between chains */
    STEPZIP_FORMAT_STEPS = 2    /* binary STEP/DIR log, one byte per tick */
};

/* ---------------------------------------------------------------- steps */

/* A step is one tick's unit increment, packed as in the STEP/DIR log:
 * bit 2i set = axis i moved, bit 2i+1 set = it moved in the negative
 * direction. Freeman-8 code c on two axes is stepzip_freeman_step(c). */
typedef uint16_t stepzip_step;

/* The two-axis step of Freeman-8 code `code` (0..7: +x, +x+y, +y, -x+y, -x,
 * -x-y, -y, +x-y); 0 (not a valid step) for another value. Thread-safe. */
STEPZIP_API stepzip_step stepzip_freeman_step(int code);

/* One segment: per-axis totals and the initial values of its evaluation
 * functions (the phase; see include/stepzip/segment.hpp). Totals past the
 * chain's axis count and phases past the profile's count are zero. */
struct stepzip_segment {
    int64_t delta[STEPZIP_MAX_AXES];
    int64_t phase[STEPZIP_MAX_AXES - 1];
};

/* --------------------------------------------------------- compression */

struct stepzip_compressor;

/* A compressor at `level` (1 fastest .. 19 smallest, as in zstd; 3 is the
 * command line's default) with the given profile and segmenter. Returns
 * NULL when out of memory or for a level, profile or segmenter outside the
 * values above. The object holds only settings and the last error. */
STEPZIP_API struct stepzip_compressor *
stepzip_alloc_compressor(int level, enum stepzip_profile profile,
                         enum stepzip_segmenter_kind segmenter);

/* Names the input in error messages (default "<input>"); `name` is copied.
 * Errors: STEPZIP_INVALID_ARGUMENT for NULL. */
STEPZIP_API enum stepzip_result
stepzip_compressor_set_source(struct stepzip_compressor *c, const char *name);

/* Compresses a whole chain file of `in_nbytes` bytes in format `format`
 * into one .stz frame in `out`. Every block is decoded again and compared
 * with the input before it is written (the round-trip proof).
 * On STEPZIP_OK, *out_nbytes is the frame size. On STEPZIP_SHORT_BUFFER,
 * *out_nbytes is the capacity needed and `out` holds nothing useful.
 * Errors: STEPZIP_SYNTAX / NOT_A_STEP / LIMIT / OVERFLOW for bad input (the
 * message names line and column or byte offset), STEPZIP_UNSUPPORTED when
 * the format cannot be detected, STEPZIP_CONNECTIVITY / INVALID_ARGUMENT
 * when a named profile cannot represent the chains, STEPZIP_MISMATCH if a
 * round-trip proof fails, STEPZIP_NO_MEMORY, STEPZIP_INVALID_ARGUMENT for
 * NULL pointers (`in` may be NULL when in_nbytes is 0).
 * Cost: the work of compressing; a STEPZIP_SHORT_BUFFER call does it all,
 * so size the buffer generously (stepzip_compress_bound is a good start). */
STEPZIP_API enum stepzip_result
stepzip_compress(struct stepzip_compressor *c, enum stepzip_format format,
                 const void *in, size_t in_nbytes, void *out, size_t out_nbytes_avail,
                 size_t *out_nbytes);

/* A capacity that holds the frame of most inputs of `in_nbytes` bytes
 * (the frame may carry a block as zstd of its bytes, so its size is close
 * to zstd's bound plus headers). Not a guarantee: a call may still return
 * STEPZIP_SHORT_BUFFER with the exact size needed. Thread-safe. */
STEPZIP_API size_t stepzip_compress_bound(size_t in_nbytes);

/* The profile named `name` ("eval4", "eval8", "patent", "grbl", "marlin",
 * or "auto" for STEPZIP_PROFILE_AUTO), as the command line's --profile
 * takes them, stored in *profile. Errors: STEPZIP_INVALID_ARGUMENT for an
 * unknown name or NULL pointers (*profile unchanged). Thread-safe. */
STEPZIP_API enum stepzip_result stepzip_profile_from_name(const char *name,
                                                          enum stepzip_profile *profile);

/* The name of `profile` ("auto" for STEPZIP_PROFILE_AUTO); "unknown" for a
 * value outside the enum. Never NULL. Thread-safe. */
STEPZIP_API const char *stepzip_profile_name(enum stepzip_profile profile);

/* The last error of `c` as one line; "" when the last call succeeded. */
STEPZIP_API const char *stepzip_compressor_error(const struct stepzip_compressor *c);

STEPZIP_API void stepzip_free_compressor(struct stepzip_compressor *c);

/* ------------------------------------------------------- decompression */

struct stepzip_decompressor;

/* A decompressor; NULL when out of memory. */
STEPZIP_API struct stepzip_decompressor *stepzip_alloc_decompressor(void);

/* What a frame holds (see stepzip::FrameInfo). */
struct stepzip_frame_info {
    int format_version;
    enum stepzip_profile profile;
    enum stepzip_format format;
    int axes;
    uint64_t chains, steps, segments;
    uint64_t decoded_bytes;    /* size of the original input */
    uint64_t compressed_bytes; /* size of the frame */
};

/* Reads the structure of the .stz frame in `in` (block checksums checked,
 * nothing decoded into the caller's memory) into *info, so the caller can
 * size the output buffer from info->decoded_bytes.
 * Errors: STEPZIP_BAD_MAGIC, BAD_VERSION, RESERVED_BITS, TRUNCATED,
 * CORRUPT, LIMIT, CHECKSUM (message names the byte offset),
 * STEPZIP_INVALID_ARGUMENT for NULL pointers. */
STEPZIP_API enum stepzip_result
stepzip_inspect(struct stepzip_decompressor *d, const void *in, size_t in_nbytes,
                struct stepzip_frame_info *info);

/* Decodes the .stz frame in `in` into `out` and checks its XXH64.
 * On STEPZIP_OK, *out_nbytes is the size of the original bytes. On
 * STEPZIP_SHORT_BUFFER, *out_nbytes is the capacity needed. On any error
 * the contents of `out` are unspecified.
 * Errors: as stepzip_inspect(), and STEPZIP_CHECKSUM when the decoded
 * bytes differ from what was compressed. Never reports success for bytes
 * that differ from the original (up to XXH64 collisions). */
STEPZIP_API enum stepzip_result
stepzip_decompress(struct stepzip_decompressor *d, const void *in, size_t in_nbytes,
                   void *out, size_t out_nbytes_avail, size_t *out_nbytes);

STEPZIP_API const char *stepzip_decompressor_error(const struct stepzip_decompressor *d);

STEPZIP_API void stepzip_free_decompressor(struct stepzip_decompressor *d);

/* ------------------------------------------------ reverse interpolation */

/* Cuts `nsteps` steps of an `axes`-axis chain into exact segments under
 * `profile` (not AUTO) with `segmenter` (DEFAULT means greedy), storing
 * them in `out`: expanding them in order with stepzip_expand_segments()
 * gives exactly the steps. *nsegments receives the count; on
 * STEPZIP_SHORT_BUFFER it is the capacity needed (at most nsteps always
 * suffices). Errors: STEPZIP_INVALID_ARGUMENT (axes, profile, an invalid
 * step), STEPZIP_CONNECTIVITY (a diagonal step under eval4 / patent),
 * STEPZIP_UNSUPPORTED (the patent segmenter on more than two axes), NULL
 * pointers. Thread-safe (no handle); the error text is not kept, use the
 * streaming segmenter to get messages. */
STEPZIP_API enum stepzip_result
stepzip_segment_steps(enum stepzip_profile profile, enum stepzip_segmenter_kind segmenter, int axes,
                      const stepzip_step *steps, size_t nsteps,
                      struct stepzip_segment *out, size_t out_capacity, size_t *nsegments);

/* Forward interpolation: the steps of `nsegments` segments under `profile`
 * on `axes` axes, into `out`; *nsteps receives the count, or on
 * STEPZIP_SHORT_BUFFER the capacity needed. Errors:
 * STEPZIP_INVALID_ARGUMENT / STEPZIP_LIMIT for a segment that does not pass
 * the profile's checks (totals, phase range, axes), NULL pointers.
 * Thread-safe. */
STEPZIP_API enum stepzip_result
stepzip_expand_segments(enum stepzip_profile profile, int axes,
                        const struct stepzip_segment *segments, size_t nsegments,
                        stepzip_step *out, size_t out_capacity, size_t *nsteps);

/* ------------------------------------- streaming reverse interpolation */

/* The online greedy segmenter of include/stepzip/streaming.hpp: steps are
 * pushed as they arrive (a digitizer, a step log being written) and each
 * segment becomes readable as soon as it is final. At most `max_held` steps
 * are held back after any push (0 means the default, 65536): when that many
 * wait, the longest exact prefix is forced out. Without a forced cut the
 * segments equal stepzip_segment_steps(..., STEPZIP_SEGMENTER_GREEDY, ...).
 * One chain at a time; stepzip_segmenter_finish() ends it. */
struct stepzip_segmenter;

/* NULL when out of memory, or for a profile that is AUTO or unknown, or an
 * axis count the profile does not take. */
STEPZIP_API struct stepzip_segmenter *
stepzip_alloc_segmenter(enum stepzip_profile profile, int axes, size_t max_held);

/* Pushes `nsteps` steps. Final segments are queued inside the object until
 * read with stepzip_segmenter_read(). Errors: STEPZIP_INVALID_ARGUMENT (an
 * invalid step; the steps before it were taken) and STEPZIP_CONNECTIVITY,
 * with a message naming the step's 1-based index in the chain. */
STEPZIP_API enum stepzip_result
stepzip_segmenter_push(struct stepzip_segmenter *s, const stepzip_step *steps, size_t nsteps);

/* Ends the chain: every held step is queued in segments; the object is
 * then ready for the next chain (queued segments stay until read). */
STEPZIP_API enum stepzip_result stepzip_segmenter_finish(struct stepzip_segmenter *s);

/* Moves up to `capacity` queued segments, oldest first, into `out` and
 * returns how many were moved (0 when none is queued). */
STEPZIP_API size_t stepzip_segmenter_read(struct stepzip_segmenter *s,
                                          struct stepzip_segment *out, size_t capacity);

/* Segments queued and not yet read. */
STEPZIP_API size_t stepzip_segmenter_queued(const struct stepzip_segmenter *s);

/* Steps pushed into the current chain and not yet in a queued segment;
 * never more than the bound after a push returns. */
STEPZIP_API size_t stepzip_segmenter_held(const struct stepzip_segmenter *s);

STEPZIP_API const char *stepzip_segmenter_error(const struct stepzip_segmenter *s);

STEPZIP_API void stepzip_free_segmenter(struct stepzip_segmenter *s);

/* ------------------------------------------- streaming (de)compression */
/* Frames compressed and decompressed through caller buffers of any size, as
 * with ZSTD_CStream / ZSTD_DStream: memory stays bounded by the block size
 * (not the input size), and no bound on the output size is needed, since
 * output is handed over as the caller's buffer has room for it.
 *
 * Each call takes what it can of `in` (advancing in->pos) and writes what it
 * has into `out` (advancing out->pos). `end` says whether `in` holds the
 * last bytes of the input. The frame is complete, and every output byte
 * delivered, when a call with STEPZIP_END returns STEPZIP_OK and stores 0 in
 * *remaining; until then, call again (with the same or more input, and room
 * in `out`). *remaining is otherwise a nonzero hint: the output bytes ready
 * to be delivered, or 1 when the coder needs more input or time.
 * After a frame completes, the next call starts the next frame with the same
 * settings. After an error, the handle repeats the error until
 * stepzip_*stream_reset(). Bytes already delivered before an error are part
 * of an incomplete output: discard them.
 *
 * The coder runs on one helper thread per handle, started by the first call
 * and ended by the frame's end, a reset or the free; it reads the caller's
 * input only while a call is running. Handles are used by one thread at a
 * time, as every handle here. */
struct stepzip_in_buffer {
    const void *src; /* the input */
    size_t size;     /* its size */
    size_t pos;      /* bytes already taken; advanced by the call */
};
struct stepzip_out_buffer {
    void *dst;   /* room for output */
    size_t size; /* its size */
    size_t pos;  /* bytes already written; advanced by the call */
};
enum stepzip_end_directive {
    STEPZIP_CONTINUE = 0, /* more input follows */
    STEPZIP_END = 1       /* `in` ends the input: finish the frame */
};

struct stepzip_cstream;
/* A compression stream with the settings of `settings` (level, profile,
 * segmenter, source name; copied, so `settings` may be freed) for chain
 * files of format `format` (AUTO: detected from the first bytes). NULL when
 * out of memory or for a NULL `settings` or an unknown format. */
STEPZIP_API struct stepzip_cstream *
stepzip_alloc_cstream(const struct stepzip_compressor *settings, enum stepzip_format format);
/* Compresses: see above. Errors: as stepzip_compress() (never
 * STEPZIP_SHORT_BUFFER), and STEPZIP_INVALID_ARGUMENT for NULL pointers or
 * a buffer position past its size. */
STEPZIP_API enum stepzip_result
stepzip_compress_stream(struct stepzip_cstream *cs, struct stepzip_out_buffer *out,
                        struct stepzip_in_buffer *in, enum stepzip_end_directive end,
                        size_t *remaining);
/* Abandons the current frame (if any) and clears an error. */
STEPZIP_API void stepzip_cstream_reset(struct stepzip_cstream *cs);
STEPZIP_API const char *stepzip_cstream_error(const struct stepzip_cstream *cs);
STEPZIP_API void stepzip_free_cstream(struct stepzip_cstream *cs);

struct stepzip_dstream;
/* A decompression stream; NULL when out of memory. */
STEPZIP_API struct stepzip_dstream *stepzip_alloc_dstream(void);
/* Decompresses: see above. The decoder knows that the input is complete
 * only from STEPZIP_END (bytes after a frame are an error, see
 * docs/FORMAT.md), so the last input must come with STEPZIP_END.
 * Errors: as stepzip_decompress() (never STEPZIP_SHORT_BUFFER), and
 * STEPZIP_INVALID_ARGUMENT for NULL pointers or a position past its size. */
STEPZIP_API enum stepzip_result
stepzip_decompress_stream(struct stepzip_dstream *ds, struct stepzip_out_buffer *out,
                          struct stepzip_in_buffer *in, enum stepzip_end_directive end,
                          size_t *remaining);
STEPZIP_API void stepzip_dstream_reset(struct stepzip_dstream *ds);
STEPZIP_API const char *stepzip_dstream_error(const struct stepzip_dstream *ds);
STEPZIP_API void stepzip_free_dstream(struct stepzip_dstream *ds);

#ifdef __cplusplus
}
#endif

#endif /* STEPZIP_H */
