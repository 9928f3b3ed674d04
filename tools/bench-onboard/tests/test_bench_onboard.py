"""bench_onboard.py's report: the onboard's log lines as its Java sources format them (read from the sources, so a
changed log format is noticed here), the goals' timing, the trapezoid ideal, the verdicts and the JSON; the drive's
lab CA option. No processes but openssl (a throw-away CA), no network."""

import io
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import unittest
from contextlib import redirect_stderr, redirect_stdout

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
import bench_onboard as bench  # noqa: E402

# the motion bundle's sources: its tasks (MotionTask) and its control loop (ControlLoop, LoopTiming, MicrosHistogram)
MOTION = os.path.join(HERE, "..", "..", "..", "bundles", "sabot.onboard.motion", "src", "sabot", "onboard", "motion")
SOURCES = {"MotionTask.java": "internal", "ControlLoop.java": "loop", "LoopTiming.java": "loop",
           "MicrosHistogram.java": "loop"}


def java_format(file: str, marker: str) -> str:
    """The Java string literal(s) of ``file`` concatenated in the statement that contains ``marker``."""
    with open(os.path.join(MOTION, SOURCES[file], file), encoding="utf-8") as f:
        text = f.read()
    start = text.index(marker)
    statement = text[text.rfind("(", 0, start):text.index(";", start)] if ";" in marker else \
        text[text.rfind("(", 0, start):text.index(");", start)]
    return "".join(re.findall(r'"((?:[^"\\]|\\.)*)"', statement))


def stop_line(loop: tuple, teleop: tuple) -> str:
    """The motion task's stop line as MotionTask, LoopTiming and MicrosHistogram write it (Java's %d/%.Nf are
    Python's)."""
    outer = java_format("MotionTask.java", "motion task stopped")
    summary = java_format("LoopTiming.java", "periods, start jitter") % loop
    histogram = java_format("MicrosHistogram.java", "p50 %.1f ms") % teleop
    return outer.replace("{}", summary, 1).replace("{}", histogram, 1)


LIMITS = {"maxLinearSpeed": 0.5, "maxAngularSpeed": 1.5, "maxLinearAcceleration": 0.5,
          "maxAngularAcceleration": 2.0}


def log(t: float, logger: str, text: str, level: str = "INFO") -> str:
    s = 5 + t
    return f"2026-11-23T13:00:{int(s):02d}.{int(round((s % 1) * 1000)):03d}Z {level:<5} [{logger}] {text}\n"


class TrapezoidTest(unittest.TestCase):
    def test_long_path_cruises(self):
        self.assertAlmostEqual(6.968 / 0.5 + 1.0, bench.trapezoid_time(6.968, 0.5, 0.5))

    def test_short_path_never_reaches_full_speed(self):
        self.assertAlmostEqual(2 * math.sqrt(0.2 / 0.5), bench.trapezoid_time(0.2, 0.5, 0.5))
        # continuous where the two cases meet (L = v^2 / a)
        self.assertAlmostEqual(bench.trapezoid_time(0.5, 0.5, 0.5), 2 * math.sqrt(0.5 / 0.5))


class LogTest(unittest.TestCase):
    def test_stop_line_as_the_java_sources_write_it_is_parsed(self):
        line = stop_line((30150, 12.0, 80.0, 900.0, 9.1, 14.0, 3, 123), (24.4, 30.7, 54.7, 201))
        m = bench.STOP_LINE.search(line)
        self.assertIsNotNone(m, line)
        self.assertEqual(("30150", "12", "80", "900", "9.1", "14.0", "3", "123", "24.4", "30.7", "54.7", "201"),
                         m.groups())

    def test_goal_lines_as_the_java_sources_write_them_are_matched(self):
        new = java_format("MotionTask.java", "new goal (").replace("{}", "6.500", 3).replace("{}", "6.968")
        reached = java_format("ControlLoop.java", "goal reached at").replace("{}", "6.523", 1).replace("{}", "2.9")
        self.assertEqual("6.968", bench.NEW_GOAL.search(new).group(4))
        self.assertIsNotNone(bench.GOAL_REACHED.search(reached), reached)

    def test_goal_runs_pair_each_goal_with_its_end(self):
        text = (log(0.0, "motion", "new goal (6.500, 3.000, 0.000): path 6.968 m")
                + log(1.0, "status", "status pose x=1 y=2 theta=0 v=0.40 | mission running 5% | mode follow")
                + log(21.5, "motion", "goal reached at (6.523, 2.943, 0.088)")
                + log(22.0, "motion", "new goal (10.500, 1.000, 0.000): path 0.200 m")
                + log(23.0, "motion", "fault: position uncertainty 0.50 m above the limit 0.50 m - braking", "WARN")
                + log(24.0, "motion", "new goal (1.500, 4.000, 0.000): path 3.000 m"))
        with tempfile.NamedTemporaryFile("w", suffix=".log", delete=False) as f:
            f.write(text)
        try:
            runs = bench.goal_runs(bench.read_log(f.name), LIMITS)
        finally:
            os.unlink(f.name)
        self.assertEqual(3, len(runs))
        self.assertTrue(runs[0]["reached"])
        self.assertAlmostEqual(21.5, runs[0]["time_s"], places=3)
        self.assertAlmostEqual(21.5 / 14.936, runs[0]["ratio"], places=3)
        self.assertFalse(runs[1]["reached"])
        self.assertIn("position uncertainty", runs[1]["ended_by"])
        self.assertEqual((False, None), (runs[2]["reached"], runs[2].get("ended_by")))


class ReportTest(unittest.TestCase):
    def report(self, jitter_p50: float, teleop_p99: float, jitter_p99: float = 900.0) -> tuple[int, dict, str]:
        with tempfile.TemporaryDirectory() as d:
            lines = (log(0.0, "motion", "new goal (6.500, 3.000, 0.000): path 6.968 m")
                     + log(18.0, "motion", "goal reached at (6.5, 3.0, 0.0)")
                     + log(30.0, "motion", stop_line((3000, jitter_p50, jitter_p99, max(jitter_p99, 1500.0), 9.1, 14.0, 0, 1),
                                                     (5.0, teleop_p99, 30.0, 200))))
            samples = [[float(i), 100.0 + i, 0.05 * i] for i in range(30)]  # 5 % of a core, 100..129 MB
            drive = {"limits": LIMITS, "samples": samples, "goals": [], "drive_start": 0.0, "drive_end": 60.0,
                     "load_average_start": [1.0, 1.0, 1.0], "load_average_end": [1.5, 1.0, 1.0],
                     "joystick": {"command": "./sabot controlml ... joystick", "status": 0, "output": "joystick: 200"}}
            paths = {k: os.path.join(d, k) for k in ("log", "events", "truth", "out")}
            with open(paths["log"], "w") as f:
                f.write(lines)
            with open(paths["events"], "w") as f:
                json.dump(drive, f)
            with open(paths["truth"], "w") as f:
                f.write("t_s,robot,x_m,y_m,theta_rad,v_m_s,omega_rad_s,wheel_left_rad_s,wheel_right_rad_s,"
                        "current_left_a,current_right_a,collisions\n0.000,1,1.5,4.0,0,0,0,0,0,0,0,0\n")
            args = bench.parse_args(["report", "--minutes", "1", "--events", paths["events"], "--log", paths["log"],
                                     "--truth", paths["truth"], "--out", paths["out"]])
            out, err = io.StringIO(), io.StringIO()
            with redirect_stdout(out), redirect_stderr(err):
                status = bench.report_main(args)
            with open(paths["out"]) as f:
                return status, json.load(f), out.getvalue() + err.getvalue()

    def test_figures_and_verdicts(self):
        status, r, text = self.report(jitter_p50=12.0, teleop_p99=30.0)
        self.assertEqual(0, status, text)
        figures = {f["figure"]: f for f in r["figures"]}
        self.assertEqual(True, figures["control loop start jitter at 50 Hz"]["met"])
        self.assertEqual(False, figures["joystick twist sent -> wheel set-point written"]["met"])
        goal = figures["time to reach goal 1 / ideal"]
        self.assertAlmostEqual(18.0 / (6.968 / 0.5 + 1.0), goal["ratio"], places=3)
        self.assertTrue(goal["met"])
        self.assertAlmostEqual(129.0, figures["onboard RSS while driving"]["max_mb"])
        self.assertAlmostEqual(5.0, figures["onboard CPU while driving (% of one core)"]["mean_percent"])
        self.assertEqual(0, r["contacts_in_truth"])
        self.assertIn("NOT MET  goal p99 <= 25 ms", text)
        self.assertIn("measured by: ./sabot bench onboard --minutes 1", text)

    def test_saturated_jitter_histogram_is_no_figure(self):
        status, r, text = self.report(jitter_p50=99999.0, teleop_p99=20.0)
        self.assertEqual(1, status)
        jitter = r["figures"][0]
        self.assertEqual((True, None), (jitter["saturated"], jitter["met"]))
        self.assertIn("INVALID", text)
        self.assertTrue(any("saturated" in p for p in r["problems"]))

    def test_jitter_beyond_two_periods_without_such_work_is_flagged(self):
        status, r, text = self.report(jitter_p50=6388.0, teleop_p99=20.0, jitter_p99=86391.0)
        self.assertEqual(0, status, text)
        jitter = r["figures"][0]
        self.assertEqual((False, True, False), (jitter["saturated"], jitter["suspect"], jitter["met"]))
        self.assertIn("skip offset", jitter["shown"])


class DriveArgsTest(unittest.TestCase):
    """drive's session trusts the private server's lab CA only (--ca-file, required)."""

    def test_the_drive_trusts_the_lab_ca_only(self):
        drive = ["drive", "--minutes", "1", "--events", "e.json", "--log", "o.log", "--pid", "1", "--port", "5222",
                 "--jid", "operator@sabot.local", "--password", "pw", "--robot", "sabot-01@sabot.local",
                 "--controlml", "controlml.py", "--sim-control", "1"]
        with self.assertRaises(SystemExit) as e, redirect_stderr(io.StringIO()):
            bench.parse_args(drive)
        self.assertEqual(2, e.exception.code)
        with tempfile.TemporaryDirectory() as d:
            ca = os.path.join(d, "ca.pem")
            subprocess.run(["openssl", "req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1",
                            "-nodes", "-days", "1", "-subj", "/CN=bench lab CA", "-addext",
                            "basicConstraints=critical,CA:TRUE", "-keyout", os.path.join(d, "ca.key"), "-out", ca],
                           check=True, capture_output=True)
            args = bench.parse_args(drive + ["--ca-file", ca])
            client = bench.Drive(args).client
            self.assertEqual(["bench lab CA"], [dict(x[0] for x in c["subject"])["commonName"]
                                                for c in client.get_ssl_context().get_ca_certs()])
            self.assertEqual((True, False), (client.enable_starttls, client.enable_plaintext))


if __name__ == "__main__":
    unittest.main()
