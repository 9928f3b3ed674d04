#!/usr/bin/env python3
"""./sabot bench demo (product/bin/sabot-bench-demo): what ./sabot demo costs the machine, per process.

  bench_demo.py --robots N --idle S --drive S --sabot ./sabot --out bench.json

Runs `./sabot demo --headless --robots N --goal 6.0,2.8,0` (robot 1's goal is the pose it starts at, so the fleet
stands still), waits for the demo's screenshot line (everything is up), then samples /proc/PID/stat (utime, stime)
of each of the demo's processes: S seconds with the robots idle, then S seconds while every robot drives (robot i
goes back and forth between (6.0, y_i) and (4.5, y_i), a new goal every 10 s, over one operator session). Prints per
process and window the % of one core in user and kernel time, the machine's own busy share (/proc/stat, all
processes: other users' load shows there), and the onboard logs' "does not answer" lines; writes it all as JSON.
Stops the demo with SIGTERM (its own stop: robots, simulator, server, display). Needs controlml.py's venv.
Exit status: 0 measured and no board fault, 1 a fault line or a failure (why on stderr), 2 bad usage.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import re
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "controlml-py"))
import controlml  # noqa: E402
import controlml_codec as cm  # noqa: E402

START_X, START_Y, SPACING_Y, TURN_X = 6.0, 2.8, 0.8, 4.5   # ./sabot demo's robots (DEMO_START, the rig's spacing)
GOAL_EVERY_S = 10.0
READY_TIMEOUT_S = 400.0
TICK = os.sysconf("SC_CLK_TCK")
FAULT = re.compile(r"fault: |does not answer")   # ControlLoop's "fault: REASON - braking" and the board's name


def log(msg: str) -> None:
    print(f"[sabot] {msg}", file=sys.stderr, flush=True)


def cpu_times(pid: int) -> tuple[int, int] | None:
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii", errors="replace") as f:
            fields = f.read().rsplit(")", 1)[1].split()
        return int(fields[11]), int(fields[12])   # utime, stime (fields 14 and 15 of proc(5))
    except OSError:
        return None


def machine_times() -> tuple[int, int]:
    with open("/proc/stat", encoding="ascii") as f:
        v = [int(x) for x in f.readline().split()[1:]]
    idle = v[3] + v[4]
    return sum(v) - idle, sum(v)


def children(pid: int) -> list[int]:
    out = []
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                with open(f"/proc/{d}/stat", encoding="ascii", errors="replace") as f:
                    if int(f.read().rsplit(")", 1)[1].split()[1]) == pid:
                        out.append(int(d))
            except OSError:
                pass
    return out


def java_below(pid: int) -> int | None:
    """The first java process in pid's tree (the workbench's start script runs the JVM as a child)."""
    todo = [pid]
    while todo:
        p = todo.pop(0)
        try:
            if os.path.basename(os.readlink(f"/proc/{p}/exe")) == "java":
                return p
        except OSError:
            pass
        todo.extend(children(p))
    return None


def prosody_pid(run: str) -> int | None:
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                with open(f"/proc/{d}/cmdline", "rb") as f:
                    cmd = f.read().decode(errors="replace")
            except OSError:
                continue
            if "prosody" not in cmd or "--config" not in cmd:
                continue
            try:
                with open(f"/proc/{d}/environ", "rb") as f:
                    if run.encode() in f.read():   # sabot-xmpp gives the server its state folder
                        return int(d)
            except OSError:
                pass
    return None


def sample(procs: dict[str, int], seconds: float) -> dict:
    t0, m0 = time.monotonic(), machine_times()
    c0 = {n: cpu_times(p) for n, p in procs.items()}
    time.sleep(seconds)
    wall, m1 = time.monotonic() - t0, machine_times()
    c1 = {n: cpu_times(p) for n, p in procs.items()}
    out = {}
    for n in procs:
        if c0[n] and c1[n]:
            u, s = (c1[n][0] - c0[n][0]) / TICK / wall * 100, (c1[n][1] - c0[n][1]) / TICK / wall * 100
            out[n] = {"user": round(u, 1), "sys": round(s, 1), "total": round(u + s, 1)}
    out["machine (all processes)"] = {"busy_cores": round((m1[0] - m0[0]) / (m1[1] - m0[1]) * os.cpu_count(), 2)}
    return out


async def drive(args, seconds: float, procs: dict[str, int], demo: str) -> dict:
    # the operator's account as the demo gave it to its workbench
    with open(f"{demo}/secrets/xmpp-password", encoding="utf-8") as f:
        password = f.read().strip()
    with open(f"{demo}/workspace/.metadata/.plugins/org.eclipse.core.runtime/.settings/sabot.workbench.prefs",
              encoding="utf-8") as f:
        prefs = f.read()
    ca = re.search(r"xmpp\.caFile=(.*)", prefs).group(1)
    port = int(re.search(r"xmpp\.port=(\d+)", prefs).group(1))
    client = controlml.Client("operator@sabot.local", password, ca)
    await client.login("127.0.0.1", port, 30)
    robots = [f"sabot-0{i}@sabot.local/onboard" for i in range(1, args.robots + 1)]
    loop = asyncio.get_running_loop()
    window = loop.run_in_executor(None, sample, procs, seconds)
    sent = refused = 0
    k = 0
    while not window.done():
        for i, jid in enumerate(robots):
            x, theta = (TURN_X, 3.1416) if k % 2 == 0 else (START_X, 0.0)
            payload = cm.encode_record("cm.goal", cm.goal(x, START_Y + SPACING_Y * i, theta, 0.15, 0.2))
            try:
                await client.request(jid, "set", "cm.goal", payload, 10)
                sent += 1
            except controlml.Failure as e:
                refused += 1
                log(f"goal refused by {jid}: {e}")
        k += 1
        try:
            await asyncio.wait_for(asyncio.shield(window), GOAL_EVERY_S)
        except asyncio.TimeoutError:
            pass
    result = await window
    result["goals sent"] = {"sent": sent, "refused": refused}
    try:
        await asyncio.wait_for(client.disconnect(wait=0.5), 1.0)
    except asyncio.TimeoutError:
        pass
    return result


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--robots", type=int, required=True)
    ap.add_argument("--idle", type=float, required=True)
    ap.add_argument("--drive", type=float, required=True)
    ap.add_argument("--sabot", required=True)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    root = os.path.dirname(os.path.abspath(args.sabot))
    demo = os.path.join(root, "target", "demo")
    out_path = os.path.join(root, "target", "bench-demo.log")
    command = [args.sabot, "demo", "--headless", "--robots", str(args.robots), "--goal", f"{START_X},{START_Y},0",
               "--for", str(int(READY_TIMEOUT_S + args.idle + args.drive + 60))]
    log(f"{' '.join(command)} (its output in {out_path}); load average {open('/proc/loadavg').read().split()[0]}")
    os.makedirs(os.path.dirname(out_path), exist_ok=True)
    started = time.monotonic()
    with open(out_path, "w", encoding="utf-8") as out:
        demo_proc = subprocess.Popen(command, stdout=out, stderr=subprocess.STDOUT)
    procs: dict[str, int] = {}
    record: dict = {"command": " ".join(command), "robots": args.robots, "load_average_start": os.getloadavg()}
    try:
        text = ""
        while "screenshot: " not in text:
            if demo_proc.poll() is not None or time.monotonic() - started > READY_TIMEOUT_S:
                log(f"the demo did not come up; its output: {out_path}")
                return 1
            time.sleep(1)
            text = open(out_path, encoding="utf-8", errors="replace").read()
        record["ready_s"] = round(time.monotonic() - started, 1)
        procs["sabot-sim"] = int(re.search(r"simulator: .*\(pid (\d+)\)", text).group(1))
        for m in re.finditer(r"robot sabot-0(\d)@\S+ \(pid (\d+)\)", text):
            procs[f"onboard {m.group(1)}"] = int(m.group(2))
        wb = java_below(int(re.search(r"workbench started \(pid (\d+)\)", text).group(1)))
        if wb:
            procs["workbench"] = wb
        xvfb = re.search(r"Xvfb pid (\d+)", text)
        if xvfb:
            procs["Xvfb"] = int(xvfb.group(1))
        pros = prosody_pid(os.path.join(demo, "xmpp"))
        if pros:
            procs["prosody"] = pros
        log(f"all up after {record['ready_s']} s; processes {procs}; idle {args.idle:.0f} s")
        record["idle"] = sample(procs, args.idle)
        log(f"driving {args.drive:.0f} s")
        record["drive"] = asyncio.run(drive(args, args.drive, procs, demo))
    finally:
        demo_proc.send_signal(signal.SIGTERM)
        demo_proc.wait(60)
    faults = {}
    for i in range(1, args.robots + 1):
        lines = [ln.strip() for ln in open(f"{demo}/robot{i}/onboard.log", encoding="utf-8", errors="replace")
                 if FAULT.search(ln) and "status" not in ln]
        faults[f"onboard {i}"] = lines
    record["fault_lines"] = faults
    record["load_average_end"] = os.getloadavg()
    with open(args.out, "w", encoding="utf-8") as f:
        json.dump(record, f, indent=1)
    print(f"# {record['command']} (./sabot bench demo --robots {args.robots} --idle {args.idle:.0f} "
          f"--drive {args.drive:.0f}); load average {record['load_average_start'][0]:.1f} -> "
          f"{record['load_average_end'][0]:.1f}")
    print(f"{'process':<24} {'idle: user':>10} {'sys':>6} {'total':>6}   {'driving: user':>13} {'sys':>6} {'total':>6}")
    for n in procs:
        a, b = record["idle"].get(n), record["drive"].get(n)
        if a and b:
            print(f"{n:<24} {a['user']:>9.1f}% {a['sys']:>5.1f}% {a['total']:>5.1f}%   {b['user']:>12.1f}% "
                  f"{b['sys']:>5.1f}% {b['total']:>5.1f}%")
    print(f"{'machine, all processes':<24} {record['idle']['machine (all processes)']['busy_cores']:>9.2f} cores"
          f"{'':>17}{record['drive']['machine (all processes)']['busy_cores']:>9.2f} cores")
    print(f"goals sent while driving: {record['drive']['goals sent']['sent']}, refused "
          f"{record['drive']['goals sent']['refused']}")
    bad = {n: v for n, v in faults.items() if v}
    print(f"board faults in the onboard logs: {sum(len(v) for v in faults.values())}"
          + "".join(f"\n  {n}: {v[0]}" for n, v in bad.items()))
    print(f"JSON: {args.out}; demo logs: {demo}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
