// capture_compressor: a digitizer's live step stream in, a .stz file out,
// and the vectors shown while the capture runs.
//
//   capture_compressor OUT.stz [AXES] < capture.steps
//
// The input is a STEP/DIR log as a digitizer or a step counter emits it: one
// byte per tick, bit 2i = axis i stepped, bit 2i+1 = its direction negative
// (a level: it may stay set on an axis that does not step); a tick on which
// no axis steps is idle. The program reads it in small pieces as they
// arrive and
//  - pushes every step into a StreamingSegmenter, printing each segment on
//    stdout ("segment DX DY ...") the moment it is final, with at most 4096
//    steps held back, so a viewer can draw the capture while it is traced;
//  - passes the same bytes to the container's streaming compressor
//    (compress_stream), which writes the .stz frame block by block.
// At the end it reports on stderr the segments shown, the most steps ever
// held back and the frame's size. `stepzip verify OUT.stz capture.steps`
// proves the file.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "stepzip/container.hpp"
#include "stepzip/streaming.hpp"

int main(int argc, char** argv) {
    if (argc < 2 || argc > 3) {
        std::cerr << "usage: capture_compressor OUT.stz [AXES] < capture.steps\n";
        return 2;
    }
    const int axes = argc == 3 ? std::atoi(argv[2]) : 2;
    stepzip::StreamingSegmenter live(stepzip::Profile::eval8, axes, 4096);
    if (!live.valid() || axes > 4) {
        std::cerr << "capture_compressor: a steps log has 2 to 4 axes\n";
        return 2;
    }

    std::vector<stepzip::Segment> ready;
    std::uint64_t shown = 0;
    std::size_t most_held = 0;
    std::string error;
    auto show = [&] {
        for (const stepzip::Segment& s : ready) {
            std::cout << "segment";
            for (int a = 0; a < axes; ++a) std::cout << ' ' << s.delta[static_cast<std::size_t>(a)];
            std::cout << '\n';
        }
        shown += ready.size();
        ready.clear();
    };

    // The compressor pulls the capture through this function; each piece is
    // also pushed, step by step, into the live segmenter.
    stepzip::ReadFn read = [&](char* buf, std::size_t cap) -> stepzip::Result<std::size_t> {
        std::cin.read(buf, static_cast<std::streamsize>(std::min<std::size_t>(cap, 512)));
        const auto n = static_cast<std::size_t>(std::cin.gcount());
        if (n == 0 && std::cin.bad())
            return stepzip::make_error(stepzip::Errc::io, "<stdin>: read error");
        for (std::size_t i = 0; i < n; ++i) {
            // A DIR bit is a level: it means something only on an axis that steps.
            unsigned byte = static_cast<unsigned char>(buf[i]), step = 0;
            for (int a = 0; a < 4; ++a)
                if (byte >> (2 * a) & 1u) step |= (byte >> (2 * a) & 3u) << (2 * a);
            if (step == 0) continue;  // idle tick
            if (auto r = live.push(static_cast<stepzip::Step>(step), ready); !r) {
                error = r.error().message;
                return stepzip::make_error(r.error().code, "<stdin>: " + error);
            }
            most_held = std::max(most_held, live.held());
        }
        show();
        return n;
    };

    const std::string tmp = std::string(argv[1]) + ".part";
    std::ofstream out(tmp, std::ios::binary);
    if (!out) {
        std::cerr << "capture_compressor: cannot write " << tmp << "\n";
        return 1;
    }
    stepzip::WriteFn write = [&](std::string_view bytes) -> stepzip::Result<void> {
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        if (!out) return stepzip::make_error(stepzip::Errc::io, tmp + ": write error");
        return {};
    };

    stepzip::CompressOptions opt;
    opt.format = stepzip::InputFormat::steps;
    opt.source = "<stdin>";
    auto info = stepzip::compress_stream(read, write, opt);
    if (!info) {
        std::remove(tmp.c_str());
        std::cerr << "capture_compressor: " << info.error().message << "\n";
        return 1;
    }
    out.close();
    if (!out || std::rename(tmp.c_str(), argv[1]) != 0) {
        std::remove(tmp.c_str());
        std::cerr << "capture_compressor: cannot write " << argv[1] << "\n";
        return 1;
    }
    live.finish(ready);
    show();
    std::cerr << "capture_compressor: " << info->steps << " steps, " << shown
              << " segments shown live (at most " << most_held << " steps held back), "
              << info->decoded_bytes << " bytes -> " << info->compressed_bytes << " bytes\n";
    return 0;
}
