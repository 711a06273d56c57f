/* The C interface (stepzip.h), compiled as C: compression round trip with
 * caller buffers and STEPZIP_SHORT_BUFFER, errors with messages, reverse
 * interpolation and its inverse, the streaming segmenter's bound, profiles
 * by name, and streaming compression and decompression through small
 * caller buffers. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stepzip.h"

static int failures = 0;

#define CHECK(cond)                                                        \
    do {                                                                   \
        if (!(cond)) {                                                     \
            fprintf(stderr, "%s:%d: FAILED: %s\n", __FILE__, __LINE__, #cond); \
            ++failures;                                                    \
        }                                                                  \
    } while (0)

static const char kChains[] =
    "# two chains\n"
    "0 0 0020020020\n"
    "5 -3 00010001000100010001000122223333\n";

static void test_round_trip(void) {
    struct stepzip_compressor *c =
        stepzip_alloc_compressor(3, STEPZIP_PROFILE_AUTO, STEPZIP_SEGMENTER_DEFAULT);
    struct stepzip_decompressor *d = stepzip_alloc_decompressor();
    CHECK(c != NULL && d != NULL);
    size_t in_n = sizeof kChains - 1, need = 0, got = 0;
    char tiny[4];
    /* too small: the size needed comes back */
    CHECK(stepzip_compress(c, STEPZIP_FORMAT_AUTO, kChains, in_n, tiny, sizeof tiny, &need) ==
          STEPZIP_SHORT_BUFFER);
    CHECK(need > sizeof tiny);
    CHECK(strcmp(stepzip_result_name(STEPZIP_SHORT_BUFFER), "short_buffer") == 0);
    char *frame = malloc(need);
    CHECK(stepzip_compress(c, STEPZIP_FORMAT_AUTO, kChains, in_n, frame, need, &got) == STEPZIP_OK);
    CHECK(got == need);
    CHECK(strcmp(stepzip_compressor_error(c), "") == 0);
    CHECK(stepzip_compress_bound(in_n) >= got);

    struct stepzip_frame_info info;
    CHECK(stepzip_inspect(d, frame, got, &info) == STEPZIP_OK);
    CHECK(info.decoded_bytes == in_n);
    CHECK(info.chains == 2);
    CHECK(info.steps == 10 + 32);
    CHECK(info.axes == 2);
    CHECK(info.format == STEPZIP_FORMAT_FREEMAN);

    char *back = malloc(in_n);
    size_t back_n = 0;
    CHECK(stepzip_decompress(d, frame, got, back, 3, &back_n) == STEPZIP_SHORT_BUFFER);
    CHECK(back_n == in_n);
    CHECK(stepzip_decompress(d, frame, got, back, in_n, &back_n) == STEPZIP_OK);
    CHECK(back_n == in_n && memcmp(back, kChains, in_n) == 0);

    /* a flipped byte in the frame is reported, never decoded as success */
    frame[got / 2] ^= 0x40;
    enum stepzip_result r = stepzip_decompress(d, frame, got, back, in_n, &back_n);
    CHECK(r != STEPZIP_OK);
    CHECK(strlen(stepzip_decompressor_error(d)) > 0);
    CHECK(stepzip_decompress(d, "not a frame", 11, back, in_n, &back_n) == STEPZIP_BAD_MAGIC);

    /* bad input names its line and column */
    CHECK(stepzip_compressor_set_source(c, "bad.fc") == STEPZIP_OK);
    r = stepzip_compress(c, STEPZIP_FORMAT_FREEMAN, "0 0 0129\n", 9, frame, need, &got);
    CHECK(r == STEPZIP_SYNTAX);
    CHECK(strstr(stepzip_compressor_error(c), "bad.fc:1:") != NULL);

    /* NULL where a buffer is needed */
    CHECK(stepzip_compress(c, STEPZIP_FORMAT_AUTO, NULL, 5, frame, need, &got) ==
          STEPZIP_INVALID_ARGUMENT);
    CHECK(stepzip_alloc_compressor(0, STEPZIP_PROFILE_EVAL8, STEPZIP_SEGMENTER_GREEDY) == NULL);
    CHECK(stepzip_alloc_compressor(3, (enum stepzip_profile)9, STEPZIP_SEGMENTER_GREEDY) == NULL);
    free(back);
    free(frame);
    stepzip_free_compressor(c);
    stepzip_free_decompressor(d);
    stepzip_free_compressor(NULL);
    stepzip_free_decompressor(NULL);
}

/* Freeman digits to steps. */
static size_t to_steps(const char *codes, stepzip_step *out) {
    size_t n = 0;
    for (; codes[n]; ++n) out[n] = stepzip_freeman_step(codes[n] - '0');
    return n;
}

static void test_segment_and_expand(void) {
    stepzip_step steps[64], back[64];
    /* SPEC: forward of (7, 3) under patent is 0020020020; it is one segment */
    size_t n = to_steps("0020020020", steps), count = 0;
    struct stepzip_segment segs[64];
    CHECK(stepzip_segment_steps(STEPZIP_PROFILE_PATENT, STEPZIP_SEGMENTER_GREEDY, 2, steps, n,
                                segs, 64, &count) == STEPZIP_OK);
    CHECK(count == 1);
    CHECK(segs[0].delta[0] == 7 && segs[0].delta[1] == 3);
    CHECK(segs[0].phase[0] == 3 - 7); /* the patent's default phase Y - X */
    size_t m = 0;
    CHECK(stepzip_expand_segments(STEPZIP_PROFILE_PATENT, 2, segs, count, back, 64, &m) == STEPZIP_OK);
    CHECK(m == n && memcmp(back, steps, n * sizeof *steps) == 0);
    CHECK(stepzip_expand_segments(STEPZIP_PROFILE_PATENT, 2, segs, count, back, 2, &m) ==
          STEPZIP_SHORT_BUFFER);
    CHECK(m == n);

    /* a random-looking chain: optimal never has more segments than greedy,
     * both expand back exactly */
    n = to_steps("0001000100012222322221110007776666555", steps);
    size_t greedy = 0, optimal = 0;
    CHECK(stepzip_segment_steps(STEPZIP_PROFILE_EVAL8, STEPZIP_SEGMENTER_GREEDY, 2, steps, n, segs,
                                64, &greedy) == STEPZIP_OK);
    CHECK(stepzip_expand_segments(STEPZIP_PROFILE_EVAL8, 2, segs, greedy, back, 64, &m) == STEPZIP_OK);
    CHECK(m == n && memcmp(back, steps, n * sizeof *steps) == 0);
    CHECK(stepzip_segment_steps(STEPZIP_PROFILE_EVAL8, STEPZIP_SEGMENTER_OPTIMAL, 2, steps, n, segs,
                                64, &optimal) == STEPZIP_OK);
    CHECK(optimal <= greedy);
    CHECK(stepzip_segment_steps(STEPZIP_PROFILE_EVAL8, STEPZIP_SEGMENTER_GREEDY, 2, steps, n, segs,
                                1, &count) == STEPZIP_SHORT_BUFFER);
    CHECK(count == greedy);

    /* a diagonal step under a 4-connected profile */
    n = to_steps("001", steps);
    CHECK(stepzip_segment_steps(STEPZIP_PROFILE_EVAL4, STEPZIP_SEGMENTER_GREEDY, 2, steps, n, segs,
                                64, &count) == STEPZIP_CONNECTIVITY);
    /* a segment whose phase is out of range */
    segs[0].delta[0] = 5;
    segs[0].delta[1] = 2;
    segs[0].phase[0] = 100;
    CHECK(stepzip_expand_segments(STEPZIP_PROFILE_EVAL8, 2, segs, 1, back, 64, &m) != STEPZIP_OK);
}

static void test_streaming(void) {
    /* a long run and turns, pushed one step at a time with a bound of 8 */
    stepzip_step steps[200];
    size_t n = 0;
    for (int i = 0; i < 50; ++i) steps[n++] = stepzip_freeman_step(i % 3 == 0 ? 1 : 0);
    for (int i = 0; i < 30; ++i) steps[n++] = stepzip_freeman_step(2);
    for (int i = 0; i < 40; ++i) steps[n++] = stepzip_freeman_step(i % 2 ? 4 : 5);
    struct stepzip_segmenter *s = stepzip_alloc_segmenter(STEPZIP_PROFILE_EVAL8, 2, 8);
    CHECK(s != NULL);
    struct stepzip_segment segs[200];
    size_t count = 0;
    for (size_t i = 0; i < n; ++i) {
        CHECK(stepzip_segmenter_push(s, &steps[i], 1) == STEPZIP_OK);
        CHECK(stepzip_segmenter_held(s) <= 8);
        count += stepzip_segmenter_read(s, segs + count, 200 - count);
    }
    CHECK(stepzip_segmenter_finish(s) == STEPZIP_OK);
    CHECK(stepzip_segmenter_held(s) == 0);
    count += stepzip_segmenter_read(s, segs + count, 200 - count);
    CHECK(stepzip_segmenter_queued(s) == 0);
    stepzip_step back[200];
    size_t m = 0;
    CHECK(stepzip_expand_segments(STEPZIP_PROFILE_EVAL8, 2, segs, count, back, 200, &m) == STEPZIP_OK);
    CHECK(m == n && memcmp(back, steps, n * sizeof *steps) == 0);

    /* unbounded: the same segments as the one-shot greedy cut */
    struct stepzip_segmenter *u = stepzip_alloc_segmenter(STEPZIP_PROFILE_EVAL8, 2, 0);
    CHECK(stepzip_segmenter_push(u, steps, n) == STEPZIP_OK);
    CHECK(stepzip_segmenter_finish(u) == STEPZIP_OK);
    size_t streamed = stepzip_segmenter_read(u, segs, 200), batch = 0;
    struct stepzip_segment ref[200];
    CHECK(stepzip_segment_steps(STEPZIP_PROFILE_EVAL8, STEPZIP_SEGMENTER_GREEDY, 2, steps, n, ref,
                                200, &batch) == STEPZIP_OK);
    CHECK(streamed == batch && memcmp(segs, ref, batch * sizeof *ref) == 0);

    /* a bad step is refused with its index */
    stepzip_step bad = 0x10; /* moves axis 2 of a two-axis chain */
    CHECK(stepzip_segmenter_push(u, &bad, 1) == STEPZIP_INVALID_ARGUMENT);
    CHECK(strstr(stepzip_segmenter_error(u), "step 1") != NULL);
    CHECK(stepzip_alloc_segmenter(STEPZIP_PROFILE_EVAL4, 3, 0) == NULL);
    CHECK(stepzip_alloc_segmenter(STEPZIP_PROFILE_AUTO, 2, 0) == NULL);
    stepzip_free_segmenter(s);
    stepzip_free_segmenter(u);
}

static void test_profile_names(void) {
    enum stepzip_profile p = STEPZIP_PROFILE_EVAL8;
    CHECK(stepzip_profile_from_name("grbl", &p) == STEPZIP_OK && p == STEPZIP_PROFILE_GRBL);
    CHECK(stepzip_profile_from_name("auto", &p) == STEPZIP_OK && p == STEPZIP_PROFILE_AUTO);
    CHECK(stepzip_profile_from_name("eval4", &p) == STEPZIP_OK && p == STEPZIP_PROFILE_EVAL4);
    CHECK(stepzip_profile_from_name("bogus", &p) == STEPZIP_INVALID_ARGUMENT);
    CHECK(p == STEPZIP_PROFILE_EVAL4); /* unchanged by the failure */
    CHECK(stepzip_profile_from_name(NULL, &p) == STEPZIP_INVALID_ARGUMENT);
    CHECK(strcmp(stepzip_profile_name(STEPZIP_PROFILE_MARLIN), "marlin") == 0);
    CHECK(strcmp(stepzip_profile_name(STEPZIP_PROFILE_AUTO), "auto") == 0);
    CHECK(strcmp(stepzip_profile_name((enum stepzip_profile)42), "unknown") == 0);
    /* every name maps back to its profile */
    for (int i = STEPZIP_PROFILE_AUTO; i <= STEPZIP_PROFILE_MARLIN; ++i) {
        CHECK(stepzip_profile_from_name(stepzip_profile_name((enum stepzip_profile)i), &p) ==
              STEPZIP_OK);
        CHECK((int)p == i);
    }
}

/* A freeman file of `lines` chains with runs and turns, in a malloc'd buffer. */
static char *make_chains(int lines, size_t *n) {
    char *text = malloc((size_t)lines * 128);
    size_t at = 0;
    for (int i = 0; i < lines; ++i) {
        at += (size_t)sprintf(text + at, "%d %d ", i % 97, -(i % 89));
        for (int k = 0; k < 100; ++k) text[at++] = (char)('0' + ((k / (5 + i % 7) + i) % 8 < 3 ? (i % 8) : ((i + 1) % 8)));
        text[at++] = '\n';
    }
    *n = at;
    return text;
}

/* Appends everything in `out` to `dst` at *dst_n and empties `out`. */
static void drain(struct stepzip_out_buffer *out, char *dst, size_t *dst_n, size_t cap) {
    CHECK(*dst_n + out->pos <= cap);
    if (*dst_n + out->pos <= cap) memcpy(dst + *dst_n, out->dst, out->pos);
    *dst_n += out->pos;
    out->pos = 0;
}

typedef enum stepzip_result (*stream_fn)(void *, struct stepzip_out_buffer *,
                                         struct stepzip_in_buffer *, enum stepzip_end_directive,
                                         size_t *);
static enum stepzip_result cstream_call(void *h, struct stepzip_out_buffer *o,
                                        struct stepzip_in_buffer *i, enum stepzip_end_directive e,
                                        size_t *r) {
    return stepzip_compress_stream((struct stepzip_cstream *)h, o, i, e, r);
}
static enum stepzip_result dstream_call(void *h, struct stepzip_out_buffer *o,
                                        struct stepzip_in_buffer *i, enum stepzip_end_directive e,
                                        size_t *r) {
    return stepzip_decompress_stream((struct stepzip_dstream *)h, o, i, e, r);
}

/* Pushes `src` through a stream in pieces of `piece` bytes with an output
 * buffer of `room` bytes, as a zstd streaming loop does; the output goes to
 * `dst`. Returns the first result that is not STEPZIP_OK, or STEPZIP_OK. */
static enum stepzip_result pump(stream_fn call, void *h, const char *src, size_t n, size_t piece,
                                size_t room, char *dst, size_t cap, size_t *dst_n) {
    char *buf = malloc(room);
    struct stepzip_out_buffer out = {buf, room, 0};
    enum stepzip_result r = STEPZIP_OK;
    size_t remaining = 1;
    *dst_n = 0;
    for (size_t off = 0; off < n && r == STEPZIP_OK; off += piece) {
        struct stepzip_in_buffer in = {src + off, off + piece < n ? piece : n - off, 0};
        while (in.pos < in.size && r == STEPZIP_OK) {
            r = call(h, &out, &in, STEPZIP_CONTINUE, &remaining);
            drain(&out, dst, dst_n, cap);
        }
    }
    struct stepzip_in_buffer none = {NULL, 0, 0};
    while (r == STEPZIP_OK && remaining != 0) {
        r = call(h, &out, &none, STEPZIP_END, &remaining);
        drain(&out, dst, dst_n, cap);
    }
    free(buf);
    return r;
}

static void test_streams(void) {
    size_t n = 0;
    char *text = make_chains(3000, &n);
    struct stepzip_compressor *c =
        stepzip_alloc_compressor(3, STEPZIP_PROFILE_AUTO, STEPZIP_SEGMENTER_DEFAULT);
    const size_t cap = stepzip_compress_bound(n) + n;
    char *one_shot = malloc(cap), *streamed = malloc(cap), *back = malloc(n + 1);
    size_t one_n = 0, streamed_n = 0, back_n = 0;
    CHECK(stepzip_compress(c, STEPZIP_FORMAT_FREEMAN, text, n, one_shot, cap, &one_n) == STEPZIP_OK);

    /* the streamed frame equals the one-shot frame, through 777-byte input
     * pieces and a 100-byte output buffer */
    struct stepzip_cstream *cs = stepzip_alloc_cstream(c, STEPZIP_FORMAT_FREEMAN);
    stepzip_free_compressor(c); /* the stream keeps its own copy of the settings */
    CHECK(cs != NULL);
    CHECK(pump(cstream_call, cs, text, n, 777, 100, streamed, cap, &streamed_n) == STEPZIP_OK);
    CHECK(streamed_n == one_n && memcmp(streamed, one_shot, one_n) == 0);
    CHECK(streamed_n > 100);
    /* the handle starts the next frame after a complete one */
    CHECK(pump(cstream_call, cs, text, n, 4096, 1 << 16, streamed, cap, &streamed_n) == STEPZIP_OK);
    CHECK(streamed_n == one_n && memcmp(streamed, one_shot, one_n) == 0);

    /* decoding through 333-byte pieces and a 50-byte buffer gives the text */
    struct stepzip_dstream *ds = stepzip_alloc_dstream();
    CHECK(ds != NULL);
    CHECK(pump(dstream_call, ds, one_shot, one_n, 333, 50, back, n + 1, &back_n) == STEPZIP_OK);
    CHECK(back_n == n && memcmp(back, text, n) == 0);

    /* a damaged frame is an error with a message, repeated until a reset */
    one_shot[one_n / 2] ^= 0x21;
    enum stepzip_result r = pump(dstream_call, ds, one_shot, one_n, 333, 50, back, n + 1, &back_n);
    CHECK(r != STEPZIP_OK);
    CHECK(strlen(stepzip_dstream_error(ds)) > 0);
    one_shot[one_n / 2] ^= 0x21;
    struct stepzip_out_buffer out = {back, n, 0};
    struct stepzip_in_buffer in = {one_shot, one_n, 0};
    size_t remaining = 0;
    CHECK(stepzip_decompress_stream(ds, &out, &in, STEPZIP_END, &remaining) == r);
    stepzip_dstream_reset(ds);
    CHECK(strcmp(stepzip_dstream_error(ds), "") == 0);
    CHECK(pump(dstream_call, ds, one_shot, one_n, 1 << 20, 1 << 20, back, n + 1, &back_n) == STEPZIP_OK);
    CHECK(back_n == n && memcmp(back, text, n) == 0);

    /* bad chain text: the error names the line and column */
    const char bad[] = "0 0 0011\n1 1 0192\n";
    r = pump(cstream_call, cs, bad, sizeof bad - 1, 5, 64, streamed, cap, &streamed_n);
    CHECK(r == STEPZIP_SYNTAX);
    CHECK(strstr(stepzip_cstream_error(cs), ":2:") != NULL);
    stepzip_cstream_reset(cs);

    /* a frame abandoned halfway: freeing the handle ends its coder */
    struct stepzip_out_buffer small = {streamed, 10, 0};
    struct stepzip_in_buffer half = {text, n / 2, 0};
    CHECK(stepzip_compress_stream(cs, &small, &half, STEPZIP_CONTINUE, &remaining) == STEPZIP_OK);
    CHECK(remaining != 0);
    stepzip_free_cstream(cs);

    /* inconsistent buffers */
    struct stepzip_in_buffer past = {one_shot, 4, 5};
    CHECK(stepzip_decompress_stream(ds, &out, &past, STEPZIP_END, &remaining) == STEPZIP_INVALID_ARGUMENT);
    CHECK(stepzip_alloc_cstream(NULL, STEPZIP_FORMAT_AUTO) == NULL);
    stepzip_free_dstream(ds);
    stepzip_free_cstream(NULL);
    stepzip_free_dstream(NULL);
    free(text);
    free(one_shot);
    free(streamed);
    free(back);
}

int main(void) {
    CHECK(strcmp(stepzip_version_string(), STEPZIP_VERSION_STRING) == 0);
    CHECK(strcmp(stepzip_result_name(STEPZIP_OK), "ok") == 0);
    CHECK(strcmp(stepzip_result_name((enum stepzip_result)12345), "unknown") == 0);
    test_round_trip();
    test_segment_and_expand();
    test_streaming();
    test_profile_names();
    test_streams();
    if (failures) {
        fprintf(stderr, "%d check(s) failed\n", failures);
        return 1;
    }
    printf("capi_test: all checks passed\n");
    return 0;
}
