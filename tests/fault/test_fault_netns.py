"""fault.netns_other_host: only local processes reach gmmrrtd with the default LCM URL and the
multicast route on lo (docs/hardening.md, "Who can steer the robot").

Two network namespaces joined by a virtual link play two hosts on one LAN: "robot" runs gmmrrtd
with the default URL's ttl=0 on a private port, "other" is another host on the link. Three facts:

  1. control: with the multicast route on the link (what a LAN-facing default route gives), a goal
     and poses published on "other" reach the daemon and it plans: ttl=0 alone does NOT keep other
     hosts out, it only keeps the daemon's own packets in;
  2. with `ip link set lo multicast on` and `ip route add 224.0.0.0/4 dev lo` on "robot" (the
     documented set-up), the same traffic from "other" never reaches the daemon (it stays idle),
     while a local publisher inside "robot" does (it plans);
  3. nothing the daemon publishes reaches "other" (a listener there records no PLANNER_STATUS).

Needs root and network namespaces (ip netns); creates and removes its own namespaces only, never
touches the host's. When namespaces are not permitted the test is reported SKIPPED with the
reason, never as passed.
"""
import os
import subprocess
import sys
import textwrap
import time

import pytest

from daemon_fixture import gmmrrtd_path

PORT = 7700 + os.getpid() % 200
URL_LOCAL = "udpm://239.255.76.67:%d?ttl=0" % PORT
URL_LAN = "udpm://239.255.76.67:%d?ttl=1" % PORT
NS_ROBOT, NS_OTHER = "gmmrrt_robot_%d" % os.getpid(), "gmmrrt_other_%d" % os.getpid()


def sh(*cmd, check=True):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=20, check=check)


def in_ns(ns, *cmd):
    return ["ip", "netns", "exec", ns, *cmd]


PUBLISH = textwrap.dedent("""
    import sys, time, lcm
    from gmmrrt import nav_goal_t, pose2d_t
    lc = lcm.LCM(sys.argv[1])
    end = time.time() + float(sys.argv[2])
    while time.time() < end:
        now = int(time.time() * 1e6)
        p = pose2d_t(); p.utime = now; p.x = 0.0; p.y = 0.0; p.frame = "map"
        lc.publish("ROBOT_POSE", p.encode())
        g = nav_goal_t(); g.utime = now; g.x = 3.0; g.y = 0.0; g.tolerance_m = 0.3; g.task = 0
        g.frame, g.goal_id, g.command = "map", 1, nav_goal_t.COMMAND_NEW
        lc.publish("NAV_GOAL", g.encode())
        time.sleep(0.05)
""")

LISTEN = textwrap.dedent("""
    import select, sys, time, lcm
    from gmmrrt import planner_status_t
    lc = lcm.LCM(sys.argv[1])
    seen = {"n": 0, "planning": 0}
    def on(ch, data):
        s = planner_status_t.decode(data)
        seen["n"] += 1
        seen["planning"] += s.state == planner_status_t.STATE_PLANNING
    lc.subscribe("PLANNER_STATUS", on)
    end = time.time() + float(sys.argv[2])
    while time.time() < end:
        r, _, _ = select.select([lc.fileno()], [], [], 0.05)
        if r:
            lc.handle()
    print(seen["n"], seen["planning"])
""")


@pytest.fixture
def two_hosts():
    if os.geteuid() != 0:
        pytest.skip("needs root to create network namespaces")
    made = []
    try:
        for ns in (NS_ROBOT, NS_OTHER):
            r = sh("ip", "netns", "add", ns, check=False)
            if r.returncode != 0:
                pytest.skip("network namespaces are not permitted here: %s" % r.stderr.strip())
            made.append(ns)
        veth_r, veth_o = "gr%d" % (os.getpid() % 100000), "go%d" % (os.getpid() % 100000)
        r = sh("ip", "link", "add", veth_r, "netns", NS_ROBOT, "type", "veth", "peer", "name", veth_o, "netns",
               NS_OTHER, check=False)
        if r.returncode != 0:
            pytest.skip("virtual links (veth) are not permitted here: %s" % r.stderr.strip())
        for ns, dev, addr in ((NS_ROBOT, veth_r, "10.77.0.1/24"), (NS_OTHER, veth_o, "10.77.0.2/24")):
            sh(*in_ns(ns, "ip", "link", "set", "lo", "up"))
            sh(*in_ns(ns, "ip", "addr", "add", addr, "dev", dev))
            sh(*in_ns(ns, "ip", "link", "set", dev, "up"))
            sh(*in_ns(ns, "ip", "link", "set", dev, "multicast", "on"))
        sh(*in_ns(NS_OTHER, "ip", "route", "add", "224.0.0.0/4", "dev", veth_o))
        yield veth_r
    finally:
        for ns in made:
            sh("ip", "netns", "del", ns, check=False)


def run_case(tmp_path, name, other_publishes, local_publishes, seconds=3.0):
    """gmmrrtd in "robot"; publishers as asked; listeners in both namespaces. Returns
    ((statuses, planning) seen in robot, (statuses, planning) seen in other)."""
    env = dict(os.environ)
    err = open(tmp_path / (name + ".stderr"), "w")
    daemon = subprocess.Popen(in_ns(NS_ROBOT, gmmrrtd_path(), "--lcm-url", URL_LOCAL, "--planner", "rrt-star",
                                    "--budget-ms", "30", "--log-level", "warn"), stderr=err, env=env)
    procs = []
    try:
        time.sleep(0.5)
        listen_robot = subprocess.Popen(in_ns(NS_ROBOT, sys.executable, "-c", LISTEN, URL_LOCAL, str(seconds)),
                                        stdout=subprocess.PIPE, text=True, env=env)
        listen_other = subprocess.Popen(in_ns(NS_OTHER, sys.executable, "-c", LISTEN, URL_LAN, str(seconds)),
                                        stdout=subprocess.PIPE, text=True, env=env)
        procs += [listen_robot, listen_other]
        if other_publishes:
            procs.append(subprocess.Popen(in_ns(NS_OTHER, sys.executable, "-c", PUBLISH, URL_LAN, str(seconds - 0.5)),
                                          env=env))
        if local_publishes:
            procs.append(subprocess.Popen(in_ns(NS_ROBOT, sys.executable, "-c", PUBLISH, URL_LOCAL,
                                                str(seconds - 0.5)), env=env))
        robot = tuple(int(v) for v in listen_robot.communicate(timeout=seconds + 15)[0].split())
        other = tuple(int(v) for v in listen_other.communicate(timeout=seconds + 15)[0].split())
    finally:
        for p in procs:
            if p.poll() is None:
                p.kill()
            p.wait()
        daemon.terminate()
        daemon.wait(timeout=10)
        err.close()
    return robot, other


def test_only_local_processes_reach_the_daemon(two_hosts, tmp_path):
    veth_r = two_hosts
    # 1. control: the group routed on the link, as a LAN default route does: the other host steers.
    sh(*in_ns(NS_ROBOT, "ip", "route", "add", "224.0.0.0/4", "dev", veth_r))
    robot, other = run_case(tmp_path, "open", other_publishes=True, local_publishes=False)
    assert robot[0] > 5, "the daemon published no status: the harness is broken"
    assert robot[1] > 0, "control failed: the other host's goal should reach a daemon whose group is on the link"
    # 2. the documented set-up: multicast on lo only.
    sh(*in_ns(NS_ROBOT, "ip", "route", "del", "224.0.0.0/4", "dev", veth_r))
    sh(*in_ns(NS_ROBOT, "ip", "link", "set", "lo", "multicast", "on"))
    sh(*in_ns(NS_ROBOT, "ip", "route", "add", "224.0.0.0/4", "dev", "lo"))
    robot, other = run_case(tmp_path, "closed", other_publishes=True, local_publishes=False)
    assert robot[0] > 5 and robot[1] == 0, "another host steered the daemon: %s" % (robot,)
    assert other == (0, 0), "the daemon's status left the host: %s" % (other,)
    robot, other = run_case(tmp_path, "local", other_publishes=False, local_publishes=True)
    assert robot[1] > 0, "a local publisher did not reach the daemon: %s" % (robot,)
    assert other == (0, 0), "the daemon's status left the host: %s" % (other,)
