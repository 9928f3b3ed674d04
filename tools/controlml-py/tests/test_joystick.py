"""controlml.py's joystick: the cm.velocity payload (section 4 of docs/CONTROLML.md) as slixmpp sends it, the session's
schedule (twists at the rate, skipped ticks instead of bursts, the final stop, a refusal ends it) and its arguments.
No network: the robot's answers come from a recording coroutine."""

import asyncio
import math
import os
import sys
import time
import unittest
import xml.etree.ElementTree as ET
from datetime import datetime, timedelta, timezone

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
import controlml  # noqa: E402
import controlml_codec as cm  # noqa: E402


class Robot:
    """Answers cm.velocity sets after ``delay`` seconds; refuses the set number ``refuse_at`` (1-based)."""

    def __init__(self, delay=0.0, refuse_at=0):
        self.delay, self.refuse_at = delay, refuse_at
        self.received = []  # (monotonic time, decoded record)

    async def send(self, payload):
        record = cm.decode(cm.control_ml("set", "20261121:1", "cm.velocity", payload)).value
        self.received.append((time.monotonic(), record))
        if len(self.received) == self.refuse_at:
            raise controlml.Failure(controlml.EXIT_REFUSED, "refused: invalid-state")
        await asyncio.sleep(self.delay)


def twist(record):
    return record["linear"].value, record["angular"].value


class PayloadTest(unittest.TestCase):
    def test_twist_is_the_text_form_with_the_send_time(self):
        before = datetime.now(timezone.utc)
        payload = cm.encode_record("cm.velocity", cm.velocity(0.2, -0.5, cm.utc_time()))
        self.assertEqual("DataStream", cm.local(payload.tag))
        iq = controlml.Client("operator@sabot.local", "secret", plain=True).make_iq(
            ito="robot42@sabot.local/onboard", itype="set")
        iq.append(cm.control_ml("set", "20261121:7", "cm.velocity", payload))
        elem = cm.find_control_ml(ET.fromstring(str(iq)))  # as slixmpp writes it: xlink:href must survive
        value = cm.decode(elem).value
        self.assertEqual({"linear": cm.Measure(0.2, "m/s"), "angular": cm.Measure(-0.5, "rad/s")},
                         {k: value[k] for k in ("linear", "angular")})
        sent = datetime.strptime(value["time"], "%Y-%m-%dT%H:%M:%S.%fZ").replace(tzinfo=timezone.utc)
        self.assertTrue(before <= sent <= datetime.now(timezone.utc), value["time"])

    def test_time_token_has_microseconds_and_zone(self):
        self.assertEqual("2026-11-21T10:15:30.000042Z",
                         cm.utc_time(datetime(2026, 11, 21, 11, 15, 30, 42, tzinfo=timezone(timedelta(hours=1)))))

    def test_out_of_range_twists_are_refused(self):
        for v, w in ((10.5, 0), (-10.01, 0), (0, 20.5), (0, -21), (math.nan, 0), (0, math.inf)):
            with self.assertRaises(cm.PayloadError, msg=(v, w)):
                cm.velocity(v, w, cm.utc_time())
        self.assertEqual(10.0, cm.velocity(10, -20, cm.utc_time())["linear"])


class SessionTest(unittest.TestCase):
    def run_session(self, robot, rate, duration, v=0.2, w=0.5):
        loop = asyncio.new_event_loop()
        try:
            t0 = time.monotonic()
            report = loop.run_until_complete(controlml.joystick(robot.send, v, w, rate, duration))
            return report, time.monotonic() - t0
        finally:
            loop.close()

    def test_twists_at_the_rate_then_a_stop(self):
        robot = Robot()
        report, elapsed = self.run_session(robot, rate=20, duration=0.25)
        self.assertEqual((5, 0), (report.twists, report.skipped))
        self.assertEqual([(0.2, 0.5)] * 5 + [(0.0, 0.0)], [twist(r) for _, r in robot.received])
        self.assertEqual(6, len(report.round_trips_ms))
        # the stop waits for the end of the last period: the session lasts the duration, not less
        self.assertGreaterEqual(elapsed, 0.25)
        arrivals = [t for t, _ in robot.received]
        self.assertGreaterEqual(arrivals[4] - arrivals[0], 4 * 0.05 - 0.005)  # sleeps end no earlier than asked
        times = [r["time"] for _, r in robot.received]
        self.assertEqual(sorted(times), times)

    def test_slow_answers_skip_ticks_instead_of_bursting(self):
        robot = Robot(delay=0.12)  # an answer takes more than two periods of 50 ms
        report, _ = self.run_session(robot, rate=20, duration=0.5)
        self.assertGreater(report.skipped, 0)
        self.assertEqual(10, report.twists + report.skipped)
        self.assertEqual(report.twists + 1, len(robot.received))
        gaps = [b - a for (a, _), (b, _) in zip(robot.received, robot.received[1:])]
        self.assertGreaterEqual(min(gaps), 0.12)  # never two twists closer than an answer: no catch-up burst

    def test_a_refusal_ends_the_session_without_a_stop(self):
        robot = Robot(refuse_at=3)
        with self.assertRaises(controlml.Failure) as f:
            self.run_session(robot, rate=50, duration=1.0)
        self.assertEqual(controlml.EXIT_REFUSED, f.exception.status)
        self.assertEqual([(0.2, 0.5)] * 3, [twist(r) for _, r in robot.received])

    def test_percentile_is_nearest_rank(self):
        values = [float(i) for i in range(1, 101)]
        self.assertEqual((50.0, 99.0, 100.0), (controlml.percentile(values, 0.5), controlml.percentile(values, 0.99),
                                               controlml.percentile(values, 1.0)))
        self.assertTrue(math.isnan(controlml.percentile([], 0.5)))


class ArgumentsTest(unittest.TestCase):
    def exits(self, argv):
        with self.assertRaises(SystemExit) as e, open(os.devnull, "w") as null:
            err, sys.stderr = sys.stderr, null
            try:
                controlml.parse_args(argv)
            finally:
                sys.stderr = err
        return e.exception.code

    def test_bad_joystick_usage_exits_2(self):
        base = ["--password", "x", "joystick", "r@d"]
        for extra in (["0.2"], ["0.2", "x"], ["11", "0"], ["0", "--", "-20.5"], ["nan", "0"],
                      ["0.2", "0", "--rate", "0"], ["0.2", "0", "--rate", "101"], ["0.2", "0", "--rate", "nan"],
                      ["0.2", "0", "--duration", "0"], ["0.2", "0", "--duration", "inf"],
                      ["0.2", "0", "--duration", "nan"]):
            self.assertEqual(2, self.exits(base + extra), extra)

    def test_good_joystick_usage_parses(self):
        a = controlml.parse_args(["--password", "x", "joystick", "r@d", "0.1", "-0.5", "--rate", "20",
                                  "--duration", "10"])
        self.assertEqual(("joystick", 0.1, -0.5, 20.0, 10.0), (a.command, a.linear, a.angular, a.rate, a.duration))
        d = controlml.parse_args(["--password", "x", "joystick", "r@d", "0.1", "0"])
        self.assertEqual((10.0, 5.0), (d.rate, d.duration))


if __name__ == "__main__":
    unittest.main()
