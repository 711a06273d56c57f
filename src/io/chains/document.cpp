// stepzip — chain files: format names, detection, the BlockReader/BlockWriter
// front ends and the whole-file conveniences. The formats themselves live in
// freeman_format.cpp, points_format.cpp and steps_format.cpp; docs/formats.md
// describes what each layout carries.
#include "stepzip/document.hpp"

#include <algorithm>
#include <cstdio>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "document_internal.hpp"

namespace stepzip {

namespace io {

void append_int(std::string& out, std::int64_t v) {
    char buf[24];
    out.append(buf, put_int(buf, v));
}

void append_number(std::string& out, std::int64_t v, Spelling sp) {
    if (sp.canonical()) return append_int(out, v);
    if (sp.sign == 1) out.push_back('+');
    if (sp.sign == 2 || v < 0) out.push_back('-');
    out.append(sp.zeros, '0');
    append_int(out, v < 0 ? -v : v);
}

bool get_spelling(LayoutCursor& c, std::int64_t v, Spelling& sp) {
    if (!c.u8(sp.sign) || !c.varint(sp.zeros)) return false;
    if (sp.sign > 2) return false;
    if (sp.sign == 1 && v < 0) return false;
    if (sp.sign == 2 && v != 0) return false;
    return sp.zeros <= kMaxFieldBytes;
}

Spelling NumberAccum::spelling() const {
    Spelling sp;
    if (plus) sp.sign = 1;
    else if (negative && magnitude == 0) sp.sign = 2;
    std::uint64_t canon = 1;
    for (std::uint64_t m = magnitude; m >= 10; m /= 10) ++canon;
    sp.zeros = digits - canon;
    return sp;
}

std::string at(const std::string& source, std::uint64_t line, std::uint64_t column,
               std::string_view what) {
    std::string s = source;
    s += ':';
    s += std::to_string(line);
    s += ':';
    s += std::to_string(column);
    s += ": ";
    s += what;
    return s;
}

std::string describe_byte(unsigned char c) {
    if (c >= 0x21 && c < 0x7F) return std::string("'") + static_cast<char>(c) + "'";
    if (c == ' ') return "a space";
    if (c == '\t') return "a tab";
    if (c == '\r') return "a carriage return";
    if (c == '\n') return "the end of the line";
    char buf[16];
    std::snprintf(buf, sizeof buf, "byte 0x%02X", c);
    return buf;
}

}  // namespace io

std::string_view format_name(InputFormat f) noexcept {
    switch (f) {
        case InputFormat::freeman: return "freeman";
        case InputFormat::points: return "points";
        case InputFormat::steps: return "steps";
        case InputFormat::timed: return "timed";
    }
    return "unknown";
}

std::optional<InputFormat> parse_format(std::string_view name) noexcept {
    if (name == "freeman") return InputFormat::freeman;
    if (name == "points") return InputFormat::points;
    if (name == "steps") return InputFormat::steps;
    if (name == "timed") return InputFormat::timed;
    return std::nullopt;
}

namespace {

std::unique_ptr<io::FormatParser> make_parser(InputFormat f, std::string source,
                                              std::size_t block_steps) {
    if (block_steps == 0) block_steps = 1;
    switch (f) {
        case InputFormat::freeman: return io::make_freeman_parser(std::move(source), block_steps);
        case InputFormat::points: return io::make_points_parser(std::move(source), block_steps);
        case InputFormat::steps: return io::make_steps_parser(std::move(source), block_steps);
        case InputFormat::timed: return io::make_timed_parser(std::move(source), block_steps);
    }
    return io::make_steps_parser(std::move(source), block_steps);
}

std::unique_ptr<io::FormatRenderer> make_renderer(InputFormat f) {
    switch (f) {
        case InputFormat::freeman: return io::make_freeman_renderer();
        case InputFormat::points: return io::make_points_renderer();
        case InputFormat::steps: return io::make_steps_renderer();
        case InputFormat::timed: return io::make_timed_renderer();
    }
    return io::make_steps_renderer();
}

struct TrialResult {
    bool ok = false;
    std::uint64_t line = 0;      // line reached (error line when !ok)
    std::size_t chains = 0;
    std::size_t longest = 0;     // most steps in one chain piece
};

TrialResult trial_parse(InputFormat f, std::string_view text) {
    TrialResult r;
    auto p = make_parser(f, "<head>", std::size_t{1} << 30);
    const Result<void> fed = p->feed(text, true);
    r.ok = fed.ok();
    r.line = p->line();
    for (const Block& b : p->ready) {
        r.chains += b.chains.size();
        for (const Chain& c : b.chains) r.longest = std::max(r.longest, c.steps.size());
    }
    return r;
}

}  // namespace

namespace io {
bool has_binary_byte(std::string_view bytes) noexcept {
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
    const std::size_t n = bytes.size();
    std::size_t i = 0;
#if defined(__SSE2__)
    // A control byte is one that min(byte, 0x1F) leaves unchanged.
    const __m128i c0 = _mm_set1_epi8(0x1F), tab = _mm_set1_epi8('\t'), lf = _mm_set1_epi8('\n');
    const __m128i cr = _mm_set1_epi8('\r'), del = _mm_set1_epi8(0x7F);
    for (; n - i >= 16; i += 16) {
        const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + i));
        const __m128i ctl = _mm_cmpeq_epi8(_mm_min_epu8(v, c0), v);
        const __m128i ws = _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi8(v, tab), _mm_cmpeq_epi8(v, lf)), _mm_cmpeq_epi8(v, cr));
        const __m128i bad = _mm_or_si128(_mm_andnot_si128(ws, ctl), _mm_cmpeq_epi8(v, del));
        if (_mm_movemask_epi8(bad) != 0) return true;
    }
#endif
    for (; i < n; ++i)
        if (is_binary_byte(p[i])) return true;
    return false;
}
}  // namespace io

std::optional<InputFormat> detect_format(std::string_view head) noexcept {
    try {
        if (io::has_binary_byte(head)) return InputFormat::steps;
        // Only whole lines take part: the head may end in the middle of one.
        std::string_view text = head;
        const std::size_t nl = text.rfind('\n');
        if (nl != std::string_view::npos) text = text.substr(0, nl + 1);
        const TrialResult fr = trial_parse(InputFormat::freeman, text);
        const TrialResult pt = trial_parse(InputFormat::points, text);
        if (fr.ok && pt.ok) {
            // "x y" lines and "x y c" lines with one code read both ways: a
            // file of one-step chains is far less likely than a point list.
            if (pt.chains == 0 || fr.longest >= 2) return InputFormat::freeman;
            return InputFormat::points;
        }
        if (fr.ok) return InputFormat::freeman;
        if (pt.ok) return InputFormat::points;
        // Neither fits: name the format that got further, so that the user
        // sees that format's syntax error.
        if (fr.line > pt.line) return InputFormat::freeman;
        if (pt.line > fr.line) return InputFormat::points;
        return std::nullopt;
    } catch (...) {
        return std::nullopt;
    }
}

// ---- BlockReader ---------------------------------------------------------------

struct BlockReader::Impl {
    std::unique_ptr<io::FormatParser> parser;
};

BlockReader::BlockReader(InputFormat format, std::string source, std::size_t block_steps)
    : impl_(std::make_unique<Impl>()) {
    impl_->parser = make_parser(format, std::move(source), block_steps);
}
BlockReader::~BlockReader() = default;
BlockReader::BlockReader(BlockReader&&) noexcept = default;
BlockReader& BlockReader::operator=(BlockReader&&) noexcept = default;

Result<void> BlockReader::feed(std::string_view data, bool last) {
    return impl_->parser->feed(data, last);
}

bool BlockReader::next(Block& out) {
    auto& q = impl_->parser->ready;
    if (q.empty()) return false;
    out = std::move(q.front());
    q.pop_front();
    return true;
}

// ---- BlockWriter ---------------------------------------------------------------

struct BlockWriter::Impl {
    std::unique_ptr<io::FormatRenderer> renderer;
};

BlockWriter::BlockWriter(InputFormat format) : impl_(std::make_unique<Impl>()) {
    impl_->renderer = make_renderer(format);
}
BlockWriter::~BlockWriter() = default;
BlockWriter::BlockWriter(BlockWriter&&) noexcept = default;
BlockWriter& BlockWriter::operator=(BlockWriter&&) noexcept = default;

Result<void> BlockWriter::write(const Block& block, std::string& out) {
    const std::size_t before = out.size();
    Result<void> r = impl_->renderer->write(block, out);
    if (!r) out.resize(before);
    return r;
}

// ---- whole files ---------------------------------------------------------------

Result<std::string> write_chains(InputFormat format, const std::vector<Chain>& chains) {
    Block block;
    block.axes = chains.empty() ? 2 : chains.front().axes;
    for (std::size_t i = 0; i < chains.size(); ++i) {
        const Chain& c = chains[i];
        const std::string where = "chain " + std::to_string(i + 1) + ": ";
        if (c.axes < 2 || c.axes > kMaxAxes)
            return make_error(Errc::invalid_argument, where + "axis count out of range");
        for (std::size_t k = 0; k < c.steps.size(); ++k)
            if (!step_valid(c.steps[k], c.axes))
                return make_error(Errc::invalid_argument,
                                  where + "step " + std::to_string(k + 1) + " is not a valid step");
        switch (format) {
            case InputFormat::freeman:
                if (c.axes != 2)
                    return make_error(Errc::invalid_argument, where + "freeman needs two axes");
                break;
            case InputFormat::points:
                if (c.axes != block.axes)
                    return make_error(Errc::invalid_argument,
                                      where + "points needs the same axis count in every chain");
                for (int a = 0; a < c.axes; ++a) {
                    const std::int64_t v = c.start[a];
                    if (v < -io::kCoordLimit || v > io::kCoordLimit ||
                        static_cast<std::int64_t>(c.steps.size()) > io::kCoordLimit)
                        return make_error(Errc::invalid_argument,
                                          where + "coordinate out of range");
                }
                break;
            case InputFormat::steps:
            case InputFormat::timed: {
                const bool timed = format == InputFormat::timed;
                if (c.axes > (timed ? 5 : 4))
                    return make_error(Errc::invalid_argument,
                                      where + (timed ? "timed holds time and at most four axes"
                                                     : "steps holds at most four axes"));
                if (timed)
                    for (std::size_t k = 0; k < c.steps.size(); ++k)
                        if (step_axis(c.steps[k], 0) != 1)
                            return make_error(Errc::invalid_argument,
                                              where + "step " + std::to_string(k + 1) +
                                                  " does not advance time (axis 0) by one tick");
                Point expect{};
                if (i > 0) expect = chains[i - 1].end();
                if (c.start != expect)
                    return make_error(Errc::invalid_argument,
                                      where + (i == 0 ? "a steps file starts at the origin"
                                                      : "a steps file is one chain; this chain "
                                                        "does not start where the previous ended"));
                break;
            }
        }
    }
    std::string out;
    if (format == InputFormat::steps || format == InputFormat::timed) {
        // One chain: concatenate the steps.
        Block one;
        one.axes = 2;
        Chain all;
        for (const Chain& c : chains) {
            all.axes = std::max(all.axes, c.axes);
            all.steps.insert(all.steps.end(), c.steps.begin(), c.steps.end());
        }
        one.axes = all.axes;
        one.chains.push_back(std::move(all));
        BlockWriter w(format);
        if (auto r = w.write(one, out); !r) return std::move(r).error();
        return out;
    }
    block.chains = chains;
    BlockWriter w(format);
    if (auto r = w.write(block, out); !r) return std::move(r).error();
    return out;
}

Result<std::vector<Chain>> read_chains(InputFormat format, std::string_view data,
                                       std::string source) {
    BlockReader reader(format, std::move(source));
    if (auto r = reader.feed(data, true); !r) return std::move(r).error();
    std::vector<Chain> chains;
    Block b;
    while (reader.next(b)) {
        std::size_t i = 0;
        if (b.continues && !b.chains.empty() && !chains.empty()) {
            Chain& prev = chains.back();
            prev.axes = std::max(prev.axes, b.chains[0].axes);
            prev.steps.insert(prev.steps.end(), b.chains[0].steps.begin(),
                              b.chains[0].steps.end());
            i = 1;
        }
        for (; i < b.chains.size(); ++i) chains.push_back(std::move(b.chains[i]));
    }
    return chains;
}

}  // namespace stepzip
