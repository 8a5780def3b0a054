#pragma once
// Bus messages -> the recorder's plain structs. The one place where the evaluation meets LCM;
// relplane-logger (live) and relplane-eval (from a log) both feed their recorder through
// FeedEncoded, so a replayed run is scored exactly like a live one.

#include <cstdint>
#include <relplane/map_t.hpp>
#include <relplane/pose_t.hpp>
#include <relplane/status_t.hpp>
#include <string>
#include <vector>

#include "relplane/eval/run_recorder.hpp"
#include "relplane/eval/types.hpp"

namespace relplane::eval {

// False with a reason for a pose with non-finite numbers, a zero quaternion or a covariance
// that is not symmetric positive semi-definite.
bool FromMessage(const relplane::pose_t& msg, PoseSample* out, std::string* reason);
// False with a reason for a plane with non-finite numbers.
bool FromMessage(const relplane::map_t& msg, MapSnapshot* out, std::string* reason);
StatusSample FromMessage(const relplane::status_t& msg);

// The channels the recorder reads: POSE, SIM_TRUTH, MAP, SIM_WORLD, STATUS and PLANES (only
// its seq, for the per-stage latency).
const std::vector<std::string>& RecordedChannels();

enum class FeedResult { kUsed, kIgnored, kRejected };

// Decodes one encoded message of `channel` and hands it to `recorder`. Other channels are
// ignored; an undecodable or invalid message is rejected with a one-line reason.
FeedResult FeedEncoded(RunRecorder& recorder, const std::string& channel, const uint8_t* data,
                       size_t size, int64_t receive_us, std::string* reason);

}  // namespace relplane::eval
