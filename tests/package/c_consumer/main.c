/* An outside C program built with `pkg-config --cflags --libs stepzip`:
 * compresses a chain file, decompresses it, and cuts a chain in segments. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stepzip.h>

int main(void) {
    static const char chains[] = "0 0 0020020020\n3 4 00010001000122223333\n";
    const size_t n = sizeof chains - 1;
    struct stepzip_compressor *c =
        stepzip_alloc_compressor(3, STEPZIP_PROFILE_AUTO, STEPZIP_SEGMENTER_DEFAULT);
    struct stepzip_decompressor *d = stepzip_alloc_decompressor();
    size_t cap = stepzip_compress_bound(n), size = 0, back_n = 0;
    char *frame = malloc(cap), back[sizeof chains];
    if (!c || !d || !frame) return 1;
    enum stepzip_result r = stepzip_compress(c, STEPZIP_FORMAT_AUTO, chains, n, frame, cap, &size);
    if (r != STEPZIP_OK) {
        fprintf(stderr, "compress: %s: %s\n", stepzip_result_name(r), stepzip_compressor_error(c));
        return 1;
    }
    r = stepzip_decompress(d, frame, size, back, sizeof back, &back_n);
    if (r != STEPZIP_OK || back_n != n || memcmp(back, chains, n) != 0) {
        fprintf(stderr, "decompress: %s: %s\n", stepzip_result_name(r), stepzip_decompressor_error(d));
        return 1;
    }
    stepzip_step steps[10];
    const char *codes = "0020020020";
    for (int i = 0; i < 10; ++i) steps[i] = stepzip_freeman_step(codes[i] - '0');
    struct stepzip_segment seg[10];
    size_t count = 0;
    r = stepzip_segment_steps(STEPZIP_PROFILE_PATENT, STEPZIP_SEGMENTER_GREEDY, 2, steps, 10, seg,
                              10, &count);
    if (r != STEPZIP_OK || count != 1 || seg[0].delta[0] != 7 || seg[0].delta[1] != 3) return 1;
    printf("stepzip %s from C: %zu bytes -> %zu bytes and back; 0020020020 is one segment (7, 3)\n",
           stepzip_version_string(), n, size);
    free(frame);
    stepzip_free_compressor(c);
    stepzip_free_decompressor(d);
    return 0;
}
