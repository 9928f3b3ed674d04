"""What controlml.py puts on the wire: the IQs it builds with slixmpp, serialised as slixmpp sends them, parsed back
and compared with the spec's examples (slixmpp drops a namespaced attribute whose namespace has no prefix: the text
form's xlink:href must survive). No network."""

import asyncio
import datetime
import os
import sys
import unittest
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, HERE)
import controlml  # noqa: E402
import controlml_codec as cm  # noqa: E402
from test_codec import same_tree, spec_example  # noqa: E402


class WireTest(unittest.TestCase):
    def setUp(self):
        self.loop = asyncio.new_event_loop()
        asyncio.set_event_loop(self.loop)
        self.client = controlml.Client("operator@sabot.local", "secret", plain=True)

    def tearDown(self):
        self.loop.close()

    def sent(self, kind, res, payload, rid="20261121:7"):
        iq = self.client.make_iq(ito="robot42@sabot.local/onboard", itype=kind)
        iq.append(cm.control_ml(kind, rid, res, payload))
        text = str(iq)  # slixmpp's serialisation, as written to the stream
        return ET.fromstring(text), text

    def test_an_entity_time_request_is_answered_with_utc(self):
        # slixmpp 1.17's own answer raises ValueError writing the zone offset; the client's answer must parse
        request = self.client.make_iq(ito="operator@sabot.local/cli", ifrom="robot42@sabot.local/onboard",
                                      itype="get")
        request.enable("entity_time")
        now = datetime.datetime(2026, 11, 28, 23, 7, 56, 532364, tzinfo=datetime.timezone.utc)
        reply = ET.fromstring(str(controlml.time_answer(request, now)))
        self.assertEqual(("result", "robot42@sabot.local/onboard"), (reply.get("type"), reply.get("to")))
        time = reply.find("{urn:xmpp:time}time")
        self.assertEqual("Z", time.findtext("{urn:xmpp:time}tzo"))
        self.assertEqual("2026-11-28T23:07:56.532364Z", time.findtext("{urn:xmpp:time}utc"))

    def test_get_is_the_spec_request(self):
        iq, _ = self.sent("get", "cm.position", None)
        spec = spec_example("<iq type='get' id='a1'")[0]
        self.assertEqual(("get", "robot42@sabot.local/onboard"), (iq.get("type"), iq.get("to")))
        self.assertTrue(same_tree(cm.find_control_ml(iq), cm.find_control_ml(spec)))

    def test_text_form_goal_keeps_its_xlink_reference(self):
        goal = cm.encode_record("cm.goal", cm.goal(1.5, 4.0, 3.14, 0.1, 0.2))
        iq, text = self.sent("set", "cm.goal", goal)
        self.assertIn("xlink:href=", text)
        elem = cm.find_control_ml(iq)
        self.assertEqual(cm.RECORD_PREFIX + "cm.goal", elem[0][0].get(f"{{{cm.XLINK_NS}}}href"))
        self.assertEqual({"x": cm.Measure(1.5, "m"), "y": cm.Measure(4.0, "m"), "theta": cm.Measure(3.14, "rad"),
                          "positionTolerance": cm.Measure(0.1, "m"), "headingTolerance": cm.Measure(0.2, "rad")},
                         cm.decode(elem).value)

    def test_xml_form_position_round_trips_to_the_spec_result(self):
        spec = cm.find_control_ml(spec_example("<iq type='get' id='a1'")[1])
        payload = spec[0]
        iq, _ = self.sent("result", "cm.position", payload)
        self.assertTrue(same_tree(cm.find_control_ml(iq), spec))

    def test_consecutive_requests_have_increasing_ids(self):
        a, b = self.client.ids.next(), self.client.ids.next()
        self.assertTrue(cm.is_request_id(a) and cm.is_request_id(b))
        self.assertEqual(int(a.split(":")[1]) + 1, int(b.split(":")[1]))


class StatusLineTest(unittest.TestCase):
    def test_watch_line_has_the_onboard_status_shape(self):
        pose = cm.Element("result", "20261121:1", "cm.position",
                          {"x": cm.Measure(1.2344, "m"), "y": cm.Measure(2.345, "m"), "theta": cm.Measure(0.123, "rad")})
        mission = cm.Element("result", "20261121:2", "cm.mission",
                             {"state": "running", "maintenance": False, "progress": cm.Measure(42.0, "%"),
                              "detail": ""})
        line = controlml.status_line(pose, mission, ("dnd", cm.PresenceLevel("busy", "running", False), ""))
        self.assertEqual("pose x=1.234 y=2.345 theta=0.123 | mission running 42% | presence busy", line)
        self.assertEqual("pose x=1.234 y=2.345 theta=0.123 | mission running 42% | presence offline",
                         controlml.status_line(pose, mission, None))


class ArgumentsTest(unittest.TestCase):
    def exits(self, argv):
        with self.assertRaises(SystemExit) as e, open(os.devnull, "w") as null:
            err, sys.stderr = sys.stderr, null
            try:
                controlml.parse_args(argv)
            finally:
                sys.stderr = err
        return e.exception.code

    def test_bad_usage_exits_2(self):
        base = ["--password", "x"]
        for argv in ([], ["get", "r@d", "cm.position"], base + ["get", "r@d", "position"],
                     base + ["set-goal", "r@d", "1", "2"], base + ["set-goal", "r@d", "1", "2", "nan"],
                     base + ["set-goal", "r@d", "1", "2", "0", "--tol", "0"], base + ["mission", "r@d", "stop"],
                     base + ["watch", "r@d", "--count", "-1"], base + ["frobnicate"]):
            self.assertEqual(2, self.exits(argv), argv)

    def test_good_usage_parses(self):
        a = controlml.parse_args(["--password", "x", "--port", "15322", "set-goal", "r@d", "1.5", "4", "3.14",
                                  "--tol", "0.2"])
        self.assertEqual(("set-goal", 1.5, 4.0, 3.14, 0.2, 15322), (a.command, a.x, a.y, a.theta, a.tol, a.port))


if __name__ == "__main__":
    unittest.main()
