#!/usr/bin/env python3
"""ControlML 1.0 interop suite: a second, independent implementation (slixmpp, written from docs/CONTROLML.md,
docs/controlml.xsd and docs/IDENTITY.md) against a ControlML device on a real XMPP server.

It expects a device prepared as tests/sabot.controlml.tests' InteropSuiteTest prepares it (see its Javadoc): every
resource served by a device that keeps what it is set, except cm.map (not served); cm.mission sets refused by the
word in their `detail`, and its get a mission of two targets (a wait reached, a dock active) with one queued; cm.position published with x = 1, 2, 3, ... at 20 Hz, leased up to 40 Hz for at most
10 s (cm.telemetry); the operator may set, the
viewer may get, the stranger nothing; its vCard and QR inventory published for the serial given.

One line per check, "PASS name" or "FAIL name: why"; the last line is "interop: N passed, N failed". Exit 0 only when
every check passed.
"""
from __future__ import annotations

import argparse
import asyncio
import base64
import hashlib
import os
import socket
import subprocess
import sys
import tempfile
import uuid
import xml.etree.ElementTree as ET
import zlib
from datetime import datetime, timedelta, timezone
from pathlib import Path

import slixmpp
from slixmpp.exceptions import IqError, IqTimeout

sys.path.insert(0, str(Path(__file__).resolve().parent))
import controlml as tool  # noqa: E402
import controlml_codec as cm  # noqa: E402

STANZAS = "urn:ietf:params:xml:ns:xmpp-stanzas"
TIMEOUT = 10.0
TELEMETRY_NODE = "urn:sabot:controlml:1:telemetry:cm.position"
# section 8: the error type of each RFC 6120 condition a device sends
ERROR_TYPE = {"bad-request": "modify", "item-not-found": "cancel", "service-unavailable": "cancel",
              "not-acceptable": "modify", "forbidden": "auth", "not-authorized": "auth",
              "unexpected-request": "wait", "resource-constraint": "wait"}
# section 8: the condition of each reason a device sends
CONDITION = {"bad-attributes": "bad-request", "bad-id": "bad-request", "type-mismatch": "bad-request",
             "malformed-payload": "bad-request", "payload-mismatch": "bad-request",
             "unknown-resource": "item-not-found", "unsupported-operation": "service-unavailable",
             "payload-too-large": "not-acceptable", "invalid-value": "not-acceptable", "wrong-unit": "not-acceptable",
             "stale-command": "not-acceptable", "access-denied": "forbidden", "set-not-permitted": "forbidden",
             "maintenance-lock": "not-authorized", "invalid-state": "unexpected-request",
             "busy": "resource-constraint", "device-fault": "service-unavailable"}
MAX_PAYLOAD = 65_536

results: list[tuple[bool, str]] = []


def check(name: str, ok: bool, why: str = "") -> bool:
    results.append((ok, name))
    print(("PASS " if ok else "FAIL ") + name + ("" if ok else ": " + why), flush=True)
    return ok


# ------------------------------------------------------------------------------------------------- section 1 size
def payload_size(elem: ET.Element) -> int:
    """Section 1's payload size of an element as ElementTree holds it (namespace declarations are not attributes)."""
    name = elem.tag.rsplit("}", 1)[-1]
    size = 2 * len(name) + 5
    for key, value in elem.attrib.items():
        size += len(key.rsplit("}", 1)[-1]) + len(value) + 4
    size += len(elem.text or "")
    for child in elem:
        size += payload_size(child) + len(child.tail or "")
    return size


def goal_xml(x: str = "1.5", unit: str = "m", pad: int = 0) -> str:
    fields = [("x", x, unit), ("y", "2", "m"), ("theta", "0", "rad"), ("positionTolerance", "0.05", "m"),
              ("headingTolerance", "0.1", "rad")]
    body = "".join(f"<field name='{n}'><Quantity><uom code='{u}'/><value>{v}</value></Quantity></field>"
                   for n, v, u in fields)
    return f"<DataRecord xmlns='{cm.SWE_NS}'>{' ' * pad}{body}</DataRecord>"


def control_ml(attributes: str, content: str = "", stamp: bool = True) -> ET.Element:
    """A control-ml element from raw attribute text; a set gets its send time (section 1) unless ``stamp`` is
    false or the text has one."""
    if stamp and "type='set'" in attributes and "sent=" not in attributes:
        attributes += f" sent='{cm.utc_time()}'"
    return ET.fromstring(f"<control-ml xmlns='{cm.CM_NS}' {attributes}>{content}</control-ml>")


class Answer:
    """An IQ answer as received: its type, the <error/>'s type, condition and reason, and the control-ml child."""

    def __init__(self, xml: ET.Element):
        self.xml = xml
        self.type = xml.get("type")
        self.cm = cm.find_control_ml(xml)
        error = next((c for c in xml if cm.local(c.tag) == "error"), None)
        self.error_type = error.get("type") if error is not None else None
        self.condition = self.reason = None
        for c in (error if error is not None else []):
            if cm._ns(c.tag) == STANZAS and cm.local(c.tag) != "text":
                self.condition = cm.local(c.tag)
            elif cm._ns(c.tag) == cm.ERRORS_NS:
                self.reason = cm.local(c.tag)

    def failure(self):
        f = self.cm.find(f"{{{cm.CM_NS}}}failure") if self.cm is not None else None
        return None if f is None else (f.get("condition"), f.get("reason"))

    def __str__(self) -> str:
        return ET.tostring(self.xml, encoding="unicode")[:600]


class Peer(tool.Client):
    def __init__(self, jid: str, password: str, ca_file: str):
        super().__init__(jid, password, ca_file)
        for p in ("xep_0030", "xep_0060", "xep_0115", "xep_0163", "xep_0054", "xep_0199"):
            self.register_plugin(p)
        self.items: list[tuple[str, float]] = []  # (control-ml id, x) of every cm.position item as delivered
        self.item_arrived = asyncio.Event()
        self.add_event_handler("pubsub_publish", self._on_item)
        self.messages: asyncio.Queue = asyncio.Queue()
        self.add_event_handler("message", lambda m: self.messages.put_nowait(m))

    def _on_item(self, msg) -> None:
        # the raw XML: iterating slixmpp's items stanza inside its own event handler never ends
        event = "{http://jabber.org/protocol/pubsub#event}"
        items = msg.xml.find(f"{event}event/{event}items")
        if items is None or items.get("node") != TELEMETRY_NODE:
            return
        for item in items.findall(f"{event}item"):
            elem = item.find(f"{{{cm.CM_NS}}}control-ml")
            if elem is None:
                continue
            try:
                e = cm.decode(elem)
            except cm.PayloadError:
                continue
            self.items.append((e.id, e.value["x"].value))
            self.item_arrived.set()

    async def raw(self, to: str, itype: str, elem: ET.Element) -> Answer:
        iq = self.make_iq(ito=to, itype=itype)
        iq.append(elem)
        try:
            return Answer((await iq.send(timeout=TIMEOUT)).xml)
        except IqError as e:
            return Answer(e.iq.xml)


async def online(jid: str, password: str, server: str, port: int, ca_file: str, interest: bool = False) -> Peer:
    peer = Peer(jid, password, ca_file)
    if interest:  # section 6 step 1: +notify in the caps of the initial presence

        async def add_interest(_event):
            peer.plugin["xep_0163"].add_interest(TELEMETRY_NODE, jid=peer.boundjid)
            await peer.plugin["xep_0115"].update_caps(peer.boundjid, broadcast=False)

        peer.add_event_handler("session_bind", add_interest)
    await peer.login(server, port, TIMEOUT)
    return peer


# ------------------------------------------------------------------------------------------------- checks
def refusal(name: str, a: Answer, reason: str, echo: bool = True) -> None:
    condition = CONDITION[reason]
    ok = a.type == "error" and a.condition == condition and a.reason == reason \
        and a.error_type == ERROR_TYPE[condition]
    if echo:
        ok = ok and a.cm is not None and a.cm.get("type") == "error" and a.failure() == (condition, reason)
    else:
        ok = ok and a.cm is None
    check(f"{name} -> {condition}/{reason}, error type {ERROR_TYPE[condition]}"
          + ("" if echo else ", <error/> only"), ok, str(a))


async def get_set(op: Peer, robot: str) -> None:
    a = await op.raw(robot, "get", cm.control_ml("get", op.ids.next(), "cm.position"))
    value = cm.decode(a.cm).value if a.cm is not None else None
    check("get cm.position (answer in the text form)", a.type == "result" and value is not None
          and a.cm.find(f"{{{cm.SWE_NS}}}DataStream") is not None and "covariance" in value, str(a))
    a = await op.raw(robot, "get", cm.control_ml("get", op.ids.next(), "cm.pid"))
    check("get cm.pid (answer in the XML form, a DataArray)", a.type == "result" and a.cm is not None
          and isinstance(cm.decode(a.cm).value.get("gains"), list), str(a))
    for text_form, x in ((False, 2.5), (True, -1.25)):
        form = "text" if text_form else "XML"
        payload = cm.encode_record("cm.goal", cm.goal(x, 0.5, 0.25), text_form=text_form)
        a = await op.raw(robot, "set", cm.control_ml("set", op.ids.next(), "cm.goal", payload))
        check(f"set cm.goal in the {form} form", a.type == "result" and a.cm is not None
              and a.cm.get("type") == "result" and len(a.cm) == 0, str(a))
        g = await op.raw(robot, "get", cm.control_ml("get", op.ids.next(), "cm.goal"))
        check(f"get cm.goal gives the value set in the {form} form",
              g.cm is not None and abs(cm.decode(g.cm).value["x"].value - x) < 1e-12, str(g))
    a = await op.raw(robot, "set", control_ml(f"type='set' id='{op.ids.next()}' res='cm.goal'", goal_xml("50", "cm")))
    g = await op.raw(robot, "get", cm.control_ml("get", op.ids.next(), "cm.goal"))
    check("a unit of the same dimension is converted (50 cm -> 0.5 m)", a.type == "result" and g.cm is not None
          and abs(cm.decode(g.cm).value["x"].value - 0.5) < 1e-12, str(g))


async def refusals(op: Peer, viewer: Peer, stranger: Peer, robot: str) -> None:
    ids = op.ids
    bare = [("missing type", f"id='{ids.next()}' res='cm.position'", "bad-attributes"),
            ("type put", f"type='put' id='{ids.next()}' res='cm.position'", "bad-attributes"),
            ("res Position", f"type='get' id='{ids.next()}' res='Position'", "bad-attributes"),
            ("id 2026-11-21:1", "type='get' id='2026-11-21:1' res='cm.position'", "bad-id"),
            ("id 20261332:1", "type='get' id='20261332:1' res='cm.position'", "bad-id"),
            ("id 20250229:1 (no such day)", "type='get' id='20250229:1' res='cm.position'", "bad-id"),
            ("id 20261121:4294967296", "type='get' id='20261121:4294967296' res='cm.position'", "bad-id"),
            ("id 20261121:01", "type='get' id='20261121:01' res='cm.position'", "bad-id")]
    for name, attributes, reason in bare:
        refusal(name, await op.raw(robot, "get", control_ml(attributes)), reason, echo=False)
    refusal("extra attribute", await op.raw(robot, "get", control_ml(
        f"type='get' id='{ids.next()}' res='cm.position' urgent='yes'")), "bad-attributes")
    # the send time (section 1): on a set only, UTC, and required where the set moves the robot (section 5)
    refusal("sent on a get", await op.raw(robot, "get", control_ml(
        f"type='get' id='{ids.next()}' res='cm.position' sent='{cm.utc_time()}'")), "bad-attributes")
    refusal("sent with a zone offset", await op.raw(robot, "set", control_ml(
        f"type='set' id='{ids.next()}' res='cm.goal' sent='2026-11-28T10:15:30+01:00'", goal_xml())),
        "bad-attributes")
    refusal("a cm.goal set without its send time", await op.raw(robot, "set", control_ml(
        f"type='set' id='{ids.next()}' res='cm.goal'", goal_xml(), stamp=False)), "bad-attributes")
    a = await op.raw(robot, "set", control_ml(f"type='set' id='{ids.next()}' res='cm.limits'", ET.tostring(cm.encode_record(
        "cm.limits", {"maxLinearSpeed": 0.5, "maxAngularSpeed": 1.0, "maxLinearAcceleration": 0.5,
                      "maxAngularAcceleration": 1.0}, text_form=False), encoding="unicode"), stamp=False))
    check("a cm.limits set without a send time is applied (it does not move the robot)", a.type == "result",
          str(a))
    an_hour_ago = cm.utc_time(datetime.now(timezone.utc) - timedelta(hours=1))
    refusal("a cm.goal sent an hour ago", await op.raw(robot, "set", control_ml(
        f"type='set' id='{ids.next()}' res='cm.goal' sent='{an_hour_ago}'", goal_xml())), "stale-command")
    in_an_hour = cm.utc_time(datetime.now(timezone.utc) + timedelta(hours=1))
    refusal("a cm.goal sent an hour ahead of the device's clock", await op.raw(robot, "set", control_ml(
        f"type='set' id='{ids.next()}' res='cm.goal' sent='{in_an_hour}'", goal_xml())), "stale-command")
    refusal("control-ml set in an iq get", await op.raw(robot, "get", control_ml(
        f"type='set' id='{ids.next()}' res='cm.goal'", goal_xml())), "type-mismatch")
    refusal("control-ml error without failure in an iq set", await op.raw(robot, "set", control_ml(
        f"type='error' id='{ids.next()}' res='cm.goal'")), "type-mismatch")
    refusal("an unknown SWE element", await op.raw(robot, "set", control_ml(
        f"type='set' id='{ids.next()}' res='cm.goal'",
        f"<DataRecord xmlns='{cm.SWE_NS}'><field name='x'><Oops/></field></DataRecord>")), "malformed-payload")
    refusal("a set of a get-only resource", await op.raw(robot, "set", control_ml(
        f"type='set' id='{ids.next()}' res='cm.obstacles'", "")), "unsupported-operation")
    refusal("set without payload", await op.raw(robot, "set", control_ml(
        f"type='set' id='{ids.next()}' res='cm.goal'")), "payload-mismatch")
    refusal("unknown resource", await op.raw(robot, "get", control_ml(
        f"type='get' id='{ids.next()}' res='cm.teleport'")), "unknown-resource")
    refusal("a resource the device does not serve", await op.raw(robot, "get", control_ml(
        f"type='get' id='{ids.next()}' res='cm.map'")), "unsupported-operation")
    refusal("NaN", await op.raw(robot, "set", control_ml(
        f"type='set' id='{ids.next()}' res='cm.goal'", goal_xml("NaN"))), "invalid-value")
    refusal("+INF (XSD 1.1)", await op.raw(robot, "set", control_ml(
        f"type='set' id='{ids.next()}' res='cm.goal'", goal_xml("+INF"))), "invalid-value")
    refusal("seconds for a length", await op.raw(robot, "set", control_ml(
        f"type='set' id='{ids.next()}' res='cm.goal'", goal_xml("1", "s"))), "wrong-unit")
    long_number = "0." + "0" * 200 + "15e201"
    a = await op.raw(robot, "set", control_ml(f"type='set' id='{ids.next()}' res='cm.goal'", goal_xml(long_number)))
    check("an xs:double of 210 characters is a number", a.type == "result", str(a))

    # the payload size at its edge, computed by section 1's rule on this side
    base = payload_size(ET.fromstring(goal_xml()))
    at_limit = goal_xml(pad=MAX_PAYLOAD - base)
    assert payload_size(ET.fromstring(at_limit)) == MAX_PAYLOAD
    a = await op.raw(robot, "set", control_ml(f"type='set' id='{ids.next()}' res='cm.goal'", at_limit))
    check("a payload of exactly 65,536 is accepted", a.type == "result", str(a))
    refusal("a payload of 65,537", await op.raw(robot, "set", control_ml(
        f"type='set' id='{ids.next()}' res='cm.goal'", goal_xml(pad=MAX_PAYLOAD - base + 1))), "payload-too-large")

    refusal("a stranger's get", await stranger.raw(robot, "get", cm.control_ml("get", stranger.ids.next(),
                                                                               "cm.position")), "access-denied")
    refusal("a viewer's set", await viewer.raw(robot, "set", cm.control_ml("set", viewer.ids.next(), "cm.goal",
                                                                           cm.encode_record("cm.goal", cm.goal(
                                                                               1, 1, 0)))), "set-not-permitted")
    # cm.role (section 9): each requester learns its own role; a stranger has none
    for peer, expected in ((op, "maintainer"), (viewer, "observer")):
        a = await peer.raw(robot, "get", cm.control_ml("get", peer.ids.next(), "cm.role"))
        role = cm.decode(a.cm).value.get("role") if a.type == "result" and a.cm is not None else None
        check(f"cm.role tells the {expected} its role", role == expected, str(a))
    refusal("a stranger's cm.role", await stranger.raw(robot, "get", cm.control_ml("get", stranger.ids.next(),
                                                                                   "cm.role")), "access-denied")
    for word in ("maintenance-lock", "invalid-state", "busy", "device-fault"):
        mission = cm.encode_record("cm.mission", {"state": "paused", "maintenance": False,
                                                  "progress": cm.Measure(0.0, "%"), "detail": word})
        refusal(f"the device's own refusal: {word}", await op.raw(robot, "set", cm.control_ml(
            "set", ids.next(), "cm.mission", mission)), word)
    mission = cm.encode_record("cm.mission", {"state": "paused", "maintenance": False,
                                              "progress": cm.Measure(0.0, "%"), "detail": "throw"})
    refusal("a handler that throws", await op.raw(robot, "set", cm.control_ml("set", ids.next(), "cm.mission",
                                                                              mission)), "device-fault")
    await stale_command(op, robot)


async def missions(op: Peer, robot: str) -> None:
    """Section 4's cm.mission with targets: read as the device writes it, written as the device reads it."""
    a = await op.raw(robot, "get", cm.control_ml("get", op.ids.next(), "cm.mission"))
    try:
        got = cm.mission_targets(cm.decode(a.cm).value) if a.cm is not None else None
    except cm.PayloadError as e:
        got = e
    check("get cm.mission gives its targets, their states, the current one and the queue",
          got == (1, 1, [("wait", "reached"), ("dock", "active")]), f"{got} from {a}")
    targets = [cm.target(1, 2, 0, "pass"), cm.target(3, 2, 1.5, "wait", 4.5), cm.target(0.5, 0.5, 3.1, "dock")]
    for queue in (False, True):
        a = await op.raw(robot, "set", cm.control_ml("set", op.ids.next(), "cm.mission", cm.mission(targets, queue)))
        check(f"set cm.mission with three targets ({'queued' if queue else 'now'})", a.type == "result", str(a))
    ns = "{" + cm.SWE_NS + "}"
    no_wait = cm.mission(targets)
    no_wait.find(f"{ns}field[@name='target1']//{ns}field[@name='wait']/{ns}Quantity/{ns}value").text = "0.0"
    refusal("a wait target without a wait", await op.raw(robot, "set", cm.control_ml(
        "set", op.ids.next(), "cm.mission", no_wait)), "invalid-value")
    miscounted = cm.mission(targets)
    miscounted.find(f"{ns}field[@name='count']/{ns}Count/{ns}value").text = "4"
    refusal("a count of targets that does not match them", await op.raw(robot, "set", cm.control_ml(
        "set", op.ids.next(), "cm.mission", miscounted)), "malformed-payload")


async def stale_command(op: Peer, robot: str) -> None:
    """A set in a message whose XEP-0203 delay says it waited since 2020: the device's stale-command policy."""
    rid = op.ids.next()
    msg = op.make_message(mto=slixmpp.JID(robot).bare, mtype="normal", mbody="ControlML command cm.goal " + rid)
    msg.append(cm.control_ml("set", rid, "cm.goal", cm.encode_record("cm.goal", cm.goal(3, 3, 0))))
    msg.append(ET.fromstring("<delay xmlns='urn:xmpp:delay' stamp='2020-01-01T00:00:00Z'/>"))
    msg.append(ET.fromstring("<store xmlns='urn:xmpp:hints'/>"))
    msg.send()
    try:
        while True:
            answer = await asyncio.wait_for(op.messages.get(), TIMEOUT)
            elem = cm.find_control_ml(answer.xml)
            if elem is not None and elem.get("id") == rid:
                break
    except asyncio.TimeoutError:
        check("a set that waited since 2020 -> not-acceptable/stale-command", False, "no answer message")
        return
    failure = elem.find(f"{{{cm.CM_NS}}}failure")
    check("a set that waited since 2020 -> not-acceptable/stale-command (answer message)",
          elem.get("type") == "error" and failure is not None
          and (failure.get("condition"), failure.get("reason")) == ("not-acceptable", "stale-command"),
          ET.tostring(answer.xml, encoding="unicode")[:600])


async def replay(op: Peer, robot: str) -> None:
    rid = op.ids.next()
    first = await op.raw(robot, "set", cm.control_ml("set", rid, "cm.goal", cm.encode_record("cm.goal", cm.goal(
        4, 4, 0))))
    again = await op.raw(robot, "set", cm.control_ml("set", rid, "cm.goal", cm.encode_record("cm.goal", cm.goal(
        5, 5, 0))))
    damaged = await op.raw(robot, "set", control_ml(f"type='set' id='{rid}' res='cm.goal'",
                                                    f"<DataRecord xmlns='{cm.SWE_NS}'><Oops/></DataRecord>"))
    g = await op.raw(robot, "get", cm.control_ml("get", op.ids.next(), "cm.goal"))
    check("a set under a used id gets the first answer and is not applied",
          first.type == again.type == "result" and g.cm is not None and cm.decode(g.cm).value["x"].value == 4,
          f"{again} / {g}")
    check("a retransmission that arrives malformed gets the remembered answer", damaged.type == "result",
          str(damaged))
    rid = op.ids.next()
    busy = cm.encode_record("cm.mission", {"state": "paused", "maintenance": False,
                                           "progress": cm.Measure(0.0, "%"), "detail": "busy-once"})
    one = await op.raw(robot, "set", cm.control_ml("set", rid, "cm.mission", busy))
    two = await op.raw(robot, "set", cm.control_ml("set", rid, "cm.mission", busy))
    check("busy is not remembered: the retry under the same id is taken as new",
          one.reason == "busy" and two.type == "result", f"{one} / {two}")


async def leases(viewer: Peer, stranger: Peer, robot: str) -> None:
    """Section 6's leases: an observer leases faster telemetry, the device grants up to its full rate and its longest
    lease, ends the lease on request; refusals change nothing."""
    async def rates(peer: Peer) -> tuple[float, dict[str, float]] | None:
        a = await peer.raw(robot, "get", cm.control_ml("get", peer.ids.next(), "cm.telemetry"))
        return cm.telemetry_rates(cm.decode(a.cm).value) if a.type == "result" and a.cm is not None else None

    before = await rates(viewer)
    check("cm.telemetry tells the base rate and the longest lease", before == (10.0, {"cm.position": 20.0}),
          str(before))
    a = await viewer.raw(robot, "set", cm.control_ml("set", viewer.ids.next(), "cm.telemetry",
                                                     cm.lease(60, {"cm.position": 100})))
    granted = cm.telemetry_rates(cm.decode(a.cm).value) if a.type == "result" and a.cm is not None else None
    check("an observer's lease is granted up to the full rate and the longest lease",
          granted == (10.0, {"cm.position": 40.0}), str(a))
    check("a lease raises the rate", await rates(viewer) == (10.0, {"cm.position": 40.0}))
    a = await viewer.raw(robot, "set", cm.control_ml("set", viewer.ids.next(), "cm.telemetry",
                                                     cm.lease(60, {"cm.position": 100, "cm.goal": 5})))
    granted = cm.telemetry_rates(cm.decode(a.cm).value) if a.type == "result" and a.cm is not None else None
    check("a resource the device does not publish is granted 0 Hz",
          granted == (10.0, {"cm.position": 40.0, "cm.goal": 0.0}), str(a))
    wrong = cm.lease(10, {"cm.position": 5})
    wrong.find(f".//{{{cm.SWE_NS}}}field[@name='rate']/{{{cm.SWE_NS}}}Quantity/{{{cm.SWE_NS}}}uom").set("code", "m")
    refusal("a lease's rate in metres", await viewer.raw(robot, "set", cm.control_ml(
        "set", viewer.ids.next(), "cm.telemetry", wrong)), "wrong-unit")
    refusal("a stranger's lease", await stranger.raw(robot, "set", cm.control_ml(
        "set", stranger.ids.next(), "cm.telemetry", cm.lease(10, {"cm.position": 40}))), "access-denied")
    check("refused leases change nothing", await rates(viewer) == (10.0, {"cm.position": 40.0}))
    a = await viewer.raw(robot, "set", cm.control_ml("set", viewer.ids.next(), "cm.telemetry", cm.lease(0, {})))
    check("a lease of 0 s ends the lease: the base rate again",
          a.type == "result" and await rates(viewer) == (10.0, {"cm.position": 20.0}), str(a))


async def telemetry(args, robot: str) -> None:
    """Section 6's recipe, twice: a first session that subscribes, and the same client coming back."""
    robot_bare = slixmpp.JID(robot).bare
    operator = f"{args.operator}@{args.domain}/interop"
    for session in (1, 2):
        print(f"... telemetry session {session}: logging in", flush=True)
        peer = await online(operator, args.password, args.server, args.port, args.ca_file, interest=True)
        print(f"... telemetry session {session}: online", flush=True)
        if session == 1:
            await asyncio.wait_for(peer.find_robot(robot_bare, TIMEOUT), TIMEOUT + 1)  # step 2: the presence subscription (the robot approves)
        deadline = asyncio.get_running_loop().time() + TIMEOUT
        while True:  # step 3: the explicit subscription; item-not-found until the node exists
            try:
                await peer.plugin["xep_0060"].subscribe(robot_bare, TELEMETRY_NODE, subscribee=peer.boundjid.full,
                                                 timeout=TIMEOUT)
                break
            except IqError as e:
                if e.condition != "item-not-found" or asyncio.get_running_loop().time() > deadline:
                    check(f"session {session}: explicit subscription", False, str(e))
                    await peer.disconnect()
                    return
        print(f"... telemetry session {session}: subscribed", flush=True)
        # wait for 20 publications after the subscription
        start = len(peer.items)
        try:
            while len({i for i, _ in peer.items[start:]}) < 20:
                peer.item_arrived.clear()
                await asyncio.wait_for(peer.item_arrived.wait(), TIMEOUT)
        except asyncio.TimeoutError:
            check(f"session {session}: telemetry arrives", False, f"{len(peer.items) - start} items")
            await peer.disconnect()
            return
        delivered = peer.items[start:]
        taken: list[tuple[str, float]] = []
        last = None
        # the dedup rule: take an id only when it is greater than the last taken, over the whole session as a client
        # keeps it: the item a server sends on the subscription (its last one) may be older than one +notify brought
        # before the subscription's answer
        for n, (rid, x) in enumerate(peer.items):
            key = (rid.split(":")[0], int(rid.split(":")[1]))
            if last is None or key > last:
                last = key
                if n >= start:
                    taken.append((rid, x))
        xs = [x for _, x in taken]
        copies = len(delivered) - len(taken)
        check(f"session {session}: each publication taken once, in order, none lost "
              f"({len(delivered)} delivered, {copies} dropped as copies)",
              xs == [xs[0] + k for k in range(len(xs))] and len({i for i, _ in taken}) == len(taken),
              f"xs {xs}")
        check(f"session {session}: a copy always repeats an id and its value",
              all(dict(taken).get(rid, x) == x for rid, x in delivered), str(delivered))
        await peer.disconnect()


async def identity(op: Peer, args, robot: str) -> None:
    iq = await op.plugin["xep_0054"].get_vcard(slixmpp.JID(robot).bare, local=False, timeout=TIMEOUT)
    v = iq.xml.find("{vcard-temp}vCard")

    def text(path: str) -> str | None:
        e = v.find("/".join("{vcard-temp}" + p for p in path.split("/")))
        return None if e is None or e.text is None else e.text.strip()

    required = ["FN", "N/FAMILY", "UID", "JABBERID", "ROLE", "PHOTO/BINVAL"]
    missing = [f for f in required if not text(f)]
    check("vCard: every required field", not missing, f"missing {missing}")
    namespace = uuid.uuid5(uuid.NAMESPACE_URL, "https://sabot.invalid/device")
    expected_uid = "urn:uuid:" + str(uuid.uuid5(namespace, args.serial))
    check("vCard: UID is uuid5(Sabot namespace, serial)", text("UID") == expected_uid, f"{text('UID')}")
    png = base64.b64decode(text("PHOTO/BINVAL") or "")
    with tempfile.NamedTemporaryFile(suffix=".png") as f:
        f.write(png)
        f.flush()
        zbar = subprocess.run(["zbarimg", "--raw", "-q", "-Sdisable", "-Sqrcode.enable", f.name],
                              capture_output=True, timeout=30)
    qr = zbar.stdout.decode("utf-8").rstrip("\n")
    check("QR: zbarimg reads the PHOTO", zbar.returncode == 0 and qr != "", zbar.stderr.decode()[:300])
    if qr.startswith("SABOTQR1:"):
        xml = zlib.decompress(base45(qr[len("SABOTQR1:"):]), -15).decode("utf-8")
    else:
        xml = qr
    try:
        doc = ET.fromstring(xml)
    except ET.ParseError as e:
        check("QR: the document is XML", False, f"{e}: {xml[:200]}")
        return
    check("QR: VERSION 1 and the vCard's UID", doc.get("VERSION") == "1" and doc.get("UID") == expected_uid,
          str(doc.attrib))
    lines = ""
    electronic = doc.find("ELECTRONIC")
    for board in electronic.findall("BOARD"):
        for item in board:
            lines += f"{board.get('NAME')}/{item.tag}/{item.get('NAME')}/{item.get('VERSION')}\n"
    digest = base64.urlsafe_b64encode(hashlib.sha256(lines.encode("utf-8")).digest()).decode().rstrip("=")
    check("QR: HASH recomputed from the document", digest == electronic.get("HASH"),
          f"{digest} != {electronic.get('HASH')}")
    parts = [p.get("VALUE") for p in doc.iter("PART")]
    check("QR: non-ASCII text survives (UTF-8 ECI)", args.part in parts, f"parts {parts}")


def base45(text: str) -> bytes:
    alphabet = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ $%*+-./:"
    out = bytearray()
    for i in range(0, len(text), 3):
        chunk = [alphabet.index(c) for c in text[i:i + 3]]
        n = sum(c * 45 ** k for k, c in enumerate(chunk))
        out += n.to_bytes(2 if len(chunk) == 3 else 1, "big")
    return bytes(out)


def starttls_required(args) -> None:
    with socket.create_connection((args.server, args.port), timeout=TIMEOUT) as s:
        s.sendall((f"<?xml version='1.0'?><stream:stream to='{args.domain}' version='1.0' xmlns='jabber:client' "
                   "xmlns:stream='http://etherx.jabber.org/streams'>").encode())
        buf = b""
        while b"</stream:features>" not in buf:
            chunk = s.recv(4096)
            if not chunk:
                break
            buf += chunk
    features = buf.decode(errors="replace")
    check("the server requires STARTTLS and offers no SASL mechanism before it",
          "xmpp-tls" in features and "<required" in features and "mechanisms" not in features, features[-300:])


async def main(args) -> None:
    starttls_required(args)
    op = await online(f"{args.operator}@{args.domain}/suite", args.password, args.server, args.port, args.ca_file)
    viewer = await online(f"{args.viewer}@{args.domain}/suite", args.password, args.server, args.port, args.ca_file)
    stranger = await online(f"{args.stranger}@{args.domain}/suite", args.password, args.server, args.port,
                            args.ca_file)
    robot = args.robot
    await get_set(op, robot)
    await refusals(op, viewer, stranger, robot)
    await replay(op, robot)
    await missions(op, robot)
    await identity(op, args, robot)
    await leases(viewer, stranger, robot)
    print("... disconnecting", flush=True)
    await asyncio.gather(*(p.disconnect() for p in (op, viewer, stranger)))
    print("... disconnected", flush=True)
    await telemetry(args, robot)


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--server", default="127.0.0.1")
    p.add_argument("--port", type=int, required=True)
    p.add_argument("--ca-file", metavar="PEM", default=os.environ.get("SABOT_XMPP_CA") or None,
                   help="the server's lab CA (DIR/ca/ca.pem of sabot-xmpp start): the only CA the clients trust, "
                        "the certificate must name --domain (default $SABOT_XMPP_CA; one of the two is required)")
    p.add_argument("--domain", default="sabot.local")
    p.add_argument("--robot", required=True, help="the device's full JID")
    p.add_argument("--operator", required=True)
    p.add_argument("--viewer", required=True)
    p.add_argument("--stranger", required=True)
    p.add_argument("--password", required=True)
    p.add_argument("--serial", required=True, help="the serial on the device's label")
    p.add_argument("--part", required=True, help="a non-ASCII PART VALUE of the inventory")
    a = p.parse_args()
    if not a.ca_file:
        p.error("give --ca-file (or $SABOT_XMPP_CA): the suite only talks to a server through TLS")
    try:
        tool.ssl_context(a.ca_file)
    except tool.Failure as f:
        p.error(str(f))
    import faulthandler
    faulthandler.dump_traceback_later(110, exit=True)  # a hang shows where it is, and ends
    try:
        asyncio.run(asyncio.wait_for(main(a), 120))
    except Exception as e:  # a crash is a failed check, reported like the others
        # a refused certificate or login: its one line (controlml.py's words)
        check("suite ran to its end", False, str(e) if isinstance(e, tool.Failure) else repr(e))
    failed = sum(1 for ok, _ in results if not ok)
    print(f"interop: {len(results) - failed} passed, {failed} failed", flush=True)
    # not sys.exit: a slixmpp task that ignores cancellation must not keep the process (and the build) waiting
    os._exit(0 if failed == 0 and results else 1)
