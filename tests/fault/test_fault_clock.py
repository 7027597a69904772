"""fault.clock_*: no sender can drag gmmrrtd's time (docs/daemon.md, "Clock").

Each test plants a timing fault in the avoid traffic of test_fault_replays.base() and replays it
through the daemon deterministically (file:// in and out, log time = the recorder's event times,
iteration budget). The stamps a sender writes are the fault; the recorder's times stay honest:

  * one pose stamped an hour ahead: refused once (REJECT_TIME_FUTURE), nothing else changes;
  * a ratchet: 60 re-sends of the current goal within 0.13 s, each stamped 1.9 s later than the
    last (before, this moved the one shared clock ~114 s ahead: every pose looked stale, and a
    12 s replay ran 1 170 cycles): one cycle per period, no stop, no resync;
  * a first goal stamped near 2^53 us: no stop (before, every pose looked stale for good);
  * a people tracker whose clock is 0.6 s or 1.9 s ahead of localisation: no rejection, no stop,
    people planned around (before, 0.6 s made every pose stale forever);
  * every sender's clock stepped an hour ahead or back (an NTP step of the sensor computers,
    the recorder not): each source is refused until its own run of consistent off-clock stamps
    is time_resync_count long and spans time_resync_ms, then followed (one resync per source);
    plans resume and the cycle rate never changes.

Run: ctest --test-dir build -R '^fault\\.clock' --output-on-failure
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
INPUTS = ("ROBOT_POSE", "PEOPLE", "NAV_GOAL", "OBSTACLES")


def utime_of(data):
    return struct.unpack(">q", data[OFF_UTIME:OFF_UTIME + 8])[0]


def with_utime(data, utime):
    return data[:OFF_UTIME] + struct.pack(">q", utime) + data[OFF_UTIME + 8:]


def run(gmmrrtd, models, tmp_path, sc, check_log=None, expected=None):
    """Replays sc; checks plans against check_log (default: the replayed log). Returns
    (summary, failures, cycles)."""
    in_log, out_log = str(tmp_path / (sc.name + ".lcmlog")), str(tmp_path / "out.lcmlog")
    sc.write(in_log)
    run_log_clock(gmmrrtd, models, in_log, out_log, iterations=300)
    summary, failures = replay_check.check(check_log or in_log, out_log, rate_hz=10.0, robot_radius=0.3,
                                           person_radius=0.25, expected_rejected=expected)
    return summary, failures, replay_check.read_outputs(out_log)


def clean_log(tmp_path, name, **kw):
    path = str(tmp_path / (name + "_clean.lcmlog"))
    base(name + "_clean", **kw).write(path)
    return path


def no_stops(cycles):
    return [(c[1].utime, c[2].status) for c in cycles if c[2] is not None and c[2].num_waypoints == 0]


def test_one_pose_stamped_an_hour_ahead(gmmrrtd, models, tmp_path):
    sc = base("future_pose")
    x, y, yaw = ms.along([(0, 0), (2, 0)], 0.2, 1.55)
    sc.add(1.55, "ROBOT_POSE", ms.pose(1.55, x, y, yaw, utime=ms.us(1.55) + HOUR_US))
    summary, failures, cycles = run(gmmrrtd, models, tmp_path, sc, check_log=clean_log(tmp_path, "future_pose"),
                                    expected={"REJECT_TIME_FUTURE": 1})
    assert not failures, "\n".join(failures)
    assert summary["stops"] == 0, summary


def test_ratchet_of_goal_resends(gmmrrtd, models, tmp_path):
    sc = base("ratchet", duration_s=12.0)
    for k in range(1, 61):
        t = 3.0 + 0.13 * k / 60
        g = ms.goal(3.0, 8, 0, ms.AVOID).encode()
        sc.add(t, "NAV_GOAL", with_utime(g, ms.us(3.0) + k * 1_900_000))
    summary, failures, cycles = run(gmmrrtd, models, tmp_path, sc,
                                    check_log=clean_log(tmp_path, "ratchet", duration_s=12.0))
    assert not failures, "\n".join(failures)  # includes one cycle per period of the 12 s log
    rej = summary["rejected"]
    assert rej["REJECT_CLOCK_RESYNC"] == 0 and rej["REJECT_POSE_STALE"] == 0, rej
    assert rej["REJECT_TIME_FUTURE"] >= 55, rej
    assert summary["stops"] == 0, no_stops(cycles)
    assert 119 <= summary["cycles"] <= 121, summary


def test_far_future_first_goal(gmmrrtd, models, tmp_path):
    sc = base("far_first")
    g = with_utime(ms.goal(0.0, 8, 0, ms.AVOID).encode(), (1 << 53) - 1)
    sc.events.insert(0, (ms.us(0.0), -1, "NAV_GOAL", g))
    summary, failures, cycles = run(gmmrrtd, models, tmp_path, sc, check_log=clean_log(tmp_path, "far_first"),
                                    expected={})
    assert not failures, "\n".join(failures)
    assert summary["stops"] == 0, no_stops(cycles)


def skewed_tracker(gmmrrtd, models, tmp_path, skew_us):
    sc = base("skew")
    sc.events = [(u, o, c, with_utime(d, utime_of(d) + skew_us) if c == "PEOPLE" else d)
                 for u, o, c, d in sc.events]
    summary, failures, cycles = run(gmmrrtd, models, tmp_path, sc, check_log=clean_log(tmp_path, "skew"),
                                    expected={})
    assert not failures, "\n".join(failures)
    assert summary["stops"] == 0, no_stops(cycles)
    assert all(c[1].stale_inputs == 0 for c in cycles)


def test_tracker_clock_0_6_s_ahead(gmmrrtd, models, tmp_path):
    skewed_tracker(gmmrrtd, models, tmp_path, 600_000)


def test_tracker_clock_1_9_s_ahead(gmmrrtd, models, tmp_path):
    skewed_tracker(gmmrrtd, models, tmp_path, 1_900_000)


def stepped_senders(gmmrrtd, models, tmp_path, step_us, reason):
    at_s, duration = 2.0, 9.0
    sc = base("step", duration_s=duration)
    sc.events = [(u, o, c, with_utime(d, utime_of(d) + step_us) if u >= ms.us(at_s) else d)
                 for u, o, c, d in sc.events]
    # The checker reads the same messages unstepped: it judges plans, not clocks.
    summary, failures, cycles = run(gmmrrtd, models, tmp_path, sc,
                                    check_log=clean_log(tmp_path, "step", duration_s=duration))
    failures = [f for f in failures if "names pose utime" not in f]  # plans name the stepped pose stamps
    assert not failures, "\n".join(failures)
    rej = summary["rejected"]
    assert rej["REJECT_CLOCK_RESYNC"] == 4, rej  # each of the four sources once, on its own
    assert rej[reason] > 0, rej
    # One cycle per period throughout: the step moved no time base.
    assert 89 <= summary["cycles"] <= 91, summary
    # The pose is refused for about time_resync_ms (1 s): stops then, and only pose stops.
    stops = no_stops(cycles)
    assert all(st == 50 for _, st in stops), stops
    assert all(ms.us(at_s) <= u <= ms.us(at_s + 1.2) for u, _ in stops), stops
    # After the slowest source (1 Hz goal and obstacles: 5 messages over >= 1 s) resynchronised,
    # every cycle plans.
    after = [c for c in cycles if c[1].utime > ms.us(at_s + 4.5)]
    assert len(after) >= 20 and all(c[2] is not None and c[2].num_waypoints > 0 for c in after)


def test_every_sender_stepped_an_hour_ahead(gmmrrtd, models, tmp_path):
    stepped_senders(gmmrrtd, models, tmp_path, +HOUR_US, "REJECT_TIME_FUTURE")


def test_every_sender_stepped_an_hour_back(gmmrrtd, models, tmp_path):
    stepped_senders(gmmrrtd, models, tmp_path, -HOUR_US, "REJECT_TIME_BACKWARDS")
