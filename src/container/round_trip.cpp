// The encoder's round-trip proof (docs/FORMAT.md section 4): every block
// record is decoded again exactly as the decoder does and the decoded block
// compared with the input block, field by field (in the parallel jobs). The
// input block's rendering was compared with the input bytes when it was
// parsed (compress.cpp), and a renderer is a function of the block alone
// (document.hpp: each layout is self-contained), so the decoded block
// renders to the input bytes: it is not rendered a second time.
#include "encoder.hpp"
#include "modeled_block.hpp"
#include "raw_cm.hpp"
#include "table_block.hpp"
#include "timed_block.hpp"

namespace stepzip::stz {

void prove_decoded(BlockJob& job, const EncoderSettings& s, const WindowView& window) {
    if (job.error.code != Errc::ok) return;  // (reported by the caller)
    const std::string where = s.source + ": round-trip proof";
    const RecordView rec = view_record(job.record);
    std::string dec;
    if (rec.type == kRaw || rec.type == kChains) {
        auto z = unzstd(rec.payload, static_cast<std::uint32_t>(rec.dsize), where);
        if (!z) {
            job.error = make_error(Errc::mismatch, z.error().message);
            return;
        }
        dec = std::move(*z);
    }
    if (rec.type == kExtended && job.type == kRaw) {  // the CM raw block
        auto d = read_raw_cm_block(rec.payload, where);
        if (!d) {
            job.error = make_error(Errc::mismatch, d.error().message);
            return;
        }
        dec = std::move(*d);
    }
    if (job.type == kRaw) {
        if (dec != job.raw_payload) job.error = make_error(Errc::mismatch, where + ": raw block differs");
        job.counts.chains = job.block.chains.size();
        job.counts.steps = job.steps;
        return;
    }
    job.decoded.axes = job.block.axes;  // the frame's (the decoder's header)
    job.decoded.continues = job.block.continues;
    job.decoded.open = job.block.open;
    const WindowView* w = (rec.flags & kFlagWindow) ? &window : nullptr;
    // Block type 6 carries the model kind in the job (the encoder wrote it).
    const bool mixed = rec.type == kMixedModel;
    Result<void> r =
        rec.type == kChains
            ? read_chain_payload(dec, s.profile, s.axes, true, job.decoded, job.counts, where)
        : rec.type == kTable || (rec.type == kExtended && job.type == kTable)
            ? read_table_block(rec.payload, s.profile, s.axes, true, job.decoded, job.counts, where, w, nullptr, rec.type)
        : rec.type == kExtended
            ? read_extended_block(rec.payload, s.profile, s.axes, true, job.decoded, job.counts, where, w)
        : job.type == kSegmentModel
            ? read_segment_model(rec.payload, s.profile, s.axes, true, job.decoded, job.counts, where, w, nullptr,
                                 s.timed, mixed)
            : read_step_model(rec.payload, s.axes, true, job.decoded, job.counts, where, w, kFormatVersion, nullptr,
                              mixed);
    if (!r) {
        job.error = make_error(Errc::mismatch, r.error().message);
        return;
    }
    if (job.decoded.chains != job.block.chains || job.decoded.layout != job.block.layout)
        job.error = make_error(Errc::mismatch, where + ": decoded chains differ from the input (internal error)");
}

}  // namespace stepzip::stz
