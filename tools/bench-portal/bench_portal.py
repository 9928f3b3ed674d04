#!/usr/bin/env python3
"""The robot's web page (docs/PORTAL.md): its figures measured against a running onboard product.

  bench_portal.py idle --pid PID --seconds S                   RSS and CPU of the onboard JVM while nobody looks
  bench_portal.py page --base URL --ca-file CA --account A --password P --pid PID --loads N
                       --goal-cmd '...' --watch S --poll-ms MS  page loads, the live update's delay, RSS/CPU watched

Standard library only (http.client, ssl): the figures are the server's, not a browser's rendering. Each prints one
JSON object on stdout.
"""
import argparse
import http.client
import json
import os
import re
import shlex
import ssl
import statistics
import subprocess
import sys
import time
import urllib.parse
from datetime import datetime

CLK_TCK = os.sysconf("SC_CLK_TCK")


def proc_sample(pid):
    """(VmRSS in kB, utime + stime in clock ticks) of a process."""
    with open(f"/proc/{pid}/status") as f:
        rss_kb = next(int(line.split()[1]) for line in f if line.startswith("VmRSS:"))
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return rss_kb, int(fields[11]) + int(fields[12])  # utime, stime: fields 14 and 15 of proc(5)


# The web service's own threads: Jetty's pool (acceptor, selector and the threads answering requests), its scheduler
# and its session housekeeper (names as /proc/PID/task/TID/comm shows them, cut to 15 characters)
PORTAL_THREADS = re.compile(r"^(qtp[0-9]+-|Scheduler-|Session-HouseKe)")


def portal_ticks(pid):
    """utime + stime of the web service's threads of PID (0 when it has none)."""
    total = 0
    for tid in os.listdir(f"/proc/{pid}/task"):
        try:
            with open(f"/proc/{pid}/task/{tid}/comm") as f:
                name = f.read().strip()
            if PORTAL_THREADS.match(name):
                with open(f"/proc/{pid}/task/{tid}/stat") as f:
                    fields = f.read().rsplit(")", 1)[1].split()
                total += int(fields[11]) + int(fields[12])
        except FileNotFoundError:
            pass  # a thread that ended meanwhile
    return total


def usage_over(pid, seconds, work=None):
    """RSS (mean, max, MB) and CPU (% of one core) of PID over SECONDS, sampled once a second; WORK runs between."""
    t0 = time.monotonic()
    _, ticks0 = proc_sample(pid)
    web0 = portal_ticks(pid)
    rss = []
    while time.monotonic() - t0 < seconds:
        if work:
            work()
        else:
            time.sleep(1.0)  # sampling period of /proc: nothing to synchronise with
        rss.append(proc_sample(pid)[0])
    _, ticks1 = proc_sample(pid)
    web1 = portal_ticks(pid)
    wall = time.monotonic() - t0
    return {"rss_mean_mb": statistics.mean(rss) / 1024, "rss_max_mb": max(rss) / 1024,
            "cpu_percent": 100.0 * (ticks1 - ticks0) / CLK_TCK / wall,
            "web_threads_cpu_percent": 100.0 * (web1 - web0) / CLK_TCK / wall, "seconds": wall, "samples": len(rss)}


def percentile(values, p):
    v = sorted(values)
    return v[min(len(v) - 1, int(round(p / 100.0 * (len(v) - 1))))]


class Page:
    """One person's browser on the page: a keep-alive TLS connection (the lab CA only) and the session cookie."""

    def __init__(self, base, ca_file):
        u = urllib.parse.urlsplit(base)
        self.host, self.port = u.hostname, u.port
        self.tls = ssl.create_default_context(cafile=ca_file) if u.scheme == "https" else None
        self.cookie = None
        self.conn = None

    def connect(self):
        if self.conn:
            self.conn.close()
        if self.tls:
            self.conn = http.client.HTTPSConnection(self.host, self.port, context=self.tls, timeout=10)
        else:
            self.conn = http.client.HTTPConnection(self.host, self.port, timeout=10)
        self.conn.connect()

    def request(self, method, path, body=None):
        """(status, headers, body, seconds to the status line, seconds to the body's end)."""
        headers = {"Cookie": self.cookie} if self.cookie else {}
        if body is not None:
            headers["Content-Type"] = "application/x-www-form-urlencoded"
        t0 = time.perf_counter()
        self.conn.request(method, path, body=body, headers=headers)
        r = self.conn.getresponse()
        t1 = time.perf_counter()
        data = r.read()
        t2 = time.perf_counter()
        return r.status, r.headers, data, t1 - t0, t2 - t0

    def login(self, account, password):
        self.connect()
        status, headers, body, _, _ = self.request("POST", "/login", urllib.parse.urlencode(
            {"account": account, "password": password}))
        if status != 303:
            sys.exit(f"log-in as {account} refused: {status} {body[:300]!r}")
        self.cookie = headers["Set-Cookie"].split(";", 1)[0]


def cmd_idle(a):
    print(json.dumps(usage_over(a.pid, a.seconds)))


def cmd_page(a):
    page = Page(a.base, a.ca_file)
    page.login(a.account, a.password)
    first, complete, fresh_first = [], [], []
    for i in range(a.loads):
        # a person opening the page: a new TLS connection, the page, then its parts on the same connection
        t0 = time.perf_counter()
        page.connect()
        status, _, html, ttfb, _ = page.request("GET", "/")
        if status != 200:
            sys.exit(f"GET / answered {status}")
        fresh_first.append(time.perf_counter() - t0)
        for part in ("/static/portal.css", "/static/portal.js", "/qr.png", "/api/status"):
            s, _, _, _, _ = page.request("GET", part)
            if s != 200:
                sys.exit(f"GET {part} answered {s}")
        complete.append(time.perf_counter() - t0)
        # the page again on the open connection: the server's own time to first byte
        _, _, _, ttfb_kept, _ = page.request("GET", "/")
        first.append(ttfb_kept)
    # the live update: the page's poll while the robot drives; each answer's pose is how old when it arrives
    subprocess.run(shlex.split(a.goal_cmd), check=True, stdout=subprocess.DEVNULL)
    ages, poses = [], set()

    def poll_once():
        t_end = time.monotonic() + 1.0
        while time.monotonic() < t_end:
            s, _, body, _, _ = page.request("GET", "/api/status")
            received = time.time()
            st = json.loads(body)
            pose = st.get("pose")
            if pose:
                stamp = datetime.fromisoformat(pose["time"].replace("Z", "+00:00")).timestamp()
                ages.append(received - stamp)
                poses.add((round(pose["x"], 3), round(pose["y"], 3)))
            time.sleep(a.poll_ms / 1000.0)  # the page's poll interval, as its script waits between requests

    page.connect()
    watched = usage_over(a.pid, a.watch, poll_once)
    print(json.dumps({
        "loads": a.loads,
        "first_byte_ms": {"p50": 1000 * percentile(first, 50), "p99": 1000 * percentile(first, 99)},
        "first_byte_new_tls_ms": {"p50": 1000 * percentile(fresh_first, 50), "p99": 1000 * percentile(fresh_first, 99)},
        "complete_ms": {"p50": 1000 * percentile(complete, 50), "p99": 1000 * percentile(complete, 99)},
        "update_age_ms": {"p50": 1000 * percentile(ages, 50), "p99": 1000 * percentile(ages, 99), "n": len(ages)},
        "poll_ms": a.poll_ms,
        "distinct_poses": len(poses),
        "watched": watched}))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    i = sub.add_parser("idle")
    i.add_argument("--pid", type=int, required=True)
    i.add_argument("--seconds", type=float, default=30)
    g = sub.add_parser("page")
    g.add_argument("--base", required=True)
    g.add_argument("--ca-file", required=True)
    g.add_argument("--account", required=True)
    g.add_argument("--password", required=True)
    g.add_argument("--pid", type=int, required=True)
    g.add_argument("--loads", type=int, default=200)
    g.add_argument("--goal-cmd", required=True)
    g.add_argument("--watch", type=float, default=20)
    g.add_argument("--poll-ms", type=int, default=250)
    a = p.parse_args()
    {"idle": cmd_idle, "page": cmd_page}[a.command](a)


if __name__ == "__main__":
    main()
