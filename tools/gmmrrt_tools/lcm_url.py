"""A UDP multicast LCM URL of one run's own, for the live tests (tests/replay, tests/fault) and
the daemon benchmark (gmmrrt_tools.bench.daemon).

Every live test runs gmmrrtd and a sender on one multicast group with ttl=0 (traffic stays on
the host). Two processes on the same port hear each other, whatever test they belong to: a
second daemon answers this test's goals, a second sender's messages are refused by this daemon
and counted. CTest's RESOURCE_LOCK serialises the live tests of one `ctest` run only; the same
tests of another checkout, another user's run or a daemon left over by a killed test share the
host too. A port taken from the pid modulo a few hundred, as the tests did, collided now and
then when several runs overlapped (a cancel answered by two daemons, a counter off by the other
sender's messages). Here the port is drawn at random from 12768 and skipped when a socket of
this host is bound to it already (/proc/net/udp, udp6): a daemon or a test that listens there.

Call private_url() once per daemon and use the URL for the daemon, its senders and its listeners.
"""
import random

# Below Linux's ephemeral range (32768-60999): no client socket sits on these by chance.
PORTS = (20000, 32768)
GROUP = "239.255.76.67"  # LCM's default group; the port is what separates the tests


def bound_udp_ports():
    """The local ports of this host's UDP sockets (IPv4 and IPv6)."""
    ports = set()
    for table in ("/proc/net/udp", "/proc/net/udp6"):
        try:
            with open(table) as f:
                next(f, None)  # header
                for line in f:
                    fields = line.split()
                    if len(fields) > 1 and ":" in fields[1]:
                        ports.add(int(fields[1].rsplit(":", 1)[1], 16))
        except OSError:
            continue  # no procfs (not Linux): the random draw alone
    return ports


def private_url(rng=None):
    """udpm://GROUP:PORT?ttl=0 with a port no socket of this host is bound to."""
    rng = rng or random.SystemRandom()
    taken = bound_udp_ports()
    for _ in range(1000):
        port = rng.randrange(*PORTS)
        if port not in taken:
            return "udpm://%s:%d?ttl=0" % (GROUP, port)
    raise RuntimeError("no free UDP port in %d-%d: %d are bound" % (PORTS[0], PORTS[1] - 1, len(taken)))
