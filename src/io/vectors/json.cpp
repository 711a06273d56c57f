// stepzip — segmented chains as JSON (one object, chains in input order).
#include <string>

#include "stepzip/vectors.hpp"

namespace stepzip {

namespace {

void append_array(std::string& out, const std::int64_t* v, int n) {
    out += '[';
    for (int i = 0; i < n; ++i) {
        if (i) out += ',';
        out += std::to_string(v[i]);
    }
    out += ']';
}

}  // namespace

std::string write_json(const std::vector<SegmentedChain>& chains, const CutInfo& info) {
    // Every string written is a fixed identifier: no escaping is needed.
    std::string out = "{\"profile\":\"" + std::string(profile_name(info.profile)) +
                      "\",\"segmenter\":\"" + std::string(segmenter_name(info.segmenter)) +
                      "\",\"exact\":" + (info.exact ? "true" : "false");
    if (info.stats) {
        out += ",\"stats\":{\"patent_segments\":" + std::to_string(info.stats->patent_segments) +
               ",\"patent_exact\":" + std::to_string(info.stats->patent_exact) +
               ",\"patent_max_deviation\":" + std::to_string(info.stats->patent_max_deviation) +
               "}";
    }
    out += ",\"chains\":[";
    for (std::size_t c = 0; c < chains.size(); ++c) {
        const SegmentedChain& sc = chains[c];
        const int axes = sc.chain.axes;
        out += c ? ",\n" : "\n";
        out += "{\"start\":";
        append_array(out, sc.chain.start.data(), axes);
        out += ",\"steps\":" + std::to_string(sc.chain.steps.size()) + ",\"segments\":[";
        const int phases = phase_count(info.profile, axes);
        for (std::size_t k = 0; k < sc.segments.size(); ++k) {
            const Segment& s = sc.segments[k];
            if (k) out += ',';
            out += "{\"delta\":";
            append_array(out, s.delta.data(), axes);
            out += ",\"phase\":";
            append_array(out, s.phase.data(), phases);
            out += '}';
        }
        out += "]}";
    }
    out += "\n]}\n";
    return out;
}

}  // namespace stepzip
