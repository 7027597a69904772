// test_demo_io.cpp - the learner's demonstration readers (learner/src/demo_io.cpp): good logs
// and CSVs, the pairing rule, skipped bad events, and fault tests on truncated and bit-flipped
// logs and malformed CSV lines (STYLE.md 15). Layout: docs/demonstrations.md.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <unistd.h>
#include <lcm/eventlog.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "gmmrrt/demo_info_t.hpp"
#include "gmmrrt/features.h"
#include "gmmrrt/model.h"
#include "gmmrrt/people_t.hpp"
#include "gmmrrt/pose2d_t.hpp"
#include "gmmrrt_learner/demo_io.hpp"

// cmocka last: its fail() macro would clash with std::ios::fail.
extern "C" {
#include <cmocka.h>
}

using gmmrrt::learn::Episode;
using gmmrrt::learn::ReadResult;

namespace {

std::string g_dir;  // scratch folder for this run

std::string TempPath(const std::string& name) { return g_dir + "/" + name; }

bool Contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

bool AnyWarningContains(const ReadResult& r, const std::string& part) {
    for (const std::string& w : r.warnings)
        if (Contains(w, part))
            return true;
    return false;
}

// Writes events to an LCM log and remembers where each one ends.
class LogWriter {
  public:
    explicit LogWriter(const std::string& path) : path_(path) {
        log_ = lcm_eventlog_create(path.c_str(), "w");
        assert_non_null(log_);
    }
    ~LogWriter() { Close(); }
    void Close() {
        if (log_ != nullptr) {
            lcm_eventlog_destroy(log_);
            log_ = nullptr;
        }
    }
    template <typename Msg>
    void Write(const char* channel, const Msg& msg, int64_t utime) {
        std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
        assert_true(msg.encode(buf.data(), 0, static_cast<int>(buf.size())) >= 0);
        WriteRaw(channel, buf, utime);
    }
    void WriteRaw(const char* channel, std::vector<uint8_t> buf, int64_t utime) {
        lcm_eventlog_event_t ev;
        std::memset(&ev, 0, sizeof ev);
        ev.timestamp = utime;
        ev.channellen = static_cast<int32_t>(std::strlen(channel));
        ev.datalen = static_cast<int32_t>(buf.size());
        ev.channel = const_cast<char*>(channel);
        ev.data = buf.data();
        assert_int_equal(lcm_eventlog_write_event(log_, &ev), 0);
        std::fflush(log_->f);
        ends.push_back(std::ftell(log_->f));
    }
    std::vector<long> ends;  // byte offset after each event

  private:
    std::string path_;
    lcm_eventlog_t* log_ = nullptr;
};

gmmrrt::demo_info_t Info(int64_t utime, int32_t episode, int8_t task, int8_t homotopy, int32_t person_id) {
    gmmrrt::demo_info_t m;
    m.utime = utime;
    m.episode = episode;
    m.task = task;
    m.homotopy = homotopy;
    m.person_id = person_id;
    return m;
}

gmmrrt::pose2d_t Pose(int64_t utime, double x, double y, double yaw) {
    gmmrrt::pose2d_t m{};
    m.utime = utime;
    m.frame = "map";
    m.x = x;
    m.y = y;
    m.yaw = yaw;
    m.velocity_valid = false;
    return m;
}

// Two people: a distractor (id 7) and the person of the task.
gmmrrt::people_t People(int64_t utime, int32_t id, double x, double y, double yaw) {
    gmmrrt::people_t m{};
    m.utime = utime;
    m.frame = "map";
    m.num_people = 2;
    m.people[0].utime = utime;
    m.people[0].id = 7;
    m.people[0].x = -100;
    m.people[0].y = -100;
    m.people[1].utime = utime;
    m.people[1].id = id;
    m.people[1].x = x;
    m.people[1].y = y;
    m.people[1].yaw = yaw;
    return m;
}

constexpr int64_t kT0 = 1700000000000000;  // utime of the first episode
constexpr int kSamplesPerEpisode = 10;

// A good log: episode 0 avoid/left about person 3, episode 1 approach/frontal about person 5.
// Returns the event end offsets.
std::vector<long> WriteGoodLog(const std::string& path, int samples = kSamplesPerEpisode) {
    LogWriter w(path);
    w.Write("DEMO_INFO", Info(kT0, 0, 1, 1, 3), kT0);
    for (int i = 0; i < samples; ++i) {
        const int64_t t = kT0 + i * 100000;
        w.Write("PEOPLE", People(t, 3, 2.0, 0.5, 3.0), t);
        w.Write("ROBOT_POSE", Pose(t, 0.1 * i, 0.01 * i, 0.1), t);
    }
    const int64_t t1 = kT0 + 60000000;
    w.Write("DEMO_INFO", Info(t1, 1, 2, 3, 5), t1);
    for (int i = 0; i < samples; ++i) {
        const int64_t t = t1 + i * 50000;
        w.Write("PEOPLE", People(t, 5, -1.0, 4.0, 1.5), t);
        w.Write("ROBOT_POSE", Pose(t, -0.2 * i, 1.0, M_PI), t);
    }
    w.Close();
    return w.ends;
}

void WriteText(const std::string& path, const std::string& text) {
    std::ofstream f(path, std::ios::binary);
    f << text;
}

std::vector<char> ReadBytes(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::vector<char>((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

void WriteBytes(const std::string& path, const std::vector<char>& bytes, size_t n) {
    std::ofstream f(path, std::ios::binary);
    f.write(bytes.data(), static_cast<std::streamsize>(n));
}

const std::string kHeader = "episode_id,task,homotopy,t,robot_x,robot_y,person_x,person_y,person_yaw\n";

// ---------------------------------------------------------------- logs

void test_log_good_file_gives_labelled_paired_samples(void** state) {
    (void)state;
    const std::string path = TempPath("good.lcmlog");
    WriteGoodLog(path);
    std::vector<Episode> eps;
    ReadResult r = gmmrrt::learn::ReadDemoLog(path, &eps);
    assert_true(r.ok);
    assert_int_equal(r.warnings.size(), 0);
    assert_int_equal(eps.size(), 2);
    assert_string_equal(eps[0].id.c_str(), "good_0000");
    assert_int_equal(eps[0].task, GMMRRT_TASK_AVOID);
    assert_int_equal(eps[0].homotopy, GMMRRT_HOMOTOPY_LEFT);
    assert_int_equal(eps[1].task, GMMRRT_TASK_APPROACH);
    assert_int_equal(eps[1].homotopy, GMMRRT_HOMOTOPY_FRONTAL);
    assert_int_equal(eps[0].samples.size(), kSamplesPerEpisode);
    assert_int_equal(eps[1].samples.size(), kSamplesPerEpisode);
    for (int i = 0; i < kSamplesPerEpisode; ++i) {
        const auto& s = eps[0].samples[static_cast<size_t>(i)];
        assert_float_equal(s.t_s, 0.1 * i, 1e-12);
        assert_float_equal(s.robot_x, 0.1 * i, 1e-12);
        assert_float_equal(s.robot_y, 0.01 * i, 1e-12);
        assert_float_equal(s.robot_yaw, 0.1, 1e-12);
        assert_float_equal(s.person_x, 2.0, 1e-12);  // the task's person, not the distractor
        assert_float_equal(s.person_yaw, 3.0, 1e-12);
        const auto& q = eps[1].samples[static_cast<size_t>(i)];
        assert_float_equal(q.t_s, 0.05 * i, 1e-12);
        assert_float_equal(q.person_y, 4.0, 1e-12);
    }
}

void test_log_pose_without_recent_person_is_skipped(void** state) {
    (void)state;
    const std::string path = TempPath("stale.lcmlog");
    {
        LogWriter w(path);
        w.Write("DEMO_INFO", Info(kT0, 0, 1, 2, 3), kT0);
        w.Write("PEOPLE", People(kT0, 3, 1, 1, 0), kT0);
        // Ages relative to the person's entry at kT0, against kMaxPersonAgeS.
        const int64_t max_age_us = static_cast<int64_t>(gmmrrt::learn::kMaxPersonAgeS * 1e6);
        w.Write("ROBOT_POSE", Pose(kT0 + max_age_us, 0, 0, 0), kT0);                     // at the limit: paired
        w.Write("ROBOT_POSE", Pose(kT0 + max_age_us + 1000, 1, 0, 0), kT0);              // 1 ms over: skipped
        w.Write("PEOPLE", People(kT0 + max_age_us + 2000, 9, 1, 1, 0), kT0);            // other person only
        w.Write("ROBOT_POSE", Pose(kT0 + max_age_us + 3000, 2, 0, 0), kT0);              // still stale: skipped
    }
    std::vector<Episode> eps;
    ReadResult r = gmmrrt::learn::ReadDemoLog(path, &eps);
    assert_true(r.ok);
    assert_int_equal(eps.size(), 1);
    assert_int_equal(eps[0].samples.size(), 1);
    assert_true(AnyWarningContains(r, "2 ROBOT_POSE events had no PEOPLE entry of person 3"));
}

void test_log_nan_pose_and_backwards_time_are_skipped_with_warnings(void** state) {
    (void)state;
    const std::string path = TempPath("bad_events.lcmlog");
    {
        LogWriter w(path);
        w.Write("DEMO_INFO", Info(kT0, 0, 1, 2, 3), kT0);                          // event 1
        w.Write("PEOPLE", People(kT0, 3, 1, 1, 0), kT0);                           // event 2
        w.Write("ROBOT_POSE", Pose(kT0 + 100000, 0, 0, 0), kT0);                   // event 3
        w.Write("ROBOT_POSE", Pose(kT0 + 200000, std::nan(""), 0, 0), kT0);        // event 4: NaN
        w.Write("ROBOT_POSE", Pose(kT0 + 50000, 0.5, 0, 0), kT0);                  // event 5: backwards
        w.Write("ROBOT_POSE", Pose(kT0 + 300000, std::numeric_limits<double>::infinity(), 0, 0), kT0);  // 6
        w.Write("ROBOT_POSE", Pose(kT0 + 400000, 1, 0, 0), kT0);                   // event 7
    }
    std::vector<Episode> eps;
    ReadResult r = gmmrrt::learn::ReadDemoLog(path, &eps);
    assert_true(r.ok);
    assert_int_equal(eps.size(), 1);
    assert_int_equal(eps[0].samples.size(), 2);
    assert_true(AnyWarningContains(r, path + ": event 4"));
    assert_true(AnyWarningContains(r, path + ": event 5"));
    assert_true(AnyWarningContains(r, path + ": event 6"));
    assert_true(AnyWarningContains(r, "time does not advance"));
    assert_true(AnyWarningContains(r, "not finite"));
}

void test_log_missing_channels_are_errors(void** state) {
    (void)state;
    const std::string no_people = TempPath("no_people.lcmlog");
    {
        LogWriter w(no_people);
        w.Write("DEMO_INFO", Info(kT0, 0, 1, 2, 3), kT0);
        w.Write("ROBOT_POSE", Pose(kT0, 0, 0, 0), kT0);
    }
    std::vector<Episode> eps;
    ReadResult r = gmmrrt::learn::ReadDemoLog(no_people, &eps);
    assert_false(r.ok);
    assert_true(Contains(r.error, no_people));
    assert_true(Contains(r.error, "no PEOPLE event"));

    const std::string no_info = TempPath("no_info.lcmlog");
    {
        LogWriter w(no_info);
        w.Write("PEOPLE", People(kT0, 3, 1, 1, 0), kT0);
        w.Write("ROBOT_POSE", Pose(kT0, 0, 0, 0), kT0);
    }
    r = gmmrrt::learn::ReadDemoLog(no_info, &eps);
    assert_false(r.ok);
    assert_true(Contains(r.error, "no DEMO_INFO"));
    assert_int_equal(eps.size(), 0);  // untouched on failure

    const std::string missing = TempPath("does_not_exist.lcmlog");
    r = gmmrrt::learn::ReadDemoLog(missing, &eps);
    assert_false(r.ok);
    assert_true(Contains(r.error, missing));
}

void test_log_bad_demo_info_drops_its_episode(void** state) {
    (void)state;
    const std::string path = TempPath("bad_info.lcmlog");
    {
        LogWriter w(path);
        w.Write("DEMO_INFO", Info(kT0, 0, 9, 1, 3), kT0);  // task 9 is unknown
        w.Write("PEOPLE", People(kT0, 3, 1, 1, 0), kT0);
        w.Write("ROBOT_POSE", Pose(kT0, 0, 0, 0), kT0);
        w.Write("DEMO_INFO", Info(kT0 + 1000000, 1, 1, 2, 3), kT0);
        w.Write("PEOPLE", People(kT0 + 1000000, 3, 1, 1, 0), kT0);
        w.Write("ROBOT_POSE", Pose(kT0 + 1000000, 0, 0, 0), kT0);
    }
    std::vector<Episode> eps;
    ReadResult r = gmmrrt::learn::ReadDemoLog(path, &eps);
    assert_true(r.ok);
    assert_int_equal(eps.size(), 1);
    assert_int_equal(eps[0].homotopy, GMMRRT_HOMOTOPY_RIGHT);
    assert_true(AnyWarningContains(r, path + ": event 1"));
}

// Byte positions worth damaging: every byte of each event's header and channel name and the
// last bytes of its payload (where lengths and boundaries matter), every 13th byte elsewhere
// (payload bytes, which the decoders check). Keeps the fault tests to seconds on a busy machine.
bool WorthTrying(size_t i, const std::vector<long>& ends) {
    long start = 0;
    for (long e : ends) {
        const long pos = static_cast<long>(i);
        if (pos < e)
            return pos < start + 48 || pos >= e - 8 || i % 13 == 0;
        start = e;
    }
    return true;
}

// A log cut at any byte is read up to its last complete event: the cut is a warning naming
// the file, the event and "truncated"; what remains is a prefix of the whole log's samples. When
// too little remains to form an episode, the error names the cut.
void test_log_truncated_anywhere_reads_the_complete_events_with_a_warning(void** state) {
    (void)state;
    const std::string good = TempPath("trunc_src.lcmlog");
    const std::vector<long> ends = WriteGoodLog(good, 2);
    const std::vector<char> bytes = ReadBytes(good);
    const std::string cut = TempPath("trunc.lcmlog");
    size_t read_with_warning = 0;
    for (size_t n = 4; n < bytes.size(); ++n) {  // below 4 bytes it is not recognised as a log
        if (!WorthTrying(n, ends))
            continue;
        WriteBytes(cut, bytes, n);
        std::vector<Episode> eps;
        ReadResult r = gmmrrt::learn::ReadDemoLog(cut, &eps);
        bool at_boundary = false;
        for (long e : ends)
            at_boundary = at_boundary || static_cast<long>(n) == e;
        bool warned = false;
        for (const std::string& w : r.warnings)
            warned = warned || (Contains(w, cut) && Contains(w, ": event ") && Contains(w, "truncated"));
        if (at_boundary) {
            if (warned)
                fail_msg("cut at %zu, an event boundary: warned of a truncation", n);
        } else if (r.ok) {
            if (!warned)
                fail_msg("cut at %zu: read without a truncation warning", n);
            ++read_with_warning;
        } else if (!Contains(r.error, cut) || !Contains(r.error, "truncated")) {
            fail_msg("cut at %zu: error does not name the cut: '%s'", n, r.error.c_str());
        }
        if (r.ok) {
            size_t total = 0;
            for (const Episode& e : eps)
                total += e.samples.size();
            assert_true(total <= 2 * 2);
        } else {
            assert_int_equal(eps.size(), 0);
        }
    }
    // The last episode's events come after the first one's: cuts there keep episode 1.
    assert_true(read_with_warning > 0);
    // A cut by one byte loses only the last event: the first episode is whole.
    WriteBytes(cut, bytes, bytes.size() - 1);
    std::vector<Episode> eps;
    ReadResult r = gmmrrt::learn::ReadDemoLog(cut, &eps);
    assert_true(r.ok);
    assert_true(eps.size() >= 1);
    assert_int_equal(eps[0].samples.size(), 2);
}

void test_log_flipped_bytes_never_crash_and_broken_headers_are_named(void** state) {
    (void)state;
    const std::string good = TempPath("flip_src.lcmlog");
    const std::vector<long> ends = WriteGoodLog(good, 2);
    const std::vector<char> bytes = ReadBytes(good);
    const std::string flipped = TempPath("flip.lcmlog");
    for (size_t i = 0; i < bytes.size(); ++i) {
        if (!WorthTrying(i, ends))
            continue;
        std::vector<char> b = bytes;
        b[i] = static_cast<char>(b[i] ^ 0x5A);
        WriteBytes(flipped, b, b.size());
        std::vector<Episode> eps;
        ReadResult r = gmmrrt::learn::ReadDemoLog(flipped, &eps);
        // Which event does byte i belong to, and is it in the sync word?
        long start = 0;
        int64_t event_no = 1;
        for (long e : ends) {
            if (static_cast<long>(i) < e)
                break;
            start = e;
            ++event_no;
        }
        if (static_cast<long>(i) < start + 4) {
            const std::string tag = ": event " + std::to_string(event_no) + " ";
            if (r.ok || !Contains(r.error, tag))
                fail_msg("flip at %zu: expected an error naming event %d, got ok=%d '%s'", i,
                         static_cast<int>(event_no), static_cast<int>(r.ok), r.error.c_str());
        }
        if (r.ok) {
            for (const Episode& e : eps) {
                assert_true(e.task >= 0 && e.task <= 2);
                assert_true(e.homotopy >= 0 && e.homotopy <= 3);
                for (const auto& s : e.samples) {
                    assert_true(std::isfinite(s.t_s) && s.t_s >= 0);
                    assert_true(std::isfinite(s.robot_x) && std::isfinite(s.robot_y) && std::isfinite(s.robot_yaw));
                    assert_true(std::isfinite(s.person_x) && std::isfinite(s.person_y) &&
                                std::isfinite(s.person_yaw));
                }
                for (size_t k = 1; k < e.samples.size(); ++k)
                    assert_true(e.samples[k].t_s > e.samples[k - 1].t_s);
            }
        } else {
            assert_true(Contains(r.error, flipped));
        }
    }
}

void test_log_garbage_file_is_not_a_log(void** state) {
    (void)state;
    const std::string path = TempPath("garbage.lcmlog");
    WriteText(path, "not a log\n");  // shorter than an event header
    std::vector<Episode> eps;
    ReadResult r = gmmrrt::learn::ReadDemoLog(path, &eps);
    assert_false(r.ok);
    assert_true(Contains(r.error, "not an LCM log"));
}

// ---------------------------------------------------------------- CSV

void test_csv_good_file_reads_episodes_and_estimates_heading(void** state) {
    (void)state;
    const std::string path = TempPath("good.csv");
    WriteText(path, kHeader +
                        "a_1,avoid,left,0.0,0.0,0.0,2.0,0.5,3.1\n"
                        "a_1,avoid,left,0.1,0.1,0.0,2.0,0.5,3.1\n"
                        "a_1,avoid,left,0.2,0.2,0.0,2.0,0.5,3.1\n"
                        "b_2,approach,frontal,0.0,1.0,1.0,0.0,0.0,0.0\r\n"
                        "b_2,approach,frontal,0.4,1.0,1.5,0.0,0.0,0.0\n"
                        "c_3,approach,right,0.0,5.0,5.0,0.0,0.0,0.0\n");
    std::vector<Episode> eps;
    ReadResult r = gmmrrt::learn::ReadEpisodes(path, &eps);
    assert_true(r.ok);
    assert_int_equal(eps.size(), 3);
    assert_string_equal(eps[0].id.c_str(), "a_1");
    assert_int_equal(eps[0].task, GMMRRT_TASK_AVOID);
    assert_int_equal(eps[0].homotopy, GMMRRT_HOMOTOPY_LEFT);
    assert_int_equal(eps[1].task, GMMRRT_TASK_APPROACH);
    assert_int_equal(eps[1].homotopy, GMMRRT_HOMOTOPY_FRONTAL);
    assert_int_equal(eps[2].homotopy, GMMRRT_HOMOTOPY_RIGHT);
    assert_int_equal(eps[0].samples.size(), 3);
    assert_float_equal(eps[0].samples[1].robot_x, 0.1, 1e-12);
    assert_float_equal(eps[0].samples[2].t_s, 0.2, 1e-12);
    assert_float_equal(eps[0].samples[2].person_yaw, 3.1, 1e-12);
    for (const auto& s : eps[0].samples)
        assert_float_equal(s.robot_yaw, 0.0, 1e-12);  // moving along +x
    for (const auto& s : eps[1].samples)
        assert_float_equal(s.robot_yaw, M_PI / 2, 1e-12);  // moving along +y
    assert_true(std::isnan(eps[2].samples[0].robot_yaw));  // a single sample: no motion
}

void test_csv_event_listed_twice_is_read_once_and_named(void** state) {
    (void)state;
    const std::string path = TempPath("repeats.csv");
    // a and b: one walker listed with both labels; c and d: c again with its label; e differs from c in
    // one position, so it is an event of its own.
    WriteText(path, kHeader +
                        "a,avoid,left,0.0,0.0,1.0,0.0,0.0,0.0\n"
                        "a,avoid,left,0.4,1.0,1.2,0.0,0.0,0.0\n"
                        "b,avoid,right,0.0,0.0,1.0,0.0,0.0,0.0\n"
                        "b,avoid,right,0.4,1.0,1.2,0.0,0.0,0.0\n"
                        "c,avoid,left,0.0,0.0,1.0,0.0,0.0,0.0\n"
                        "c,avoid,left,0.4,1.0,1.3,0.0,0.0,0.0\n"
                        "d,avoid,left,0.0,0.0,1.0,0.0,0.0,0.0\n"
                        "d,avoid,left,0.4,1.0,1.3,0.0,0.0,0.0\n"
                        "e,avoid,left,0.0,0.0,1.0,0.0,0.0,0.0\n"
                        "e,avoid,left,0.4,1.0,1.3,0.0,0.0,0.1\n");
    std::vector<Episode> eps;
    ReadResult r = gmmrrt::learn::ReadEpisodes(path, &eps);
    assert_true(r.ok);
    assert_int_equal(eps.size(), 3);
    assert_string_equal(eps[0].id.c_str(), "a");
    assert_string_equal(eps[1].id.c_str(), "c");
    assert_string_equal(eps[2].id.c_str(), "e");
    assert_int_equal(r.warnings.size(), 2);
    assert_string_equal(r.warnings[0].c_str(),
                        (path + ": episodes a and b are one event (the same person and positions at the same "
                                "times) with opposite homotopy labels (left, right); counted once, as a")
                            .c_str());
    assert_true(Contains(r.warnings[1], path + ": episodes c and d are one event"));
    assert_false(Contains(r.warnings[1], "labels"));
}

void ExpectCsvError(const std::string& name, const std::string& body, const std::string& expect) {
    const std::string path = TempPath(name);
    WriteText(path, body);
    std::vector<Episode> eps;
    ReadResult r = gmmrrt::learn::ReadEpisodeCsv(path, &eps);
    if (r.ok || !Contains(r.error, path) || !Contains(r.error, expect))
        fail_msg("%s: expected an error containing '%s', got ok=%d '%s'", name.c_str(), expect.c_str(),
                 static_cast<int>(r.ok), r.error.c_str());
    assert_int_equal(eps.size(), 0);
}

void test_csv_errors_name_the_line(void** state) {
    (void)state;
    const std::string ok_row = "a,avoid,left,0.0,0,0,1,1,0\n";
    ExpectCsvError("bad_header.csv", "episode,task\n" + ok_row, "line 1: header");
    ExpectCsvError("empty.csv", "", "line 1: empty file");
    ExpectCsvError("only_header.csv", kHeader, "no episodes");
    ExpectCsvError("columns.csv", kHeader + ok_row + "a,avoid,left,0.1,0,0,1,1\n", "line 3: 8 columns");
    ExpectCsvError("number.csv", kHeader + ok_row + "a,avoid,left,0.1,0,zero,1,1,0\n",
                   "line 3: column robot_y = 'zero'");
    ExpectCsvError("nan.csv", kHeader + ok_row + "a,avoid,left,0.1,nan,0,1,1,0\n", "line 3: column robot_x");
    ExpectCsvError("inf.csv", kHeader + ok_row + "a,avoid,left,0.1,0,0,inf,1,0\n", "line 3: column person_x");
    ExpectCsvError("empty_field.csv", kHeader + ok_row + "a,avoid,left,0.1,0,0,1,,0\n", "line 3: column person_y");
    ExpectCsvError("task.csv", kHeader + "a,wander,left,0.0,0,0,1,1,0\n", "line 2: unknown task 'wander'");
    ExpectCsvError("homotopy.csv", kHeader + "a,avoid,up,0.0,0,0,1,1,0\n", "line 2: unknown homotopy 'up'");
    // "all" selects every homotopy; on an episode it is no label (an unlabelled one is empty).
    ExpectCsvError("all.csv", kHeader + "a,avoid,all,0.0,0,0,1,1,0\n", "line 2: unknown homotopy 'all'");
    ExpectCsvError("time.csv", kHeader + ok_row + "a,avoid,left,0.0,0,0,1,1,0\n", "line 3: time does not increase");
    ExpectCsvError("relabel.csv", kHeader + ok_row + "a,avoid,right,0.1,0,0,1,1,0\n", "line 3: episode 'a' changes");
    ExpectCsvError("repeat.csv", kHeader + ok_row + "b,avoid,left,0.0,0,0,1,1,0\n" + "a,avoid,left,0.5,0,0,1,1,0\n",
                   "line 4: episode 'a' appears again");
    std::vector<Episode> eps;
    ReadResult r = gmmrrt::learn::ReadEpisodeCsv(TempPath("no_such_file.csv"), &eps);
    assert_false(r.ok);
    assert_true(Contains(r.error, "no_such_file.csv: cannot open"));
}

void test_read_episodes_picks_the_reader_by_content(void** state) {
    (void)state;
    const std::string log = TempPath("dispatch.csv");  // a log, whatever its name says
    WriteGoodLog(log);
    std::vector<Episode> eps;
    ReadResult r = gmmrrt::learn::ReadEpisodes(log, &eps);
    assert_true(r.ok);
    assert_int_equal(eps.size(), 2);
    assert_float_equal(eps[1].samples[0].robot_yaw, M_PI, 1e-12);  // from ROBOT_POSE, not estimated
}

void test_split_index_reads_and_rejects_duplicates(void** state) {
    (void)state;
    const std::string good = TempPath("index.csv");
    WriteText(good, "episode_id,task,split,other\na_1,avoid,train,x\nb_2,avoid,test,y\n");
    std::map<std::string, std::string> split;
    ReadResult r = gmmrrt::learn::ReadSplitIndex(good, &split);
    assert_true(r.ok);
    assert_int_equal(split.size(), 2);
    assert_string_equal(split["a_1"].c_str(), "train");
    assert_string_equal(split["b_2"].c_str(), "test");

    const std::string dup = TempPath("index_dup.csv");
    WriteText(dup, "episode_id,split\na_1,train\na_1,test\n");
    r = gmmrrt::learn::ReadSplitIndex(dup, &split);
    assert_false(r.ok);
    assert_true(Contains(r.error, "line 3: episode 'a_1' is listed twice"));
    assert_int_equal(split.size(), 2);  // unchanged

    const std::string nocol = TempPath("index_nocol.csv");
    WriteText(nocol, "episode_id,task\na_1,avoid\n");
    r = gmmrrt::learn::ReadSplitIndex(nocol, &split);
    assert_false(r.ok);
    assert_true(Contains(r.error, "no split column"));
}

// The synthesized logs in logs/demos/ (tools/synth_demonstrations.py) read with no warning: 9 episodes per
// file with the file's labels, and avoid demonstrations pass on their labelled side (features
// from the C core, as the learner will compute them).
void test_repository_demo_logs_read_with_their_labels(void** state) {
    (void)state;
    struct {
        const char* file;
        int task, homotopy;
    } const sets[] = {{"avoid_left", GMMRRT_TASK_AVOID, GMMRRT_HOMOTOPY_LEFT},
                      {"avoid_right", GMMRRT_TASK_AVOID, GMMRRT_HOMOTOPY_RIGHT},
                      {"approach_frontal", GMMRRT_TASK_APPROACH, GMMRRT_HOMOTOPY_FRONTAL},
                      {"approach_left", GMMRRT_TASK_APPROACH, GMMRRT_HOMOTOPY_LEFT},
                      {"approach_right", GMMRRT_TASK_APPROACH, GMMRRT_HOMOTOPY_RIGHT}};
    for (const auto& set : sets) {
        const std::string path = std::string(GMMRRT_DEMOS_DIR) + "/" + set.file + ".lcmlog";
        std::vector<Episode> eps;
        ReadResult r = gmmrrt::learn::ReadDemoLog(path, &eps);
        if (!r.ok || !r.warnings.empty())
            fail_msg("%s: ok=%d error='%s' warnings=%zu", path.c_str(), static_cast<int>(r.ok), r.error.c_str(),
                     r.warnings.size());
        assert_int_equal(eps.size(), 9);
        for (const Episode& e : eps) {
            assert_int_equal(e.task, set.task);
            assert_int_equal(e.homotopy, set.homotopy);
            double d_min = 1e9, theta_at_min = 0;
            for (const auto& s : e.samples) {
                const gmmrrt_pose_t person = {s.person_x, s.person_y, s.person_yaw};
                double d = 0, theta = 0;
                gmmrrt_features_from_xy(&person, s.robot_x, s.robot_y, &d, &theta);
                if (d < d_min) {
                    d_min = d;
                    theta_at_min = theta;
                }
            }
            assert_true(d_min > 0.45);
            if (set.task == GMMRRT_TASK_AVOID)
                assert_true((theta_at_min > 0) == (set.homotopy == GMMRRT_HOMOTOPY_LEFT));
        }
    }
}

void test_real_upo_csv_reads_with_its_index(void** state) {
    (void)state;
    const std::string dir = std::getenv("GMMRRT_REAL_DATA");
    const std::string csv = dir + "/upo_avoid_episodes.csv";
    std::vector<Episode> eps;
    ReadResult r = gmmrrt::learn::ReadEpisodes(csv, &eps);
    if (!r.ok)
        fail_msg("%s", r.error.c_str());
    std::map<std::string, std::string> split;
    r = gmmrrt::learn::ReadSplitIndex(dir + "/upo_avoid_index.csv", &split);
    if (!r.ok)
        fail_msg("%s", r.error.c_str());
    assert_int_equal(eps.size(), split.size());  // one index row per episode (README)
    for (const Episode& e : eps) {
        assert_true(split.count(e.id) == 1);
        assert_int_equal(e.task, GMMRRT_TASK_AVOID);
        assert_true(e.homotopy == GMMRRT_HOMOTOPY_LEFT || e.homotopy == GMMRRT_HOMOTOPY_RIGHT);
    }
    // The UCY files and their shared index read too, each episode listed in the index.
    std::vector<Episode> ucy;
    for (const char* name : {"/ucy_avoid_episodes.csv", "/ucy_approach_episodes.csv"}) {
        r = gmmrrt::learn::ReadEpisodes(dir + name, &ucy);
        if (!r.ok)
            fail_msg("%s", r.error.c_str());
    }
    r = gmmrrt::learn::ReadSplitIndex(dir + "/ucy_index.csv", &split);
    if (!r.ok)
        fail_msg("%s", r.error.c_str());
    assert_true(!ucy.empty());
    for (const Episode& e : ucy)
        assert_true(split.count(e.id) == 1);
}

}  // namespace

// Usage: test_demos_demo_io [real]. "real" runs only the real-data check and exits 77
// (CTest SKIP_RETURN_CODE) when GMMRRT_REAL_DATA does not hold the UPO files.
int main(int argc, char** argv) {
    char tmpl[] = "/tmp/gmmrrt_demo_io_XXXXXX";
    if (mkdtemp(tmpl) == nullptr) {
        std::perror("mkdtemp");
        return 1;
    }
    g_dir = tmpl;
    int failed = 0;
    if (argc > 1 && std::strcmp(argv[1], "real") == 0) {
        const char* real = std::getenv("GMMRRT_REAL_DATA");
        const std::string csv = std::string(real != nullptr ? real : "") + "/upo_avoid_episodes.csv";
        if (real == nullptr || access(csv.c_str(), R_OK) != 0) {
            std::printf("SKIP: real data not found (%s is not readable): set GMMRRT_REAL_DATA to the "
                        "folder of the real demonstrations\n", csv.c_str());
            std::filesystem::remove_all(g_dir);
            return 77;
        }
        const struct CMUnitTest tests[] = {cmocka_unit_test(test_real_upo_csv_reads_with_its_index)};
        failed = cmocka_run_group_tests(tests, nullptr, nullptr);
    } else {
        const struct CMUnitTest tests[] = {
            cmocka_unit_test(test_log_good_file_gives_labelled_paired_samples),
            cmocka_unit_test(test_log_pose_without_recent_person_is_skipped),
            cmocka_unit_test(test_log_nan_pose_and_backwards_time_are_skipped_with_warnings),
            cmocka_unit_test(test_log_missing_channels_are_errors),
            cmocka_unit_test(test_log_bad_demo_info_drops_its_episode),
            cmocka_unit_test(test_log_truncated_anywhere_reads_the_complete_events_with_a_warning),
            cmocka_unit_test(test_log_flipped_bytes_never_crash_and_broken_headers_are_named),
            cmocka_unit_test(test_log_garbage_file_is_not_a_log),
            cmocka_unit_test(test_csv_good_file_reads_episodes_and_estimates_heading),
            cmocka_unit_test(test_csv_errors_name_the_line),
            cmocka_unit_test(test_csv_event_listed_twice_is_read_once_and_named),
            cmocka_unit_test(test_read_episodes_picks_the_reader_by_content),
            cmocka_unit_test(test_split_index_reads_and_rejects_duplicates),
            cmocka_unit_test(test_repository_demo_logs_read_with_their_labels),
        };
        failed = cmocka_run_group_tests(tests, nullptr, nullptr);
    }
    std::filesystem::remove_all(g_dir);
    return failed;
}
