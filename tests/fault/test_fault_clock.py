"""fault.clock_*: gmmrrtd's time guard (docs/daemon.md, "Clock steps").

Each test plants a timing fault in the avoid traffic of test_fault_replays.base(), replays it
through the daemon deterministically (file:// in and out, log clock, iteration budget), and
checks the outputs with tools/gmmrrt_tools/replay_check.py plus the clock-specific facts:

  * one pose stamped an hour ahead among good ones is rejected as REJECT_TIME_FUTURE exactly
    once and changes nothing else: no stop, one cycle per period, every plan valid (before the
    guard, it dragged the clock an hour ahead and every later pose was "backwards": stops until
    restart);
  * every channel stepped an hour ahead, or an hour back, from 2.0 s on: the messages off the
    clock are rejected (TIME_FUTURE or TIME_BACKWARDS) until the pose channel has disagreed
    time_resync_count times in a row, then the clock adopts the new time once
    (REJECT_CLOCK_RESYNC = 1) and plans resume on the new time line.

The expected counts are derived from the planted traffic, not written down.
Run one: ctest --test-dir build -R '^fault\\.clock' --output-on-failure
"""
import struct

from tests.common.daemon_fixture import run_log_clock
from test_fault_replays import base

from gmmrrt import planner_status_t
from gmmrrt_tools import replay_check
from gmmrrt_tools import scenario_logs as ms

R = planner_status_t
HOUR_US = 3600 * 10**6
OFF_UTIME = 8  # big-endian int64 right after the 8-byte fingerprint, in every input type
RESYNC_COUNT = 10  # the daemon's default time_resync_count, passed explicitly below
INPUTS = ("ROBOT_POSE", "PEOPLE", "NAV_GOAL", "OBSTACLES")


def utime_of(data):
    return struct.unpack(">q", data[OFF_UTIME:OFF_UTIME + 8])[0]


def with_utime(data, utime):
    return data[:OFF_UTIME] + struct.pack(">q", utime) + data[OFF_UTIME + 8:]


def run(gmmrrtd, models, tmp_path, sc, check_log=None):
    """Replays sc; checks plans against check_log (default: the replayed log). Returns
    (summary, failures, cycles)."""
    in_log, out_log = str(tmp_path / (sc.name + ".lcmlog")), str(tmp_path / "out.lcmlog")
    sc.write(in_log)
    run_log_clock(gmmrrtd, models, in_log, out_log, iterations=300,
                  extra=("--time-resync-count", str(RESYNC_COUNT)))
    summary, failures = replay_check.check(check_log or in_log, out_log, rate_hz=10.0, robot_radius=0.3,
                                           person_radius=0.25,
                                           expected_rejected={replay_check.REASONS[k]: v
                                                              for k, v in sc.expected.items()})
    return summary, failures, replay_check.read_outputs(out_log)


def test_one_pose_stamped_an_hour_ahead(gmmrrtd, models, tmp_path):
    sc = base("future_pose")
    x, y, yaw = ms.along([(0, 0), (2, 0)], 0.2, 1.55)
    sc.add(1.55, "ROBOT_POSE", ms.pose(1.55, x, y, yaw, utime=ms.us(1.55) + HOUR_US))
    sc.expect(R.REJECT_TIME_FUTURE, 1)
    # The checker reads the good traffic only: the daemon must have behaved as if the stray
    # pose never came (its utime would also stretch the checker's rate window by an hour).
    clean = base("future_pose_clean")
    clean_log = str(tmp_path / "clean.lcmlog")
    clean.write(clean_log)
    summary, failures, cycles = run(gmmrrtd, models, tmp_path, sc, check_log=clean_log)
    assert not failures, "\n".join(failures)
    assert summary["rejected"]["REJECT_TIME_FUTURE"] == 1, summary
    assert summary["rejected"]["REJECT_CLOCK_RESYNC"] == 0, summary
    assert summary["rejected"]["REJECT_TIME_BACKWARDS"] == 0, summary
    assert summary["stops"] == 0, summary
    after = [c for c in cycles if c[1].utime > ms.us(1.55)]
    assert len(after) >= 20 and all(c[2] is not None and c[2].num_waypoints > 0 for c in after), summary


def stepped(name, step_us, at_s=2.0):
    """base() traffic with every input message from at_s on moved by step_us. Returns the
    scenario, the expected rejections (reason, count) and the stepped pose utime that resyncs."""
    sc = base(name)
    events = []
    for utime, order, channel, data in sc.events:
        if utime >= ms.us(at_s):
            data = with_utime(data, utime_of(data) + step_us)
        events.append((utime, order, channel, data))
    sc.events = events
    # The pose channel is the first to disagree RESYNC_COUNT times in a row (10 Hz); everything
    # off the clock before its RESYNC_COUNT-th stepped pose is rejected.
    ordered = sorted(events, key=lambda e: (e[0], e[1]))
    poses = [e for e in ordered if e[2] == "ROBOT_POSE" and e[0] >= ms.us(at_s)]
    resync_event = poses[RESYNC_COUNT - 1]
    rejected = sum(1 for e in ordered if e[2] in INPUTS and ms.us(at_s) <= e[0] and
                   (e[0], e[1]) < (resync_event[0], resync_event[1]))
    return sc, rejected, utime_of(resync_event[3])


def check_step(gmmrrtd, models, tmp_path, sc, reason, n_rejected, resync_utime):
    sc.expect(reason, n_rejected)
    sc.expect(R.REJECT_CLOCK_RESYNC, 1)
    # The checker keeps a channel's messages in utime order (dropping older-than-last ones):
    # it reads the same messages ordered by their utime, so each time line is whole.
    by_utime = ms.Scenario(sc.name + "_by_utime", "", sc.duration_s)
    by_utime.events = [(utime_of(e[3]), e[1], e[2], e[3]) for e in sc.events]
    check_log = str(tmp_path / "by_utime.lcmlog")
    by_utime.write(check_log)
    summary, failures, cycles = run(gmmrrtd, models, tmp_path, sc, check_log=check_log)
    # The input spans an hour on two time lines: the checker's one-window rate rule does not
    # apply; the rate is checked per time line below. Every other check must pass.
    failures = [f for f in failures if " cycles for " not in f]
    assert not failures, "\n".join(failures)
    assert summary["rejected"]["REJECT_CLOCK_RESYNC"] == 1, summary
    assert n_rejected >= RESYNC_COUNT - 1
    after = [c for c in cycles if c[1].utime > resync_utime and c[1].utime - resync_utime < HOUR_US // 2]
    last_input = max(utime_of(e[3]) for e in sc.events if e[0] >= ms.us(2.0))  # on the new time line
    want = (last_input - resync_utime) // 100_000
    assert abs(len(after) - want) <= 1, "%d cycles after the resync, want %d" % (len(after), want)
    # Plans resume on the new time line: every cycle after the resync plans (no stop).
    assert all(c[2] is not None and c[2].num_waypoints > 0 for c in after), \
        [(c[1].utime, c[1].state, c[1].last_error) for c in after if c[2] is None or c[2].num_waypoints == 0]
    before = [c for c in cycles if ms.us(0.0) <= c[1].utime < ms.us(2.0) + 1]
    assert abs(len(before) - 20) <= 1, "%d cycles before the step" % len(before)


def test_every_channel_stepped_an_hour_ahead(gmmrrtd, models, tmp_path):
    sc, n, resync_utime = stepped("step_ahead", +HOUR_US)
    check_step(gmmrrtd, models, tmp_path, sc, R.REJECT_TIME_FUTURE, n, resync_utime)


def test_every_channel_stepped_an_hour_back(gmmrrtd, models, tmp_path):
    sc, n, resync_utime = stepped("step_back", -HOUR_US)
    check_step(gmmrrtd, models, tmp_path, sc, R.REJECT_TIME_BACKWARDS, n, resync_utime)
