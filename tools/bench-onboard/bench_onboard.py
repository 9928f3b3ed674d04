#!/usr/bin/env python3
"""The operator's side of ./sabot bench onboard (product/bin/sabot-bench-onboard), in controlml.py's venv.

  bench_onboard.py drive --minutes N --pid PID --log onboard.log --events drive.json --port P --ca-file CA.pem
                         --jid J --password W --robot R --controlml tools/controlml-py/controlml.py --sim-control C
      drives the running onboard product over ControlML for N minutes: goal 1, one joystick session (controlml.py
      joystick, a separate process and session), then a loop of goals between free points of the lab; samples the
      onboard's /proc/PID (RSS, CPU) once a second meanwhile. Writes what it did to drive.json. Both sessions use
      STARTTLS and trust only CA.pem, the private server's lab CA (the ca= of sabot-xmpp start's line: RIG_CA of
      product/bin/lib.sh); a refused certificate ends the drive (exit 1, controlml.py's line on stderr).
  bench_onboard.py report --minutes N --events drive.json --log onboard.log --truth truth.csv --out bench.json
      after the onboard product stopped: reads its log (the motion task's stop line, the goals' lines) and the drive's
      record, prints the table of figures and writes it as JSON.

Exit status: 0 done, 1 the drive or the figures failed (why on stderr), 2 bad usage.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import math
import os
import re
import signal
import sys
import time
from datetime import datetime
from typing import NamedTuple

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "controlml-py"))
import controlml  # noqa: E402
import controlml_codec as cm  # noqa: E402

# --- the drive -------------------------------------------------------------------------------------------------------
# Goal 1 of the issue: tests/sabot.system.tests NavigationTest (start 1.5,4.0,0; behind the lab's partition), with its
# tolerances.
GOAL_1 = (6.5, 3.0, 0.0)
POSITION_TOLERANCE, HEADING_TOLERANCE = 0.15, 0.2
# Free points of the lab map (onboard-bridge/maps/lab.pgm, 12 x 9 m), each >= 0.9 m from any wall or furniture; the
# legs go round the box (8.5-9.3, 1.6-2.2), through the gap between the partition's top and the north wall, and round
# the partition's south end. The loop ends on goal 1 from NavigationTest's start, so goal 1 repeats in long runs.
LOOP = ((10.5, 1.0, 0.0), (10.5, 7.5, 1.5708), (2.0, 7.5, 3.1416), (1.5, 4.0, 0.0), GOAL_1)
# One joystick session after goal 1: a circle of 0.3 m radius at goal 1, clear of everything.
JOYSTICK_LINEAR, JOYSTICK_ANGULAR, JOYSTICK_RATE, JOYSTICK_SECONDS = 0.15, 0.5, 19.1, 30.0
MISSION_POLL_S = 0.25  # cm.mission gets while a goal runs: the end is seen within this
SAMPLE_PERIOD_S = 1.0  # /proc samples of the onboard process
GOAL_TIMEOUT_S = 180.0  # a goal not ended by then is aborted (the robot's own settle timeout is 15 s)
IMU_SETTLE_S = 3.0  # localizer.imuSettleTime's default: the robot holds still this long after the motion task starts
REQUEST_TIMEOUT_S = 10.0

# --- the figures' goals (issue 13, "Figures") ------------------------------------------------------------------------
JITTER_P99_GOAL_US = 1000.0
TELEOP_P99_GOAL_MS = 25.0
GOAL_TIME_RATIO_GOAL = 1.25
RSS_GOAL_MB = 150.0
CPU_GOAL_PERCENT = 15.0
CPU_WINDOW_S = 10.0  # the CPU's worst window
PERIOD_US = 20000.0  # the control loop's period at motion.rate = 50 Hz
HISTOGRAM_LAST_BIN_US = 99999.0  # the onboard's MicrosHistogram: 1 us bins up to 100 ms, longer ones in the last

LOG_LINE = re.compile(r"^(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d+[+-]\d\d:\d\d|\S+Z) +(\w+) +\[(\w+)\] (.*)$")
STOP_LINE = re.compile(
    r"control loop (\d+) periods, start jitter p50 (\d+) us p99 (\d+) us max (\d+) us, work p50 ([\d.]+) ms "
    r"p99 ([\d.]+) ms, (\d+) overruns, (\d+) optional reads skipped; joystick twist to wheel set-point "
    r"p50 ([\d.]+) ms p99 ([\d.]+) ms max ([\d.]+) ms \(n (\d+)\)")
NEW_GOAL = re.compile(r"new goal \(([-\d.]+), ([-\d.]+), ([-\d.]+)\): path ([\d.]+) m")
GOAL_REACHED = re.compile(r"goal reached at \(([-\d.]+), ([-\d.]+), ([-\d.]+)\)")
MISSION_ENDED = re.compile(r"mission failed: |stopped: |fault: ")


class LogLine(NamedTuple):
    t: float  # epoch seconds
    level: str
    logger: str
    text: str


def read_log(path: str) -> list[LogLine]:
    out = []
    with open(path, encoding="utf-8", errors="replace") as f:
        for raw in f:
            m = LOG_LINE.match(raw.rstrip("\n"))
            if m:
                out.append(LogLine(datetime.fromisoformat(m.group(1).replace("Z", "+00:00")).timestamp(), m.group(2),
                                   m.group(3), m.group(4)))
    return out


def proc_sample(pid: int) -> tuple[float, float, float]:
    """(monotonic s, RSS MB, CPU s of user + system) of process ``pid``."""
    with open(f"/proc/{pid}/status", encoding="ascii") as f:
        rss_kb = next(int(line.split()[1]) for line in f if line.startswith("VmRSS:"))
    with open(f"/proc/{pid}/stat", encoding="ascii") as f:
        fields = f.read().rsplit(")", 1)[1].split()  # after the command name, which may hold spaces
    ticks = int(fields[11]) + int(fields[12])  # utime, stime: fields 14 and 15 of proc(5)
    return time.monotonic(), rss_kb / 1024.0, ticks / os.sysconf("SC_CLK_TCK")


def trapezoid_time(length: float, v_max: float, a_max: float) -> float:
    """Shortest time over ``length`` m from rest to rest at speed <= v_max and acceleration <= a_max."""
    if length >= v_max * v_max / a_max:
        return length / v_max + v_max / a_max
    return 2.0 * math.sqrt(length / a_max)


def loadavg() -> list[float]:
    with open("/proc/loadavg", encoding="ascii") as f:
        return [float(x) for x in f.read().split()[:3]]


class Drive:
    def __init__(self, args: argparse.Namespace):
        self.args = args
        self.client = controlml.Client(args.jid, args.password, args.ca_file)
        self.robot = ""
        self.samples: list[tuple[float, float, float]] = []
        self.record: dict = {"minutes": args.minutes, "goals": [], "joystick": None, "samples": [],
                             "localisation_checks": [], "load_average_start": loadavg()}
        self.sim: tuple[asyncio.StreamReader, asyncio.StreamWriter] | None = None

    async def truth(self) -> dict[str, float]:
        """Robot 1's true pose from sabot-sim's control channel ('truth 1' -> 'ok t=.. x=.. y=.. theta=..')."""
        if self.sim is None:
            self.sim = await asyncio.open_connection("127.0.0.1", self.args.sim_control)
        reader, writer = self.sim
        writer.write(b"truth 1\n")
        await writer.drain()
        answer = (await asyncio.wait_for(reader.readline(), REQUEST_TIMEOUT_S)).decode().strip()
        if not answer.startswith("ok "):
            raise controlml.Failure(1, f"sabot-sim's control channel answered 'truth 1' with '{answer}'")
        return {k: float(v) for k, v in (f.split("=", 1) for f in answer[3:].split())}

    async def check_localisation(self) -> None:
        """Records how far the robot's estimate is from the simulator's truth, and its uncertainty: the ceiling
        landmarks keep both bounded over the drive (without them the uncertainty grows with the distance driven and
        the robot stops at localizer.maxPositionSigma after some 15 m)."""
        estimate = await self.get("cm.position")
        truth = await self.truth()
        ex, ey = controlml.measure(estimate, "x"), controlml.measure(estimate, "y")
        self.record["localisation_checks"].append({
            "time": time.time(), "truth": [truth["x"], truth["y"], truth["theta"]],
            "estimate": [ex, ey, controlml.measure(estimate, "theta")],
            "error_m": math.hypot(ex - truth["x"], ey - truth["y"]),
            "sigma_xx": estimate["covariance"][0]["xx"].value, "sigma_yy": estimate["covariance"][0]["yy"].value})

    async def sample(self) -> None:
        next_t = time.monotonic()
        while True:
            try:
                self.samples.append(proc_sample(self.args.pid))
            except (OSError, StopIteration):
                raise controlml.Failure(1, f"the onboard process {self.args.pid} is gone") from None
            next_t += SAMPLE_PERIOD_S
            await asyncio.sleep(max(0.0, next_t - time.monotonic()))

    async def get(self, res: str):
        return (await self.client.request(self.robot, "get", res, None, REQUEST_TIMEOUT_S)).value

    async def mission_command(self, action: str) -> None:
        state = {"abort": "aborted"}[action]
        current = await self.get("cm.mission")
        payload = cm.encode_record("cm.mission", {"state": state, "maintenance": bool(current["maintenance"]),
                                                  "progress": controlml.measure(current, "progress"),
                                                  "detail": f"bench {action}"})
        await self.client.request(self.robot, "set", "cm.mission", payload, REQUEST_TIMEOUT_S)

    async def goal(self, x: float, y: float, theta: float, deadline: float | None) -> dict:
        """Sends a goal and waits for its mission to end (or ``deadline``, monotonic, when not None)."""
        entry = {"goal": [x, y, theta], "sent": time.time()}
        payload = cm.encode_record("cm.goal", cm.goal(x, y, theta, POSITION_TOLERANCE, HEADING_TOLERANCE))
        try:
            await self.client.request(self.robot, "set", "cm.goal", payload, REQUEST_TIMEOUT_S)
        except controlml.Failure as f:
            entry.update(state="refused", detail=str(f), ended=time.time())
            return entry
        give_up = time.monotonic() + GOAL_TIMEOUT_S
        while True:
            mission = await self.get("cm.mission")
            state = mission["state"]
            if state in ("done", "failed", "aborted", "idle"):
                entry.update(state=state, detail=mission.get("detail", ""), ended=time.time())
                return entry
            now = time.monotonic()
            if deadline is not None and now >= deadline or now >= give_up:
                await self.mission_command("abort")
                entry.update(state="interrupted" if now < give_up else "timeout", ended=time.time(),
                             detail="end of the drive" if now < give_up else f"not ended in {GOAL_TIMEOUT_S:g} s")
                return entry
            await asyncio.sleep(MISSION_POLL_S)

    async def joystick(self) -> dict:
        shown = ["./sabot", "controlml", "--jid", self.args.jid, "--password", self.args.password, "--port",
                 str(self.args.port), "--ca-file", self.args.ca_file, "joystick", self.args.robot,
                 f"{JOYSTICK_LINEAR:g}", f"{JOYSTICK_ANGULAR:g}", "--rate", f"{JOYSTICK_RATE:g}", "--duration",
                 f"{JOYSTICK_SECONDS:g}"]
        proc = await asyncio.create_subprocess_exec(sys.executable, self.args.controlml, *shown[2:],
                                                    stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE)
        try:
            out, err = await asyncio.wait_for(proc.communicate(), JOYSTICK_SECONDS + 60)
        except asyncio.TimeoutError:
            proc.kill()
            await proc.wait()
            return {"command": " ".join(shown), "status": None, "output": "no end within the session + 60 s"}
        finally:
            if proc.returncode is None:
                proc.kill()
        text = (out.decode() + err.decode()).strip()
        return {"command": " ".join(shown), "status": proc.returncode, "output": text}

    async def run(self) -> None:
        a = self.args
        await self.client.login("127.0.0.1", a.port, REQUEST_TIMEOUT_S)
        self.robot = await self.client.find_robot(a.robot, REQUEST_TIMEOUT_S)
        limits = await self.get("cm.limits")
        self.record["limits"] = {k: controlml.measure(limits, k) for k in limits}
        # the robot holds still while its inertial biases settle after the motion task's start: goal 1's time would
        # include that wait, which is not the navigation's
        started = [line.t for line in read_log(a.log) if line.text.startswith("motion task started")]
        if started:
            await asyncio.sleep(max(0.0, started[0] + IMU_SETTLE_S + 0.2 - time.time()))
        sampler = asyncio.ensure_future(self.sample())
        t0 = time.monotonic()
        self.record["drive_start"] = time.time()
        deadline = t0 + a.minutes * 60.0
        try:
            print(f"[bench] goal 1 {GOAL_1}", file=sys.stderr, flush=True)
            self.record["goals"].append(await self.goal(*GOAL_1, deadline=None))
            self.log_goal(self.record["goals"][-1])
            print(f"[bench] joystick {JOYSTICK_LINEAR:g} m/s {JOYSTICK_ANGULAR:g} rad/s at {JOYSTICK_RATE:g} Hz "
                  f"for {JOYSTICK_SECONDS:g} s", file=sys.stderr, flush=True)
            self.record["joystick"] = await self.joystick()
            print(f"[bench] {self.record['joystick']['output']}", file=sys.stderr, flush=True)
            i = 0
            while time.monotonic() < deadline:
                if sampler.done():
                    break
                await self.check_localisation()
                r = self.record["localisation_checks"][-1]
                print(f"[bench] the estimate is {r['error_m']:.3f} m off the truth (sigma x "
                      f"{math.sqrt(r['sigma_xx']):.3f} m)", file=sys.stderr, flush=True)
                g = LOOP[i % len(LOOP)]
                i += 1
                self.record["goals"].append(await self.goal(*g, deadline=deadline))
                self.log_goal(self.record["goals"][-1])
        finally:
            self.record["drive_end"] = time.time()
            self.record["load_average_end"] = loadavg()
            sampler.cancel()
            if self.sim is not None:
                self.sim[1].close()
            try:
                await sampler  # a Failure (the onboard is gone) surfaces here
            except asyncio.CancelledError:
                pass
            self.record["samples"] = [[t - t0, rss, cpu] for t, rss, cpu in self.samples]

    def log_goal(self, g: dict) -> None:
        print(f"[bench] goal ({g['goal'][0]:g}, {g['goal'][1]:g}, {g['goal'][2]:g}): {g['state']} after "
              f"{g['ended'] - g['sent']:.1f} s {g.get('detail', '')}", file=sys.stderr, flush=True)


async def drive_main(args: argparse.Namespace) -> int:
    d = Drive(args)
    try:
        await d.run()
        return 0
    except controlml.Failure as f:
        print(f"[bench] error: {f}", file=sys.stderr)
        d.record["error"] = str(f)
        return 1
    finally:
        with open(args.events, "w", encoding="utf-8") as f:
            json.dump(d.record, f, indent=1)
        d.client.cancel_connection_attempt()
        if d.client.transport is not None:
            try:
                await asyncio.wait_for(d.client.disconnect(wait=0.5), 1.0)
            except (asyncio.TimeoutError, asyncio.CancelledError):
                pass
        d.client.abort()


# --- the report ------------------------------------------------------------------------------------------------------
def goal_runs(lines: list[LogLine], limits: dict) -> list[dict]:
    """Each 'new goal' of the log with its end: the next 'goal reached', or another ending line, before the next goal."""
    runs = []
    v, a = limits["maxLinearSpeed"], limits["maxLinearAcceleration"]
    for i, line in enumerate(lines):
        m = NEW_GOAL.search(line.text)
        if not m:
            continue
        run = {"goal": [float(m.group(k)) for k in (1, 2, 3)], "path_m": float(m.group(4)), "reached": False}
        run["ideal_s"] = trapezoid_time(run["path_m"], v, a)
        for later in lines[i + 1:]:
            if NEW_GOAL.search(later.text):
                break
            if GOAL_REACHED.search(later.text):
                run.update(reached=True, time_s=later.t - line.t, ratio=(later.t - line.t) / run["ideal_s"])
                break
            if MISSION_ENDED.search(later.text) and later.logger == "motion":
                run["ended_by"] = later.text
                break
        runs.append(run)
    return runs


def verdict(figure: dict) -> str:
    if figure.get("saturated"):
        return "INVALID"
    return "n/a" if figure["met"] is None else ("met" if figure["met"] else "NOT MET")


def report_main(args: argparse.Namespace) -> int:
    with open(args.events, encoding="utf-8") as f:
        drive = json.load(f)
    lines = read_log(args.log)
    command = f"./sabot bench onboard --minutes {args.minutes}" + "".join(
        f" --jvm-option {o}" for o in args.jvm_options.split())
    figures: list[dict] = []
    problems: list[str] = []

    stop = next((STOP_LINE.search(l.text) for l in lines if STOP_LINE.search(l.text)), None)
    if stop is None:
        problems.append("no 'motion task stopped ... control loop ...' line in the onboard log")
    else:
        g = [float(x) for x in stop.groups()]
        loop = {"periods": int(g[0]), "jitter_p50_us": g[1], "jitter_p99_us": g[2], "jitter_max_us": g[3],
                "work_p50_ms": g[4], "work_p99_ms": g[5], "overruns": int(g[6]), "optional_reads_skipped": int(g[7])}
        saturated = loop["jitter_p50_us"] >= HISTOGRAM_LAST_BIN_US
        # a start later than two periods while no period's work (p99) lasted two: the same skip offset, not yet
        # saturating the histogram
        suspect = not saturated and loop["jitter_p99_us"] >= 2 * PERIOD_US and loop["work_p99_ms"] * 1000 < 2 * PERIOD_US
        if saturated:
            problems.append("the control loop's jitter histogram is saturated (p50 in its last bin, 100 ms): the "
                            "onboard's LoopTiming skipped its expected start ahead after overruns while the "
                            "fixed-rate executor catches up, so every later start counts as late by whole periods; "
                            "the jitter figure is not a measurement (see docs/ONBOARD.md)")
        figures.append({"figure": "control loop start jitter at 50 Hz", **loop, "goal": "p99 <= 1 ms",
                        "met": None if saturated else loop["jitter_p99_us"] <= JITTER_P99_GOAL_US,
                        "saturated": saturated, "suspect": suspect, "command": command,
                        "shown": f"p50 {g[1]:.0f} us, p99 {g[2]:.0f} us, max {g[3]:.0f} us over {int(g[0])} periods "
                                 f"(work p50 {g[4]:.1f} ms p99 {g[5]:.1f} ms, {int(g[6])} overruns, "
                                 f"{int(g[7])} optional reads skipped)"
                                 + ("; p99 over two periods while the work's p99 is under two: inflated by the "
                                    "skip offset (docs/ONBOARD.md)" if suspect else "")})
        tele = {"p50_ms": g[8], "p99_ms": g[9], "max_ms": g[10], "n": int(g[11])}
        js = drive.get("joystick") or {}
        figures.append({"figure": "joystick twist sent -> wheel set-point written", **tele, "goal": "p99 <= 25 ms",
                        "met": tele["p99_ms"] <= TELEOP_P99_GOAL_MS if tele["n"] else None,
                        "command": f"{command} (twists: {js.get('command', 'none sent')})",
                        "shown": f"p50 {g[8]:.1f} ms, p99 {g[9]:.1f} ms, max {g[10]:.1f} ms (n {int(g[11])})"})
        if js.get("status") != 0:
            problems.append(f"the joystick session failed: {js.get('output', 'not run')}")

    limits = drive.get("limits") or {}
    runs = goal_runs(lines, limits) if limits else []
    goal1 = [r for r in runs if r["goal"] == list(GOAL_1)]
    if not runs or runs[0]["goal"] != list(GOAL_1) or not runs[0]["reached"]:
        problems.append("goal 1 was not reached: " + (json.dumps(runs[0]) if runs else "no 'new goal' line"))
        figures.append({"figure": "time to reach goal 1 / ideal", "goal": "<= 1.25x", "met": False,
                        "command": command, "shown": "not reached"})
    else:
        first = runs[0]
        reached = [r for r in runs if r["reached"]]
        ratios = sorted(r["ratio"] for r in reached)
        figures.append({
            "figure": "time to reach goal 1 / ideal", "time_s": first["time_s"], "ideal_s": first["ideal_s"],
            "path_m": first["path_m"], "ratio": first["ratio"], "goal": "<= 1.25x",
            "met": first["ratio"] <= GOAL_TIME_RATIO_GOAL, "command": command,
            "goal1_ratios": [r["ratio"] for r in goal1 if r["reached"]],
            "all_goals": {"reached": len(reached), "sent": len(runs), "ratio_min": ratios[0],
                          "ratio_p50": controlml.percentile(ratios, 0.5), "ratio_max": ratios[-1]},
            "shown": f"{first['time_s']:.1f} s for a {first['path_m']:.2f} m path, ideal {first['ideal_s']:.1f} s "
                     f"(v {limits['maxLinearSpeed']:g} m/s, a {limits['maxLinearAcceleration']:g} m/s2): "
                     f"{first['ratio']:.2f}x; goal 1 again: "
                     + (", ".join(f"{r['ratio']:.2f}x" for r in goal1[1:] if r["reached"]) or "-")
                     + f"; all {len(reached)}/{len(runs)} goals reached: {ratios[0]:.2f}x.."
                       f"{ratios[-1]:.2f}x, p50 {controlml.percentile(ratios, 0.5):.2f}x"})

    samples = drive.get("samples") or []
    if len(samples) < 2:
        problems.append("fewer than 2 /proc samples of the onboard process")
    else:
        rss = [s[1] for s in samples]
        cpu_mean = (samples[-1][2] - samples[0][2]) / (samples[-1][0] - samples[0][0]) * 100.0
        windows = []
        j = 0
        for i, s in enumerate(samples):
            while s[0] - samples[j][0] > CPU_WINDOW_S:
                j += 1
            if s[0] - samples[j][0] >= CPU_WINDOW_S * 0.9:
                windows.append((s[2] - samples[j][2]) / (s[0] - samples[j][0]) * 100.0)
        rss_mean, rss_max = sum(rss) / len(rss), max(rss)
        cpu_max = max(windows) if windows else cpu_mean
        figures.append({"figure": "onboard RSS while driving", "mean_mb": rss_mean, "max_mb": rss_max,
                        "samples": len(samples), "goal": "<= 150 MB", "met": rss_max <= RSS_GOAL_MB,
                        "command": command, "shown": f"mean {rss_mean:.0f} MB, max {rss_max:.0f} MB "
                                                      f"({len(samples)} samples of /proc/PID/status VmRSS, 1 s apart)"})
        figures.append({"figure": "onboard CPU while driving (% of one core)", "mean_percent": cpu_mean,
                        "max_10s_percent": cpu_max, "goal": "<= 15 %", "met": cpu_mean <= CPU_GOAL_PERCENT,
                        "command": command,
                        "shown": f"mean {cpu_mean:.1f} %, worst 10 s {cpu_max:.1f} % (/proc/PID/stat utime+stime)"})
    figures.append({"figure": "Modbus transaction time / wire time", "goal": "<= 1.2x", "met": None,
                    "command": "./sabot bench modbus", "shown": "measured by ./sabot bench modbus, not here"})

    contacts = truth_contacts(args.truth)
    result = {"command": command, "minutes": args.minutes,
              "drive_s": drive.get("drive_end", 0) - drive.get("drive_start", 0),
              "load_average": {"start": drive.get("load_average_start"), "end": drive.get("load_average_end")},
              "cores": os.cpu_count(), "limits": limits, "contacts_in_truth": contacts,
              "figures": figures, "goals": drive.get("goals", []), "goal_runs": runs,
              "joystick": drive.get("joystick"), "problems": problems, "out": args.out}
    with open(args.out, "w", encoding="utf-8") as f:
        json.dump(result, f, indent=1)
    print_table(result)
    for p in problems:
        print(f"[sabot] problem: {p}", file=sys.stderr)
    return 1 if problems else 0


def truth_contacts(path: str) -> int | None:
    """The largest contact count of robot 1 in sabot-sim's truth file (None when unreadable)."""
    try:
        with open(path, encoding="ascii") as f:
            header = f.readline().strip().split(",")
            robot, contacts = header.index("robot"), header.index("collisions")
            best = 0
            for line in f:
                cols = line.split(",")
                if len(cols) > contacts and cols[robot].strip() == "1":
                    best = max(best, int(float(cols[contacts])))
            return best
    except (OSError, ValueError):
        return None


def print_table(r: dict) -> None:
    la = r["load_average"]
    print(f"\nSabot onboard figures: {r['drive_s'] / 60:.1f} min of driving on {r['cores']} core(s), load average "
          f"{' '.join(f'{x:.2f}' for x in la['start'] or [])} at the start, "
          f"{' '.join(f'{x:.2f}' for x in la['end'] or [])} at the end; contacts in the truth: {r['contacts_in_truth']}")
    width = max(len(f["figure"]) for f in r["figures"])
    for f in r["figures"]:
        print(f"  {f['figure']:<{width}}  {verdict(f):<7}  goal {f['goal']}")
        print(f"  {'':<{width}}  {f['shown']}")
        print(f"  {'':<{width}}  measured by: {f['command']}")
    print(f"  JSON: {r['out']}")


def parse_args(argv: list[str]) -> argparse.Namespace:
    p = argparse.ArgumentParser(prog="bench_onboard", description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="command", required=True)
    d = sub.add_parser("drive")
    r = sub.add_parser("report")
    for s in (d, r):
        s.add_argument("--minutes", type=int, required=True)
        s.add_argument("--events", required=True, help="the drive's record (JSON), written by drive")
        s.add_argument("--log", required=True, help="the onboard product's console log")
    d.add_argument("--pid", type=int, required=True, help="the onboard product's JVM")
    d.add_argument("--port", type=int, required=True)
    d.add_argument("--ca-file", required=True, metavar="PEM",
                   help="the private server's lab CA (ca= of sabot-xmpp start's line): the only CA trusted")
    d.add_argument("--jid", required=True)
    d.add_argument("--password", required=True)
    d.add_argument("--robot", required=True)
    d.add_argument("--controlml", required=True, help="path of controlml.py")
    d.add_argument("--sim-control", type=int, required=True, help="sabot-sim's control channel port")
    r.add_argument("--truth", required=True)
    r.add_argument("--out", required=True)
    r.add_argument("--jvm-options", default="", help="extra options the onboard's JVM ran with (shown in the command)")
    a = p.parse_args(argv)
    if a.minutes < 1:
        p.error("--minutes must be >= 1")
    return a


def main(argv: list[str]) -> int:
    args = parse_args(argv)
    if args.command == "report":
        return report_main(args)
    loop = asyncio.new_event_loop()
    asyncio.set_event_loop(loop)
    task = loop.create_task(drive_main(args))
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, task.cancel)
    try:
        return loop.run_until_complete(task)
    except asyncio.CancelledError:
        return 130
    finally:
        # slixmpp leaves its stream's filter task behind: end it here rather than in a warning at exit
        pending = [t for t in asyncio.all_tasks(loop) if not t.done()]
        for t in pending:
            t.cancel()
        loop.run_until_complete(asyncio.gather(*pending, return_exceptions=True))
        loop.close()


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
