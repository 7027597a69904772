// demo_io.cpp - demonstration readers for the learner: LCM demonstration logs and
// episode CSVs -> Episode lists (paper Sect. 2 tasks, Sect. 3 learning, Sect. 5.1 data).
// Log layout, pairing rule and error policy: docs/demonstrations.md.
//
// The log is read with LCM's C eventlog API. Before each event its 28-byte header is
// checked against the file size, so a truncated or corrupted file is reported as such
// (LCM itself would silently resynchronise or stop) and nothing sized by the file is
// allocated beyond what the file holds. Payloads go through the validating decoders of
// gmmrrt_lcmtypes_c (lcmtypes/include/gmmrrt/msg_decode.h): counts and NaN are checked
// there, once for all readers.
#include "gmmrrt_learner/demo_io.hpp"

#include <lcm/eventlog.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <locale>
#include <map>
#include <set>
#include <sstream>

#include "gmmrrt/model.h"
#include "gmmrrt/msg_decode.h"
#include "gmmrrt_learner/labels.hpp"

namespace gmmrrt {
namespace learn {
namespace {

constexpr uint32_t kLcmSyncWord = 0xEDA1DA01u;
constexpr long kEventHeaderBytes = 28;  // sync, eventnum, timestamp, channel len, data len
constexpr int32_t kMaxChannelLen = 255;  // longer names are not written by lcm-logger
const char* const kChannelDemoInfo = "DEMO_INFO";
const char* const kChannelRobotPose = "ROBOT_POSE";
const char* const kChannelPeople = "PEOPLE";
const char* const kCsvHeader[] = {"episode_id", "task",    "homotopy", "t",         "robot_x",
                                  "robot_y",    "person_x", "person_y", "person_yaw"};
constexpr size_t kCsvColumns = sizeof(kCsvHeader) / sizeof(kCsvHeader[0]);

// Seconds from utime a to utime b. In double: utimes come from the file, and their int64
// difference can overflow (found by tests/fuzz/fuzz_demo_log); exact below 2^53 us.
double SecondsBetween(int64_t a_utime, int64_t b_utime) {
    return (static_cast<double>(b_utime) - static_cast<double>(a_utime)) * 1e-6;
}

// Collects warnings up to kMaxWarnings, then counts the rest.
class Warnings {
  public:
    explicit Warnings(std::vector<std::string>* out) : out_(out) {}
    void Add(const std::string& w) {
        if (out_->size() < kMaxWarnings)
            out_->push_back(w);
        else
            ++dropped_;
    }
    void Finish() {
        if (dropped_ > 0)
            out_->push_back("... and " + std::to_string(dropped_) + " more warnings");
    }

  private:
    std::vector<std::string>* out_;
    size_t dropped_ = 0;
};

ReadResult Fail(const std::string& msg) {
    ReadResult r;
    r.ok = false;
    r.error = msg;
    return r;
}

uint32_t BigEndian32(const unsigned char* p) {
    return (uint32_t(p[0]) << 24) | (uint32_t(p[1]) << 16) | (uint32_t(p[2]) << 8) | uint32_t(p[3]);
}

std::string Stem(const std::string& path) {
    size_t slash = path.find_last_of('/');
    std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
    size_t dot = base.find('.');
    return dot == std::string::npos || dot == 0 ? base : base.substr(0, dot);
}

std::string EpisodeId(const std::string& stem, int32_t episode) {
    char num[16];
    std::snprintf(num, sizeof num, "%04d", static_cast<int>(episode));
    return stem + "_" + num;
}

// ---------------------------------------------------------------- log reader

struct PersonEntry {
    bool valid = false;
    int64_t utime = 0;
    double x = 0, y = 0, yaw = 0;
};

// The episode being assembled from the events after one DEMO_INFO.
struct OpenEpisode {
    bool active = false;   // a DEMO_INFO was decoded and its events are being collected
    bool labelled = true;  // false after a DEMO_INFO that could not be decoded
    Episode episode;
    int32_t number = 0;
    int64_t info_event = 0;
    int64_t start_utime = 0;
    int32_t person_id = -1;
    int64_t last_pose_utime = INT64_MIN;
    int64_t last_people_utime = INT64_MIN;
    PersonEntry person;
    size_t unpaired_poses = 0;
};

class LogReader {
  public:
    LogReader(const std::string& path, ReadResult* result)
        : path_(path), stem_(Stem(path)), result_(result), warn_(&result->warnings) {}

    // Returns false with result_->error set on a structural error.
    bool Run(std::vector<Episode>* episodes) {
        struct stat st;
        if (stat(path_.c_str(), &st) != 0)
            return Error(path_ + ": cannot open: " + std::strerror(errno));
        const long file_size = static_cast<long>(st.st_size);
        lcm_eventlog_t* log = lcm_eventlog_create(path_.c_str(), "r");
        if (log == nullptr)
            return Error(path_ + ": cannot open as an LCM log: " + std::strerror(errno));
        bool ok = Loop(log, file_size, episodes);
        lcm_eventlog_destroy(log);
        warn_.Finish();
        return ok;
    }

  private:
    bool Error(const std::string& msg) {
        result_->ok = false;
        result_->error = msg;
        return false;
    }

    // An error about what the whole log lacks: when the log was cut short, says where too.
    bool EndError(const std::string& msg) {
        return Error(truncation_.empty() ? msg : msg + " (" + truncation_ + ")");
    }

    std::string Where(int64_t event_no, long offset, const char* channel) const {
        std::ostringstream s;
        s << path_ << ": event " << event_no << " (byte " << offset;
        if (channel != nullptr)
            s << ", channel " << channel;
        s << ")";
        return s.str();
    }

    // What CheckHeader found at an event's offset.
    enum class Header { kOk, kTruncatedTail, kError };

    // Checks the header of the event at `offset` against the bytes left in the file. A log whose
    // last event is cut short (a recorder killed mid-write, a copy cut by a byte) is
    // kTruncatedTail: the events before it are whole and are read, with a warning. Anything
    // else that does not add up is kError with result_->error set.
    Header CheckHeader(FILE* f, long offset, long file_size, int64_t event_no, long* next_offset) {
        unsigned char h[kEventHeaderBytes];
        size_t got = std::fread(h, 1, sizeof h, f);
        if (got >= 4 && BigEndian32(h) != kLcmSyncWord) {
            Error(Where(event_no, offset, nullptr) +
                  (event_no == 1 ? ": not an LCM log (no sync word at the start)"
                                 : ": corrupted log (no LCM sync word where an event starts)"));
            return Header::kError;
        }
        if (got < sizeof h) {
            truncation_ = Where(event_no, offset, nullptr) + ": log truncated inside an event header (" +
                          std::to_string(file_size - offset) + " bytes left)";
            return Header::kTruncatedTail;
        }
        const int32_t channel_len = static_cast<int32_t>(BigEndian32(h + 20));
        const int32_t data_len = static_cast<int32_t>(BigEndian32(h + 24));
        if (channel_len <= 0 || channel_len > kMaxChannelLen) {
            Error(Where(event_no, offset, nullptr) + ": corrupted log (channel name length " +
                  std::to_string(channel_len) + ")");
            return Header::kError;
        }
        if (data_len < 0) {
            Error(Where(event_no, offset, nullptr) + ": corrupted log (data length " + std::to_string(data_len) + ")");
            return Header::kError;
        }
        const long need = kEventHeaderBytes + channel_len + static_cast<long>(data_len);
        if (need > file_size - offset) {
            truncation_ = Where(event_no, offset, nullptr) + ": log truncated inside the event (it needs " +
                          std::to_string(need) + " bytes, " + std::to_string(file_size - offset) + " left)";
            return Header::kTruncatedTail;
        }
        // LCM looks past the event for the next sync word and fails the event when it is
        // not there; check it here so the error names the event that is broken. Fewer than 4
        // bytes after the event are a cut next header: reported when the loop gets there.
        const long next = offset + need;
        if (next + 4 <= file_size) {
            unsigned char sync[4];
            if (std::fseek(f, next, SEEK_SET) != 0 || std::fread(sync, 1, 4, f) != 4) {
                Error(Where(event_no + 1, next, nullptr) + ": read failed");
                return Header::kError;
            }
            if (BigEndian32(sync) != kLcmSyncWord) {
                Error(Where(event_no + 1, next, nullptr) + ": corrupted log (no LCM sync word where an event starts)");
                return Header::kError;
            }
        }
        if (std::fseek(f, offset, SEEK_SET) != 0) {
            Error(Where(event_no, offset, nullptr) + ": seek failed");
            return Header::kError;
        }
        *next_offset = next;
        return Header::kOk;
    }

    // Walks the log's events in order: each header checked (CheckHeader), the event read by LCM
    // and handed to on_event(event, channel, event number, offset), which returns false after
    // setting result_->error. *events: the number of whole events. False on a structural error.
    template <typename OnEvent>
    bool Walk(lcm_eventlog_t* log, long file_size, int64_t* events, OnEvent on_event) {
        int64_t event_no = 0;
        long next_offset = 0;
        for (;;) {
            // Each event is read from the offset its predecessor's header announced
            // (LCM's own read position may be past a look-ahead).
            const long offset = next_offset;
            if (offset >= file_size)
                break;
            ++event_no;
            const Header header = CheckHeader(log->f, offset, file_size, event_no, &next_offset);
            if (header == Header::kError)
                return false;
            if (header == Header::kTruncatedTail) {
                warn_.Add(truncation_ + "; read up to the last complete event (" +
                          std::to_string(event_no - 1) + " events)");
                --event_no;
                break;
            }
            lcm_eventlog_event_t* ev = lcm_eventlog_read_next_event(log);
            if (ev == nullptr)
                return Error(Where(event_no, offset, nullptr) + ": LCM could not read the event");
            const std::string channel(ev->channel, static_cast<size_t>(ev->channellen));
            const bool ok = on_event(ev, channel, event_no, offset);
            lcm_eventlog_free_event(ev);
            if (!ok)
                return false;
        }
        *events = event_no;
        return true;
    }

    bool Loop(lcm_eventlog_t* log, long file_size, std::vector<Episode>* episodes) {
        int64_t event_no = 0;
        bool seen_info = false, seen_pose = false, seen_people = false;
        size_t orphans = 0;
        std::map<int32_t, int64_t> info_event_by_number;
        OpenEpisode ep;
        const bool walked = Walk(log, file_size, &event_no,
                                 [&](const lcm_eventlog_event_t* ev, const std::string& channel, int64_t no,
                                     long offset) {
            const size_t len = static_cast<size_t>(ev->datalen);
            char err[160] = "";
            if (channel == kChannelDemoInfo) {
                seen_info = true;
                Close(&ep, episodes);
                ep = OpenEpisode();
                ep.active = true;
                gmmrrt_demo_info_t info;
                if (gmmrrt_msg_decode_demo_info(ev->data, len, &info, err, sizeof err) != GMMRRT_MSG_OK) {
                    ep.labelled = false;
                    warn_.Add(Where(no, offset, kChannelDemoInfo) + ": " + err + "; its episode is skipped");
                } else {
                    auto dup = info_event_by_number.find(info.episode);
                    if (dup != info_event_by_number.end())
                        return Error(Where(no, offset, kChannelDemoInfo) + ": episode " +
                                     std::to_string(info.episode) + " was already started at event " +
                                     std::to_string(dup->second));
                    info_event_by_number[info.episode] = no;
                    ep.number = info.episode;
                    ep.info_event = no;
                    ep.start_utime = info.utime;
                    ep.person_id = info.person_id;
                    ep.episode.id = EpisodeId(stem_, info.episode);
                    ep.episode.task = info.task;
                    ep.episode.homotopy = info.homotopy;
                }
            } else if (channel == kChannelRobotPose) {
                seen_pose = true;
                OnPose(&ep, ev, len, no, offset, &orphans);
            } else if (channel == kChannelPeople) {
                seen_people = true;
                OnPeople(&ep, ev, len, no, offset, &orphans);
            }
            return true;
        });
        if (!walked)
            return false;
        Close(&ep, episodes);
        if (orphans > 0)
            warn_.Add(path_ + ": " + std::to_string(orphans) +
                      " ROBOT_POSE/PEOPLE events before the first DEMO_INFO were ignored");
        if (event_no == 0)
            return EndError(path_ + ": empty log (no events)");
        if (!seen_info)
            return EndError(path_ + ": no DEMO_INFO event: the episodes have no task/homotopy labels");
        if (!seen_pose)
            return EndError(path_ + ": no ROBOT_POSE event");
        if (!seen_people)
            return EndError(path_ + ": no PEOPLE event");
        if (episodes->empty())
            return EndError(path_ + ": no episode has a ROBOT_POSE paired with its person (see warnings)");
        return true;
    }

  public:
    // A continuous recording: every valid ROBOT_POSE and every person of every valid PEOPLE, on
    // one clock (seconds from the first valid message's utime); DEMO_INFO and other channels are
    // ignored. An invalid message, and a message whose utime goes back, is a warning and skipped.
    bool RunRecording(Recording* rec) {
        struct stat st;
        if (stat(path_.c_str(), &st) != 0)
            return Error(path_ + ": cannot open: " + std::strerror(errno));
        if (!S_ISREG(st.st_mode))
            return Error(path_ + ": cannot open: not a regular file");
        lcm_eventlog_t* log = lcm_eventlog_create(path_.c_str(), "r");
        if (log == nullptr)
            return Error(path_ + ": cannot open as an LCM log: " + std::strerror(errno));
        bool have_t0 = false;
        int64_t t0 = 0, last_pose = INT64_MIN, last_people = INT64_MIN, events = 0;
        const auto since_t0 = [&](int64_t utime) {
            if (!have_t0) {
                t0 = utime;
                have_t0 = true;
            }
            return SecondsBetween(t0, utime);
        };
        const bool walked = Walk(log, static_cast<long>(st.st_size), &events,
                                 [&](const lcm_eventlog_event_t* ev, const std::string& channel, int64_t no,
                                     long offset) {
            const size_t len = static_cast<size_t>(ev->datalen);
            char err[160] = "";
            if (channel == kChannelRobotPose) {
                gmmrrt_pose2d_t pose{};  // frame NULL until decoded: released below either way
                if (gmmrrt_msg_decode_pose2d(ev->data, len, &pose, err, sizeof err) != GMMRRT_MSG_OK) {
                    warn_.Add(Where(no, offset, kChannelRobotPose) + ": " + err + "; skipped");
                } else if (pose.utime <= last_pose) {
                    warn_.Add(Where(no, offset, kChannelRobotPose) + ": time does not advance (utime " +
                              std::to_string(pose.utime) + " not after " + std::to_string(last_pose) +
                              "); skipped");
                } else {
                    last_pose = pose.utime;
                    rec->robot.push_back({since_t0(pose.utime), pose.x, pose.y});
                }
                gmmrrt_msg_release_pose2d(&pose);
            } else if (channel == kChannelPeople) {
                gmmrrt_people_t people{};  // frame NULL until decoded: released below either way
                if (gmmrrt_msg_decode_people(ev->data, len, &people, err, sizeof err) != GMMRRT_MSG_OK) {
                    warn_.Add(Where(no, offset, kChannelPeople) + ": " + err + "; skipped");
                } else if (people.utime <= last_people) {
                    warn_.Add(Where(no, offset, kChannelPeople) + ": time does not advance (utime " +
                              std::to_string(people.utime) + " not after " + std::to_string(last_people) +
                              "); skipped");
                } else {
                    last_people = people.utime;
                    const double t = since_t0(people.utime);
                    for (int32_t i = 0; i < people.num_people; ++i) {
                        const gmmrrt_person_t& p = people.people[i];
                        rec->people[p.id].push_back({t, p.x, p.y, p.yaw});
                    }
                }
                gmmrrt_msg_release_people(&people);
            }
            return true;
        });
        lcm_eventlog_destroy(log);
        warn_.Finish();
        if (!walked)
            return false;
        if (events == 0)
            return EndError(path_ + ": empty log (no events)");
        if (rec->robot.empty())
            return EndError(path_ + ": no ROBOT_POSE event: nothing to segment");
        if (rec->people.empty())
            return EndError(path_ + ": no PEOPLE event with a person: no one to pass or approach");
        return true;
    }

  private:
    void OnPose(OpenEpisode* ep, const lcm_eventlog_event_t* ev, size_t len, int64_t event_no, long offset,
                size_t* orphans) {
        if (!ep->active) {
            ++*orphans;
            return;
        }
        if (!ep->labelled)
            return;
        gmmrrt_pose2d_t pose;
        char err[160] = "";
        if (gmmrrt_msg_decode_pose2d(ev->data, len, &pose, err, sizeof err) != GMMRRT_MSG_OK) {
            warn_.Add(Where(event_no, offset, kChannelRobotPose) + ": " + err + "; skipped");
            return;
        }
        // A demonstration's features are relative to its person: the frame name is not needed.
        gmmrrt_msg_release_pose2d(&pose);
        if (pose.utime <= ep->last_pose_utime || pose.utime < ep->start_utime) {
            warn_.Add(Where(event_no, offset, kChannelRobotPose) + ": time does not advance (utime " +
                      std::to_string(pose.utime) + " not after " +
                      std::to_string(std::max(ep->last_pose_utime, ep->start_utime)) + "); skipped");
            return;
        }
        ep->last_pose_utime = pose.utime;
        const double age_s = std::fabs(SecondsBetween(ep->person.utime, pose.utime));
        if (!ep->person.valid || age_s > kMaxPersonAgeS) {
            ++ep->unpaired_poses;
            return;
        }
        PoseSample s;
        s.t_s = SecondsBetween(ep->start_utime, pose.utime);
        s.robot_x = pose.x;
        s.robot_y = pose.y;
        s.robot_yaw = pose.yaw;
        s.person_x = ep->person.x;
        s.person_y = ep->person.y;
        s.person_yaw = ep->person.yaw;
        ep->episode.samples.push_back(s);
    }

    void OnPeople(OpenEpisode* ep, const lcm_eventlog_event_t* ev, size_t len, int64_t event_no, long offset,
                  size_t* orphans) {
        if (!ep->active) {
            ++*orphans;
            return;
        }
        if (!ep->labelled)
            return;
        gmmrrt_people_t people;
        char err[160] = "";
        if (gmmrrt_msg_decode_people(ev->data, len, &people, err, sizeof err) != GMMRRT_MSG_OK) {
            warn_.Add(Where(event_no, offset, kChannelPeople) + ": " + err + "; skipped");
            return;
        }
        gmmrrt_msg_release_people(&people);
        if (people.utime < ep->last_people_utime) {
            warn_.Add(Where(event_no, offset, kChannelPeople) + ": time goes backwards (utime " +
                      std::to_string(people.utime) + " after " + std::to_string(ep->last_people_utime) +
                      "); skipped");
            return;
        }
        ep->last_people_utime = people.utime;
        for (int32_t i = 0; i < people.num_people; ++i) {
            const gmmrrt_person_t& p = people.people[i];
            if (p.id != ep->person_id)
                continue;
            ep->person.valid = true;
            ep->person.utime = p.utime;
            ep->person.x = p.x;
            ep->person.y = p.y;
            ep->person.yaw = p.yaw;
            break;
        }
    }

    void Close(OpenEpisode* ep, std::vector<Episode>* episodes) {
        if (!ep->active || !ep->labelled)
            return;
        if (ep->unpaired_poses > 0)
            warn_.Add(path_ + ": episode " + std::to_string(ep->number) + " (DEMO_INFO at event " +
                      std::to_string(ep->info_event) + "): " + std::to_string(ep->unpaired_poses) +
                      " ROBOT_POSE events had no PEOPLE entry of person " + std::to_string(ep->person_id) +
                      " within " + std::to_string(kMaxPersonAgeS) + " s; skipped");
        if (ep->episode.samples.empty()) {
            warn_.Add(path_ + ": episode " + std::to_string(ep->number) + " (DEMO_INFO at event " +
                      std::to_string(ep->info_event) + ") has no samples; dropped");
        } else {
            episodes->push_back(std::move(ep->episode));
        }
        ep->active = false;
    }

    std::string path_;
    std::string truncation_;  // where a cut-short last event was found
    std::string stem_;
    ReadResult* result_;
    Warnings warn_;
};

// ---------------------------------------------------------------- CSV reader

std::vector<std::string> SplitCsvLine(const std::string& line) {
    std::vector<std::string> fields;
    size_t start = 0;
    for (;;) {
        size_t comma = line.find(',', start);
        if (comma == std::string::npos) {
            fields.push_back(line.substr(start));
            return fields;
        }
        fields.push_back(line.substr(start, comma - start));
        start = comma + 1;
    }
}

bool ParseFiniteDouble(const std::string& s, double* out) {
    if (s.empty() || std::isspace(static_cast<unsigned char>(s[0])))
        return false;
    char* end = nullptr;
    errno = 0;
    double v = std::strtod(s.c_str(), &end);
    if (end != s.c_str() + s.size() || errno == ERANGE || !std::isfinite(v))
        return false;
    *out = v;
    return true;
}

void StripCr(std::string* line) {
    if (!line->empty() && line->back() == '\r')
        line->pop_back();
}

// Spreadsheet programs start UTF-8 CSV exports with a byte order mark; it is not part of the
// first column's name.
void StripUtf8Bom(std::string* line) {
    if (line->compare(0, 3, "\xEF\xBB\xBF") == 0)
        line->erase(0, 3);
}

}  // namespace

void EstimateHeadingsFromMotion(std::vector<PoseSample>* samples, double min_step_m) {
    const size_t n = samples->size();
    auto far_enough = [&](size_t a, size_t b) {
        const PoseSample& p = (*samples)[a];
        const PoseSample& q = (*samples)[b];
        return std::hypot(q.robot_x - p.robot_x, q.robot_y - p.robot_y) >= min_step_m;
    };
    for (size_t i = 0; i < n; ++i) {
        size_t back = i, fwd = i;
        bool has_back = false, has_fwd = false;
        for (size_t j = i; j-- > 0;) {
            if (far_enough(j, i)) {
                back = j;
                has_back = true;
                break;
            }
        }
        for (size_t k = i + 1; k < n; ++k) {
            if (far_enough(i, k)) {
                fwd = k;
                has_fwd = true;
                break;
            }
        }
        const PoseSample& a = (*samples)[has_back ? back : i];
        const PoseSample& b = (*samples)[has_fwd ? fwd : i];
        (*samples)[i].robot_yaw =
            (has_back || has_fwd) ? std::atan2(b.robot_y - a.robot_y, b.robot_x - a.robot_x) : std::nan("");
    }
}

// An event listed twice, the same person and positions at the same times, is read once: a data set can
// list a walker who loops round the person once per homotopy label (a loop has no one side), and counting
// both would weigh that walker twice in a fit and in an evaluation. The first listing is kept; each repeat
// is left out with a warning that names the file, both episodes and their labels when they differ.
static void DropRepeatedEvents(const std::string& path, std::vector<Episode>* episodes,
                               std::vector<std::string>* warnings) {
    Warnings warn(warnings);
    std::map<std::string, size_t> first_of;  // the samples' bytes -> index of the kept listing
    std::vector<Episode> kept;
    kept.reserve(episodes->size());
    for (Episode& e : *episodes) {
        std::string key;
        key.reserve(e.samples.size() * 6 * sizeof(double));
        for (const PoseSample& s : e.samples)
            for (double v : {s.t_s, s.robot_x, s.robot_y, s.person_x, s.person_y, s.person_yaw})
                key.append(reinterpret_cast<const char*>(&v), sizeof v);
        auto found = first_of.find(key);
        if (found == first_of.end()) {
            first_of.emplace(std::move(key), kept.size());
            kept.push_back(std::move(e));
            continue;
        }
        const Episode& first = kept[found->second];
        std::string labels;
        if (first.homotopy != e.homotopy)
            labels = std::string(" with opposite homotopy labels (") + HomotopyName(first.homotopy) + ", " +
                     HomotopyName(e.homotopy) + ")";
        warn.Add(path + ": episodes " + first.id + " and " + e.id +
                 " are one event (the same person and positions at the same times)" + labels +
                 "; counted once, as " + first.id);
    }
    warn.Finish();
    *episodes = std::move(kept);
}

ReadResult ReadEpisodeCsv(const std::string& path, std::vector<Episode>* out) {
    std::ifstream in(path);
    if (!in)
        return Fail(path + ": cannot open: " + std::strerror(errno));
    ReadResult result;
    std::string line;
    if (!std::getline(in, line))
        return Fail(path + ": line 1: empty file (expected the header)");
    StripCr(&line);
    StripUtf8Bom(&line);
    {
        std::vector<std::string> header = SplitCsvLine(line);
        bool good = header.size() == kCsvColumns;
        for (size_t i = 0; good && i < kCsvColumns; ++i)
            good = header[i] == kCsvHeader[i];
        if (!good)
            return Fail(path + ": line 1: header must be "
                               "episode_id,task,homotopy,t,robot_x,robot_y,person_x,person_y,person_yaw");
    }
    std::vector<Episode> episodes;
    std::set<std::string> finished;
    size_t line_no = 1;
    while (std::getline(in, line)) {
        ++line_no;
        StripCr(&line);
        if (line.empty())
            continue;
        const std::string where = path + ": line " + std::to_string(line_no);
        std::vector<std::string> f = SplitCsvLine(line);
        if (f.size() != kCsvColumns)
            return Fail(where + ": " + std::to_string(f.size()) + " columns, expected " +
                        std::to_string(kCsvColumns));
        if (f[0].empty())
            return Fail(where + ": empty episode_id");
        int task = 0, homotopy = 0;
        const Status task_ok = ParseTask(f[1], &task);
        if (!task_ok.ok())
            return Fail(where + ": " + task_ok.message);
        // An empty homotopy is an unlabelled episode (homotopy 0, as DEMO_INFO's HOMOTOPY_UNKNOWN):
        // `fit --homotopy all` learns from it; a fit of one side skips it. "all" is a selection,
        // not a label: an episode passes on one side.
        if (!f[2].empty() && (!ParseHomotopy(f[2], &homotopy).ok() || homotopy == GMMRRT_HOMOTOPY_ALL))
            return Fail(where + ": unknown homotopy '" + f[2] + "' (expected left, right, frontal or empty)");
        double v[6];
        for (size_t c = 3; c < kCsvColumns; ++c) {
            if (!ParseFiniteDouble(f[c], &v[c - 3]))
                return Fail(where + ": column " + kCsvHeader[c] + " = '" + f[c] + "' is not a finite number");
        }
        if (episodes.empty() || episodes.back().id != f[0]) {
            if (!episodes.empty())
                finished.insert(episodes.back().id);
            if (finished.count(f[0]) != 0)
                return Fail(where + ": episode '" + f[0] + "' appears again after other episodes");
            Episode e;
            e.id = f[0];
            e.task = task;
            e.homotopy = homotopy;
            episodes.push_back(std::move(e));
        }
        Episode& e = episodes.back();
        if (e.task != task || e.homotopy != homotopy)
            return Fail(where + ": episode '" + e.id + "' changes its task or homotopy");
        if (!e.samples.empty() && !(v[0] > e.samples.back().t_s))
            return Fail(where + ": time does not increase in episode '" + e.id + "' (t = " + f[3] + ")");
        PoseSample s;
        s.t_s = v[0];
        s.robot_x = v[1];
        s.robot_y = v[2];
        s.robot_yaw = std::nan("");
        s.person_x = v[3];
        s.person_y = v[4];
        s.person_yaw = v[5];
        e.samples.push_back(s);
    }
    if (in.bad())
        return Fail(path + ": read error after line " + std::to_string(line_no));
    if (episodes.empty())
        return Fail(path + ": no episodes (only a header)");
    DropRepeatedEvents(path, &episodes, &result.warnings);
    for (Episode& e : episodes)
        EstimateHeadingsFromMotion(&e.samples);
    for (Episode& e : episodes)
        out->push_back(std::move(e));
    return result;
}

ReadResult ReadDemoLog(const std::string& path, std::vector<Episode>* out) {
    ReadResult result;
    std::vector<Episode> episodes;
    LogReader reader(path, &result);
    if (!reader.Run(&episodes))
        return result;
    for (Episode& e : episodes)
        out->push_back(std::move(e));
    return result;
}

ReadResult WriteEpisodeCsv(const std::string& path, const std::vector<Episode>& episodes) {
    if (episodes.empty())
        return Fail(path + ": no episodes to write");
    std::ostringstream text;
    text.imbue(std::locale::classic());
    for (size_t c = 0; c < kCsvColumns; ++c)
        text << (c ? "," : "") << kCsvHeader[c];
    text << "\n";
    char num[32];
    const auto put = [&](double v) {
        std::snprintf(num, sizeof num, "%.17g", v);  // 17 digits: reads back to the same double
        text << ',' << num;
    };
    for (const Episode& e : episodes) {
        // The columns' words are the labels' (labels.hpp): a task, and a side (not "all").
        const char* task = TaskName(e.task);
        const char* homotopy = HomotopyName(e.homotopy);
        int parsed = 0;
        if (e.id.empty() || e.id.find_first_of(",\r\n") != std::string::npos)
            return Fail(path + ": episode id '" + e.id + "' is empty or holds a comma or line break");
        if (!ParseTask(task, &parsed).ok() || !ParseHomotopy(homotopy, &parsed).ok() ||
            e.homotopy == GMMRRT_HOMOTOPY_ALL)
            return Fail(path + ": episode " + e.id + ": task " + std::to_string(e.task) + " / homotopy " +
                        std::to_string(e.homotopy) + " has no label in the episode CSV");
        for (const PoseSample& s : e.samples) {
            text << e.id << ',' << task << ',' << homotopy;
            for (double v : {s.t_s, s.robot_x, s.robot_y, s.person_x, s.person_y, s.person_yaw}) {
                if (!std::isfinite(v))
                    return Fail(path + ": episode " + e.id + ": a sample is not finite");
                put(v);
            }
            text << '\n';
        }
    }
    // Whole or not at all: a temporary file beside the target, synced, then renamed over it.
    const std::string data = text.str();
    std::string tmp = path + ".XXXXXX";
    const int fd = mkstemp(&tmp[0]);
    if (fd < 0)
        return Fail(path + ": cannot create a temporary file beside it: " + std::strerror(errno));
    size_t done = 0;
    while (done < data.size()) {
        const ssize_t n = write(fd, data.data() + done, data.size() - done);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            const std::string why = std::strerror(errno);
            close(fd);
            unlink(tmp.c_str());
            return Fail(path + ": write failed: " + why);
        }
        done += static_cast<size_t>(n);
    }
    if (fchmod(fd, 0644) != 0 || fsync(fd) != 0 || close(fd) != 0 || rename(tmp.c_str(), path.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        unlink(tmp.c_str());
        return Fail(path + ": cannot write: " + why);
    }
    return ReadResult();
}

ReadResult ReadRecording(const std::string& path, Recording* out) {
    ReadResult result;
    Recording rec;
    LogReader reader(path, &result);
    if (reader.RunRecording(&rec))
        *out = std::move(rec);
    return result;
}

ReadResult ReadEpisodes(const std::string& path, std::vector<Episode>* out) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        return Fail(path + ": cannot open: " + std::strerror(errno));
    unsigned char magic[4] = {0, 0, 0, 0};
    in.read(reinterpret_cast<char*>(magic), sizeof magic);
    const bool is_log = in.gcount() == 4 && BigEndian32(magic) == kLcmSyncWord;
    in.close();
    return is_log ? ReadDemoLog(path, out) : ReadEpisodeCsv(path, out);
}

ReadResult ReadSplitIndex(const std::string& path, std::map<std::string, std::string>* split_by_episode) {
    std::ifstream in(path);
    if (!in)
        return Fail(path + ": cannot open: " + std::strerror(errno));
    std::string line;
    if (!std::getline(in, line))
        return Fail(path + ": line 1: empty file (expected a header with episode_id and split)");
    StripCr(&line);
    StripUtf8Bom(&line);
    const std::vector<std::string> header = SplitCsvLine(line);
    size_t id_col = header.size(), split_col = header.size();
    for (size_t i = 0; i < header.size(); ++i) {
        if (header[i] == "episode_id")
            id_col = i;
        else if (header[i] == "split")
            split_col = i;
    }
    if (id_col == header.size() || split_col == header.size())
        return Fail(path + ": line 1: header has no episode_id or no split column");
    std::map<std::string, std::string> splits;
    size_t line_no = 1;
    while (std::getline(in, line)) {
        ++line_no;
        StripCr(&line);
        if (line.empty())
            continue;
        const std::string where = path + ": line " + std::to_string(line_no);
        const std::vector<std::string> f = SplitCsvLine(line);
        if (f.size() != header.size())
            return Fail(where + ": " + std::to_string(f.size()) + " columns, the header has " +
                        std::to_string(header.size()));
        if (f[id_col].empty() || f[split_col].empty())
            return Fail(where + ": empty episode_id or split");
        if (!splits.emplace(f[id_col], f[split_col]).second)
            return Fail(where + ": episode '" + f[id_col] + "' is listed twice");
    }
    if (in.bad())
        return Fail(path + ": read error after line " + std::to_string(line_no));
    *split_by_episode = std::move(splits);
    return ReadResult();
}

}  // namespace learn
}  // namespace gmmrrt
