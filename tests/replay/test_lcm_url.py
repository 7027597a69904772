"""replay.lcm_url: the live tests' private LCM URL (gmmrrt_tools.lcm_url) never lands on a port
a socket of this host is bound to, so a daemon of another test run cannot hear this one's sender."""
import random
import socket

from gmmrrt_tools import lcm_url


class Draws(random.Random):
    """Draws the given ports in order (then whatever the seed gives)."""

    def __init__(self, ports):
        super().__init__(1)
        self.ports = list(ports)

    def randrange(self, start, stop=None, step=1):
        return self.ports.pop(0) if self.ports else super().randrange(start, stop, step)


def port_of(url):
    return int(url.split(":")[2].split("?")[0])


def test_a_bound_port_is_skipped():
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        for port in range(lcm_url.PORTS[0], lcm_url.PORTS[1]):  # a free one of the range
            try:
                s.bind(("", port))
                break
            except OSError:
                continue
        taken = s.getsockname()[1]
        assert taken in lcm_url.bound_udp_ports()
        url = lcm_url.private_url(Draws([taken, taken]))
        assert port_of(url) != taken, url
        assert url.startswith("udpm://239.255.76.67:") and url.endswith("?ttl=0")
    finally:
        s.close()


def test_free_ports_are_drawn_from_the_range():
    ports = {port_of(lcm_url.private_url()) for _ in range(20)}
    assert all(lcm_url.PORTS[0] <= p < lcm_url.PORTS[1] for p in ports)
    assert not ports & lcm_url.bound_udp_ports()
