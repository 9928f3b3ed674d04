"""The codec against the examples of docs/CONTROLML.md (read from the spec itself, so a changed example is noticed)
and against the rules of its sections 1, 3, 4, 7 and 8."""

import math
import os
import re
import sys
import unittest
import xml.etree.ElementTree as ET
from datetime import datetime, timezone

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
import controlml_codec as cm  # noqa: E402

SPEC = os.path.join(HERE, "..", "..", "..", "docs", "CONTROLML.md")


def spec_examples() -> list[str]:
    with open(SPEC, encoding="utf-8") as f:
        return re.findall(r"```xml\n(.*?)```", f.read(), re.S)


def spec_example(marker: str) -> ET.Element:
    """The spec's xml block containing ``marker``, parsed (several top-level elements are wrapped in <root/>)."""
    blocks = [b for b in spec_examples() if marker in b]
    assert len(blocks) == 1, f"{len(blocks)} xml examples in the spec contain {marker!r}"
    return ET.fromstring("<root xmlns='jabber:client'>" + blocks[0] + "</root>")


def same_tree(a: ET.Element, b: ET.Element) -> bool:
    """Structural equality: tags, attributes, children; text compared token by token, numbers by value (a writer may
    write 2.0E-4 or 0.0002)."""
    if a.tag != b.tag or a.attrib != b.attrib or len(a) != len(b):
        return False
    ta, tb = (a.text or "").strip(), (b.text or "").strip()
    if ta != tb:
        sa, sb = re.split(r"[, ]", ta), re.split(r"[, ]", tb)
        if len(sa) != len(sb):
            return False
        for x, y in zip(sa, sb):
            try:
                if float(x) != float(y):
                    return False
            except ValueError:
                if x != y:
                    return False
    return all(same_tree(x, y) for x, y in zip(a, b))


def fixed_clock(text):
    return lambda: datetime.fromisoformat(text).replace(tzinfo=timezone.utc)


class SpecExamples(unittest.TestCase):
    def setUp(self):
        self.section2 = spec_example("<iq type='get' id='a1'")
        self.request_iq, self.result_iq = list(self.section2)

    def test_get_request_is_the_spec_example(self):
        mine = cm.control_ml("get", "20261121:7", "cm.position")
        self.assertTrue(same_tree(mine, cm.find_control_ml(self.request_iq)), ET.tostring(mine))

    def test_xml_form_result_decodes_to_the_pose(self):
        answer = cm.decode(cm.find_control_ml(self.result_iq))
        self.assertEqual(("result", "20261121:7", "cm.position"), answer[:3])
        pose = answer.value
        self.assertEqual("2026-11-21T10:15:30.123456Z", pose["time"])
        self.assertEqual(cm.Measure(1.25, "m"), pose["x"])
        self.assertEqual(cm.Measure(-3.5, "m"), pose["y"])
        self.assertEqual(cm.Measure(0.785, "rad"), pose["theta"])
        self.assertEqual([{"xx": cm.Measure(0.01, "m2"), "xy": cm.Measure(0.001, "m2"),
                           "xtheta": cm.Measure(-2.0e-4, "m.rad"), "yy": cm.Measure(0.02, "m2"),
                           "ytheta": cm.Measure(3.0e-4, "m.rad"), "thetatheta": cm.Measure(4.0e-4, "rad2")}],
                         pose["covariance"])

    def test_text_form_result_is_the_same_record_as_the_xml_form(self):
        text_form = spec_example("<DataStream")
        self.assertEqual(cm.decode(cm.find_control_ml(self.result_iq)), cm.decode(text_form.find(f"{{{cm.CM_NS}}}control-ml")))

    def test_text_form_written_from_the_record_is_the_spec_example(self):
        spec = spec_example("<DataStream").find(f"{{{cm.CM_NS}}}control-ml")
        pose = cm.decode(spec).value
        values = {k: (v.value if isinstance(v, cm.Measure) else v) for k, v in pose.items() if k != "covariance"}
        values["covariance"] = [{k: v.value for k, v in pose["covariance"][0].items()}]
        mine = cm.control_ml("result", "20261121:7", "cm.position", cm.encode_record("cm.position", values))
        self.assertTrue(same_tree(mine, spec), ET.tostring(mine))

    def test_xml_form_written_from_the_record_is_the_spec_example(self):
        spec = cm.find_control_ml(self.result_iq)
        pose = cm.decode(spec).value
        values = {k: (v.value if isinstance(v, cm.Measure) else v) for k, v in pose.items() if k != "covariance"}
        values["covariance"] = [{k: v.value for k, v in pose["covariance"][0].items()}]
        mine = cm.control_ml("result", "20261121:7", "cm.position",
                             cm.encode_record("cm.position", values, text_form=False))
        self.assertTrue(same_tree(mine, spec), ET.tostring(mine))

    def test_error_example_gives_condition_reason_and_text(self):
        iq = spec_example("<iq type='error' id='a2'>")[0]
        refusal = cm.decode_error(iq)
        self.assertEqual(("not-acceptable", "wrong-unit"), refusal[:2])
        self.assertTrue(refusal.text.startswith("x is in 's', expected 'm'"), refusal.text)
        answer = cm.decode(cm.find_control_ml(iq))
        self.assertEqual(("error", "cm.goal"), (answer.type, answer.res))
        self.assertEqual(refusal, answer.value)

    def test_error_without_control_ml_is_read_from_the_error_element(self):
        iq = spec_example("<iq type='error' id='a2'>")[0]
        iq.remove(cm.find_control_ml(iq))
        self.assertEqual(("not-acceptable", "wrong-unit"), cm.decode_error(iq)[:2])
        self.assertTrue(cm.decode_error(iq).text.startswith("x is in 's'"))

    def test_unqualified_error_text_of_older_peers_is_read(self):
        iq = ET.fromstring("<iq xmlns='jabber:client' type='error' id='q'><error type='cancel'>"
                           "<item-not-found xmlns='urn:ietf:params:xml:ns:xmpp-stanzas'/>"
                           "<text xml:lang='en'>no such resource cm.nope</text>"
                           "<unknown-resource xmlns='urn:sabot:controlml:1:errors'/></error></iq>")
        self.assertEqual(cm.Refusal("item-not-found", "unknown-resource", "no such resource cm.nope"),
                         cm.decode_error(iq))

    def test_offline_command_message_carries_a_set(self):
        msg = spec_example("<message type='normal'")[0]
        elem = cm.find_control_ml(msg)
        self.assertEqual({"type": "set", "id": "20261121:9", "res": "cm.goal", "sent": "2026-11-21T09:14:03.512Z"},
                         elem.attrib)
        self.assertEqual("set", cm.decode(elem).type)


class RequestIdsTest(unittest.TestCase):
    def test_day_starts_at_millisecond_of_day_times_32_then_counts(self):
        ids = cm.RequestIds(fixed_clock("2026-11-21T00:00:01.500"))
        self.assertEqual(["20261121:48000", "20261121:48001"], [ids.next(), ids.next()])

    def test_new_day_restarts_the_counter(self):
        now = ["2026-11-21T23:59:59.999"]
        ids = cm.RequestIds(lambda: datetime.fromisoformat(now[0]).replace(tzinfo=timezone.utc))
        self.assertEqual("20261121:2764799968", ids.next())
        now[0] = "2026-11-22T00:00:00.002"
        self.assertEqual("20261122:64", ids.next())

    def test_ids_are_valid_and_invalid_ones_are_refused(self):
        for good in ("20261121:0", "20261121:42", "20240229:4294967295"):
            self.assertTrue(cm.is_request_id(good), good)
        for bad in ("20261121:07", "20261131:1", "20230229:1", "20261121:4294967296", "2026112:1", "20261121:-1",
                    "20261121:", "x20261121:1"):
            self.assertFalse(cm.is_request_id(bad), bad)


class WritingTest(unittest.TestCase):
    def test_goal_text_form_tokens_in_the_structure_order(self):
        stream = cm.encode_record("cm.goal", cm.goal(1.5, 4.0, 3.14, 0.1, 0.2))
        self.assertEqual("DataStream", cm.local(stream.tag))
        self.assertEqual(cm.RECORD_PREFIX + "cm.goal", stream[0].get(f"{{{cm.XLINK_NS}}}href"))
        self.assertEqual("value", stream[0].get("name"))
        self.assertEqual("1.5,4.0,3.14,0.1,0.2", stream.find(f"{{{cm.SWE_NS}}}values").text)

    def test_goal_xml_and_text_forms_decode_to_the_same_record(self):
        g = cm.goal(-2.25, 0.5, -1.0, 0.05, 0.3)
        text = cm.decode(cm.control_ml("set", "20261121:1", "cm.goal", cm.encode_record("cm.goal", g)))
        xml = cm.decode(cm.control_ml("set", "20261121:1", "cm.goal", cm.encode_record("cm.goal", g, False)))
        self.assertEqual(text, xml)
        self.assertEqual({k: cm.Measure(v, u) for (k, _, u), v in zip(cm.STRUCTURES["cm.goal"], g.values())},
                         text.value)

    def test_bad_goals_are_refused_before_sending(self):
        for args in ((math.nan, 0, 0), (0, math.inf, 0), (0, 0, 0, 0.0), (0, 0, 0, -1.0), (0, 0, 0, 0.1, 0.0),
                     (0, 0, 0, 0.1, 7.0)):
            with self.assertRaises(cm.PayloadError, msg=str(args)):
                cm.encode_record("cm.goal", cm.goal(*args))

    def test_missing_or_unknown_fields_are_refused(self):
        with self.assertRaisesRegex(cm.PayloadError, "missing theta"):
            cm.encode_record("cm.goal", {"x": 1, "y": 2, "positionTolerance": 1, "headingTolerance": 1})
        with self.assertRaisesRegex(cm.PayloadError, "unknown speed"):
            cm.encode_record("cm.velocity", {"time": "2026-11-21T10:00:00Z", "linear": 0, "angular": 0,
                                             "speed": 1})

    def test_mission_command_is_an_xml_record_with_category_boolean_quantity_text(self):
        rec = cm.encode_record("cm.mission", {"state": "paused", "maintenance": False, "progress": 0.0,
                                              "detail": "operator pause"})
        self.assertEqual("DataRecord", cm.local(rec.tag))
        self.assertEqual({"state": "paused", "maintenance": False, "progress": cm.Measure(0.0, "%"),
                          "detail": "operator pause"}, cm.decode_component(rec))

    def test_bad_attributes_are_refused(self):
        for args in (("put", "20261121:1", "cm.goal"), ("get", "20261121:01", "cm.goal"),
                     ("get", "20261121:1", "position"), ("get", "20261121:1", "cm.Position")):
            with self.assertRaises(cm.PayloadError, msg=str(args)):
                cm.control_ml(*args)


class ReadingTest(unittest.TestCase):
    def quantity(self, value, code="m"):
        return ET.fromstring(f"<Quantity xmlns='{cm.SWE_NS}'><uom code='{code}'/><value>{value}</value></Quantity>")

    def test_doubles_outside_xs_double_are_malformed(self):
        for bad in ("1,5", "0x1p3", "Infinity", "inf", "1.5.2", "", "e3", "1e"):
            with self.assertRaises(cm.PayloadError, msg=bad):
                cm.decode_component(self.quantity(bad))

    def test_special_values_are_parsed(self):
        self.assertTrue(math.isnan(cm.decode_component(self.quantity("NaN")).value))
        self.assertEqual(-math.inf, cm.decode_component(self.quantity("-INF")).value)
        self.assertEqual(1250.0, cm.decode_component(self.quantity(" 1.25E3 ")).value)

    def test_units_of_the_same_dimension_are_converted(self):
        self.assertEqual(cm.Measure(1.25, "m"), cm.decode_component(self.quantity("125", "cm")))
        self.assertAlmostEqual(math.pi, cm.decode_component(self.quantity("180", "deg")).value)
        self.assertEqual("rad", cm.decode_component(self.quantity("180", "deg")).uom)

    def test_time_without_zone_is_malformed(self):
        t = ET.fromstring(f"<Time xmlns='{cm.SWE_NS}' xmlns:x='{cm.XLINK_NS}'><uom x:href='{cm.GREGORIAN}'/>"
                          "<value>2026-11-21T10:15:30</value></Time>")
        with self.assertRaises(cm.PayloadError):
            cm.decode_component(t)

    def test_components_outside_the_subset_are_malformed(self):
        with self.assertRaisesRegex(cm.PayloadError, "not in ControlML's SWE subset"):
            cm.decode_component(ET.fromstring(f"<Vector xmlns='{cm.SWE_NS}'/>"))

    def test_records_nest_at_most_8_deep(self):
        def nested(depth):
            inner = f"<Count xmlns='{cm.SWE_NS}'><value>1</value></Count>"
            for _ in range(depth):
                inner = f"<DataRecord xmlns='{cm.SWE_NS}'><field name='f'>{inner}</field></DataRecord>"
            return ET.fromstring(inner)
        cm.decode_component(nested(8))
        with self.assertRaisesRegex(cm.PayloadError, "8 deep"):
            cm.decode_component(nested(9))

    def spec_text_form(self):
        return spec_example("<DataStream").find(f"{{{cm.CM_NS}}}control-ml")

    def test_text_form_refusals(self):
        def mutate(fn):
            elem = self.spec_text_form()
            fn(elem[0])
            return elem
        values = f"{{{cm.SWE_NS}}}values"
        cases = {
            "another resource's structure": lambda s: s[0].set(f"{{{cm.XLINK_NS}}}href", cm.RECORD_PREFIX + "cm.goal"),
            "too few tokens": lambda s: setattr(s.find(values), "text", "2026-11-21T10:15:30Z,1,2,3"),
            "a second block": lambda s: setattr(s.find(values), "text", s.find(values).text + " " + s.find(values).text),
            "another separator": lambda s: s[1][0].set("tokenSeparator", ";"),
            "a bad token": lambda s: setattr(s.find(values), "text", s.find(values).text.replace("1.25", "1,25x")),
            "no name": lambda s: s[0].attrib.pop("name"),
        }
        for what, fn in cases.items():
            with self.assertRaises(cm.PayloadError, msg=what):
                cm.decode(mutate(fn))

    def test_data_array_count_must_match_blocks(self):
        iq = spec_example("<iq type='get' id='a1'")[1]
        elem = cm.find_control_ml(iq)
        count = elem.find(f".//{{{cm.SWE_NS}}}elementCount/{{{cm.SWE_NS}}}Count/{{{cm.SWE_NS}}}value")
        count.text = "2"
        with self.assertRaisesRegex(cm.PayloadError, "elementCount 2 but 1 blocks"):
            cm.decode(elem)

    def test_a_set_carries_its_send_time_and_only_a_set(self):
        elem = cm.control_ml("set", "20261121:1", "cm.goal", cm.encode_record("cm.goal", cm.goal(1, 2, 0)),
                             sent="2026-11-28T10:15:30.125Z")
        self.assertEqual("2026-11-28T10:15:30.125Z", elem.get("sent"))
        self.assertRegex(cm.control_ml("set", "20261121:2", "cm.limits").get("sent"), r"Z$")  # now, in UTC
        self.assertIsNone(cm.control_ml("get", "20261121:3", "cm.goal").get("sent"))
        with self.assertRaises(cm.PayloadError):
            cm.control_ml("get", "20261121:4", "cm.goal", sent="2026-11-28T10:15:30Z")
        for bad in ("2026-11-28T10:15:30+01:00", "2026-11-28T10:15:30", "yesterday"):
            elem.set("sent", bad)
            with self.assertRaises(cm.PayloadError, msg=bad):
                cm.decode(elem)
        get = cm.control_ml("get", "20261121:5", "cm.position")
        get.set("sent", "2026-11-28T10:15:30Z")
        with self.assertRaises(cm.PayloadError):
            cm.decode(get)

    def test_extra_attribute_on_control_ml_is_refused(self):
        elem = cm.control_ml("get", "20261121:1", "cm.position")
        elem.set("extra", "1")
        with self.assertRaises(cm.PayloadError):
            cm.decode(elem)

    def test_presence_level(self):
        p = ET.fromstring("<presence xmlns='jabber:client'><show>dnd</show><presence-level "
                          "xmlns='urn:sabot:controlml:1' level='busy' mission='running' maintenance='false'/></presence>")
        self.assertEqual(cm.PresenceLevel("busy", "running", False), cm.decode_presence_level(p))
        self.assertIsNone(cm.decode_presence_level(ET.fromstring("<presence xmlns='jabber:client'/>")))

    def test_flatten_prints_paths_and_units(self):
        iq = spec_example("<iq type='get' id='a1'")[1]
        lines = dict(cm.flatten(cm.decode(cm.find_control_ml(iq)).value))
        self.assertEqual("1.25 m", lines["x"])
        self.assertEqual("-0.0002 m.rad", lines["covariance[0].xtheta"])



def battery_record(soc="42", soc_unit="%", volts="25.3", volt_unit="V", amps="0.61", docked="false",
                   charging="false", full="false") -> ET.Element:
    """A cm.battery record in the XML form, as section 4 lists its fields."""
    def q(name, value, unit):
        return (f"<swe:field name='{name}'><swe:Quantity><swe:uom code='{unit}'/><swe:value>{value}</swe:value>"
                f"</swe:Quantity></swe:field>")

    def b(name, value):
        return f"<swe:field name='{name}'><swe:Boolean><swe:value>{value}</swe:value></swe:Boolean></swe:field>"
    return ET.fromstring(
        f"<swe:DataRecord xmlns:swe='{cm.SWE_NS}' xmlns:xlink='{cm.XLINK_NS}'>"
        f"<swe:field name='time'><swe:Time><swe:uom xlink:href='{cm.GREGORIAN}'/>"
        "<swe:value>2026-12-01T10:00:00Z</swe:value></swe:Time></swe:field>"
        + q("stateOfCharge", soc, soc_unit) + q("voltage", volts, volt_unit) + q("current", amps, "A")
        + q("capacity", "10", "A.h") + b("docked", docked) + b("charging", charging) + b("full", full)
        + "</swe:DataRecord>")


class BatteryTest(unittest.TestCase):
    """Section 4's cm.battery as a client reads it."""

    def test_a_battery_reads_into_a_fraction_volts_amps_and_amp_hours(self):
        b = cm.battery(cm.decode_component(battery_record(volts="25300", volt_unit="mV", docked="true",
                                                          charging="true", amps="-4.5")))
        self.assertEqual({"time": "2026-12-01T10:00:00Z", "state_of_charge": 0.42, "voltage": 25.3, "current": -4.5,
                          "capacity": 10.0, "docked": True, "charging": True, "full": False}, b)
        self.assertEqual("battery 42.0 % 25.30 V -4.50 A of 10 Ah, docked, charging (at 2026-12-01T10:00:00Z)",
                         cm.battery_line(b))

    def test_a_reading_no_battery_gives_is_refused_naming_it(self):
        cases = [(dict(soc="120"), "stateOfCharge 120 % is outside 0..100"),
                 (dict(volts="0"), "voltage 0 is outside (0, 1000]"),
                 (dict(charging="true"), "charging or full away from a dock"),
                 (dict(docked="true", charging="true", full="true"), "both charging and full"),
                 (dict(volt_unit="m"), "voltage must be a Quantity in V")]
        for kwargs, message in cases:
            with self.assertRaises(cm.PayloadError, msg=str(kwargs)) as caught:
                cm.battery(cm.decode_component(battery_record(**kwargs)))
            self.assertIn(message, str(caught.exception))
        value = cm.decode_component(battery_record())
        del value["full"]
        with self.assertRaises(cm.PayloadError):
            cm.battery(value)



def passage_record(number="1", state="waiting") -> ET.Element:
    """A cm.passage record in the XML form, as section 4 lists its fields."""
    def t(name, value):
        return (f"<swe:field name='{name}'><swe:Time><swe:uom xlink:href='{cm.GREGORIAN}'/>"
                f"<swe:value>{value}</swe:value></swe:Time></swe:field>")
    return ET.fromstring(
        f"<swe:DataRecord xmlns:swe='{cm.SWE_NS}' xmlns:xlink='{cm.XLINK_NS}'>" + t("time", "2026-12-01T10:00:01Z")
        + f"<swe:field name='passage'><swe:Count><swe:value>{number}</swe:value></swe:Count></swe:field>"
        + f"<swe:field name='state'><swe:Category><swe:value>{state}</swe:value></swe:Category></swe:field>"
        + t("since", "2026-12-01T10:00:00Z") + "</swe:DataRecord>")


class PassageTest(unittest.TestCase):
    """Section 4's cm.passage as a client reads it (docs/PASSAGES.md)."""

    def test_a_claim_and_no_claim_read(self):
        self.assertEqual({"time": "2026-12-01T10:00:01Z", "passage": 1, "state": "waiting",
                          "since": "2026-12-01T10:00:00Z"}, cm.passage(cm.decode_component(passage_record())))
        self.assertEqual("none", cm.passage(cm.decode_component(passage_record("0", "none")))["state"])

    def test_what_the_spec_refuses_is_named(self):
        for number, state, message in (("0", "passing", "passage 0 with state 'passing'"),
                                       ("2", "none", "passage 2 with state 'none'"),
                                       ("65", "waiting", "passage must be a Count 0..64"),
                                       ("1", "queued", "state must be one of")):
            with self.assertRaises(cm.PayloadError, msg=state) as caught:
                cm.passage(cm.decode_component(passage_record(number, state)))
            self.assertIn(message, str(caught.exception))


if __name__ == "__main__":
    unittest.main()


class LeaseTest(unittest.TestCase):
    """Section 6's cm.telemetry record, written and read as the Java device writes and reads it."""

    def test_a_lease_is_a_record_of_streams_and_reads_back(self):
        payload = cm.lease(30, {"cm.position": 10, "cm.mission": 0.5})
        fields = [f.get("name") for f in payload]
        self.assertEqual(["lease", "count", "stream0", "stream1"], fields)
        self.assertEqual((30.0, {"cm.position": 10.0, "cm.mission": 0.5}),
                         cm.telemetry_rates(cm.decode_component(payload)))

    def test_other_units_of_frequency_and_time_are_converted(self):
        payload = cm.lease(1, {"cm.position": 30})
        ns = "{" + cm.SWE_NS + "}"
        payload.find(f".//{ns}field[@name='rate']/{ns}Quantity/{ns}uom").set("code", "/min")
        payload.find(f"{ns}field[@name='lease']/{ns}Quantity/{ns}uom").set("code", "min")
        self.assertEqual((60.0, {"cm.position": 0.5}), cm.telemetry_rates(cm.decode_component(payload)))

    def test_bad_leases_are_refused_before_sending(self):
        for seconds, rates in ((-1, {}), (3601, {}), (10, {"cm.position": 101}), (10, {"cm.position": -1}),
                               (10, {"Position": 1}), (10, {f"cm.r{i}": 1 for i in range(17)})):
            with self.subTest(seconds=seconds, rates=rates), self.assertRaises(cm.PayloadError):
                cm.lease(seconds, rates)

    def test_a_record_with_other_fields_is_refused(self):
        value = cm.decode_component(cm.lease(10, {"cm.position": 1}))
        value["extra"] = 1
        with self.assertRaises(cm.PayloadError):
            cm.telemetry_rates(value)



class MissionTest(unittest.TestCase):
    """Section 4's cm.mission with targets, written and read as the Java device writes and reads it."""

    def test_a_mission_is_the_four_fields_then_current_queued_count_and_targets(self):
        payload = cm.mission([cm.target(1, 2, 0, "pass"), cm.target(3, 2, 1.5, "wait", 4.5)], queue=True)
        self.assertEqual(["state", "maintenance", "progress", "detail", "current", "queued", "count", "target0",
                          "target1"], [f.get("name") for f in payload])
        value = cm.decode_component(payload)
        self.assertEqual("queued", value["state"])
        self.assertEqual((0, 0, [("pass", "pending"), ("wait", "pending")]), cm.mission_targets(value))
        self.assertEqual("running", cm.decode_component(cm.mission([cm.target(1, 1)]))["state"])

    def test_a_mission_without_targets_has_none(self):
        value = {"state": "paused", "maintenance": False, "progress": 3, "detail": ""}
        self.assertEqual((0, 0, []), cm.mission_targets(value))

    def test_bad_targets_and_missions_are_refused_before_sending(self):
        for args in ((1, 1, 0, "fly"), (1, 1, 0, "wait", 0), (1, 1, 0, "stop", 2), (1, 1, 0, "wait", 3601),
                     (1, 1, 0, "stop", 0, 0)):
            with self.subTest(args=args), self.assertRaises(cm.PayloadError):
                cm.target(*args)
        for targets in ([], [cm.target(1, 1)] * 65):
            with self.subTest(n=len(targets)), self.assertRaises(cm.PayloadError):
                cm.mission(targets)

    def test_a_record_whose_count_does_not_match_its_targets_is_refused(self):
        value = cm.decode_component(cm.mission([cm.target(1, 1), cm.target(2, 2)]))
        value["count"] = 3
        with self.assertRaises(cm.PayloadError):
            cm.mission_targets(value)
