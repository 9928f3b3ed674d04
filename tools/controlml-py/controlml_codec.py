"""ControlML 1 encoding and decoding, written from docs/CONTROLML.md alone (the project's second implementation).

Standard library only: this module builds and reads the ``<control-ml/>`` element and its SWE Common payloads as
``xml.etree.ElementTree`` elements; ``controlml.py`` carries them over XMPP with slixmpp. Values are decoded to:
DataRecord -> dict (field order kept), Quantity -> Measure (in the canonical unit when the unit is a known alias),
Count -> int, Boolean -> bool, Time/Text/Category -> str, DataArray -> list of dicts (one per row).
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from datetime import datetime, timezone
from typing import Any, Callable, NamedTuple

CM_NS = "urn:sabot:controlml:1"
ERRORS_NS = "urn:sabot:controlml:1:errors"
SWE_NS = "http://www.opengis.net/swe/2.0"
XLINK_NS = "http://www.w3.org/1999/xlink"
STANZAS_NS = "urn:ietf:params:xml:ns:xmpp-stanzas"
GREGORIAN = "http://www.opengis.net/def/uom/ISO-8601/0/Gregorian"
RECORD_PREFIX = "urn:sabot:controlml:1:record:"  # + res: the text form's elementType reference (section 3)

TYPES = ("get", "set", "result", "error")
MAX_COUNTER = 4294967295  # the id's counter is a 32-bit unsigned integer (section 1)
MAX_RECORD_DEPTH = 8  # DataRecords nest at most 8 deep (section 3)

_RES_RE = re.compile(r"cm(\.[a-z][a-z0-9\-]{0,30}){1,4}")
_ID_RE = re.compile(r"([0-9]{8}):(0|[1-9][0-9]{0,9})")
# xs:double lexical space: decimal or scientific, and the special values (section 3 refuses 1,5, 0x1p3, Infinity)
_DOUBLE_RE = re.compile(r"[+-]?([0-9]+(\.[0-9]*)?|\.[0-9]+)([eE][+-]?[0-9]+)?|NaN|INF|-INF|\+INF")
_TIME_RE = re.compile(r"[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}(\.[0-9]+)?(Z|[+-][0-9]{2}:[0-9]{2})")
_UTC_RE = re.compile(r"[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}(\.[0-9]{1,9})?Z")  # sent (section 1)


class PayloadError(ValueError):
    """A payload or element outside the spec (the spec's 'malformed payload'), or a value no writer may send."""


class Measure(NamedTuple):
    """A Quantity: its value and its UCUM unit code."""

    value: float
    uom: str


# Units a reader converts to the canonical unit of the same dimension (section 3): code -> (canonical, factor).
UNIT_ALIASES: dict[str, tuple[str, float]] = {
    "cm": ("m", 0.01), "mm": ("m", 0.001), "km": ("m", 1000.0),
    "deg": ("rad", math.pi / 180.0), "mrad": ("rad", 0.001),
    "ms": ("s", 0.001), "min": ("s", 60.0),
    "cm/s": ("m/s", 0.01), "km/h": ("m/s", 1000.0 / 3600.0),
    "deg/s": ("rad/s", math.pi / 180.0),
    "/s": ("Hz", 1.0), "/min": ("Hz", 1.0 / 60.0),
    "mV": ("V", 0.001), "mA": ("A", 0.001), "mA.h": ("A.h", 0.001),
}


def canonical(m: Measure) -> Measure:
    """Returns ``m`` in its canonical unit when its unit is a known alias, else ``m`` unchanged."""
    alias = UNIT_ALIASES.get(m.uom)
    return Measure(m.value * alias[1], alias[0]) if alias else m


# ---------------------------------------------------------------------------------------------------------------
# Request ids (section 1)
# ---------------------------------------------------------------------------------------------------------------
class RequestIds:
    """Ids 'YYYYMMDD:counter' for one requester. Each UTC day's counter starts at the millisecond of the day x 32,
    so a requester restarted the same day does not reuse its earlier ids."""

    def __init__(self, clock: Callable[[], datetime] = lambda: datetime.now(timezone.utc)):
        self._clock = clock
        self._day = ""
        self._counter = 0

    def next(self) -> str:
        now = self._clock().astimezone(timezone.utc)
        day = now.strftime("%Y%m%d")
        if day != self._day:
            self._day = day
            midnight = now.replace(hour=0, minute=0, second=0, microsecond=0)
            self._counter = int((now - midnight).total_seconds() * 1000) * 32
        else:
            self._counter += 1
        if self._counter > MAX_COUNTER:
            raise OverflowError("no request id left for today")
        return f"{day}:{self._counter}"


def is_resource(text: str) -> bool:
    """True when ``text`` is a resource name: 'cm.' and dot-separated lower-case words."""
    return bool(_RES_RE.fullmatch(text))


def is_request_id(text: str) -> bool:
    """True when ``text`` is 'YYYYMMDD:UINT32' with a date that exists and a counter <= 4294967295."""
    m = _ID_RE.fullmatch(text)
    if not m or int(m.group(2)) > MAX_COUNTER:
        return False
    try:
        datetime.strptime(m.group(1), "%Y%m%d")
    except ValueError:
        return False
    return True


# ---------------------------------------------------------------------------------------------------------------
# Record structures: the text form's fields in order (sections 3 and 4). A field is (name, kind, unit or columns).
# ---------------------------------------------------------------------------------------------------------------
COVARIANCE = (("xx", "Quantity", "m2"), ("xy", "Quantity", "m2"), ("xtheta", "Quantity", "m.rad"),
              ("yy", "Quantity", "m2"), ("ytheta", "Quantity", "m.rad"), ("thetatheta", "Quantity", "rad2"))
STRUCTURES: dict[str, tuple] = {
    "cm.position": (("time", "Time", None), ("x", "Quantity", "m"), ("y", "Quantity", "m"),
                    ("theta", "Quantity", "rad"), ("covariance", "DataArray", COVARIANCE)),
    "cm.velocity": (("time", "Time", None), ("linear", "Quantity", "m/s"), ("angular", "Quantity", "rad/s")),
    "cm.goal": (("x", "Quantity", "m"), ("y", "Quantity", "m"), ("theta", "Quantity", "rad"),
                ("positionTolerance", "Quantity", "m"), ("headingTolerance", "Quantity", "rad")),
    "cm.limits": (("maxLinearSpeed", "Quantity", "m/s"), ("maxAngularSpeed", "Quantity", "rad/s"),
                  ("maxLinearAcceleration", "Quantity", "m/s2"), ("maxAngularAcceleration", "Quantity", "rad/s2")),
}
# Records a client may set field by field (XML form); the text-form ones above plus the mission command.
SETTABLE: dict[str, tuple] = {
    **{res: STRUCTURES[res] for res in ("cm.goal", "cm.limits", "cm.velocity")},
    "cm.mission": (("state", "Category", None), ("maintenance", "Boolean", None), ("progress", "Quantity", "%"),
                   ("detail", "Text", None)),
}
# cm.battery (section 4): read by a client, never set; its fields in order.
BATTERY = (("time", "Time", None), ("stateOfCharge", "Quantity", "%"), ("voltage", "Quantity", "V"),
           ("current", "Quantity", "A"), ("capacity", "Quantity", "A.h"), ("docked", "Boolean", None),
           ("charging", "Boolean", None), ("full", "Boolean", None))
BATTERY_BOUND = 1000.0  # V, A and A.h: the protocol's bound on voltage, current and capacity (section 4)
# cm.passage (section 4, docs/PASSAGES.md): a robot's claim on a narrow passage of its map; read, never set.
PASSAGE_FIELDS = ("time", "passage", "state", "since")
PASSAGE_STATES = ("none", "waiting", "passing")
MAX_PASSAGES = 64
MISSION_STATES = ("idle", "running", "paused", "done", "failed", "aborted", "queued")
TARGET_ACTIONS = ("pass", "stop", "wait", "dock")
TARGET_STATES = ("pending", "active", "reached", "failed")
MAX_TARGETS, MAX_WAIT_S = 64, 3600.0  # cm.mission's ranges (section 4)


# ---------------------------------------------------------------------------------------------------------------
# Writing
# ---------------------------------------------------------------------------------------------------------------
def format_double(value: float) -> str:
    """xs:double text of a finite number (a writer never sends NaN or INF: every resource refuses them)."""
    value = float(value)
    if not math.isfinite(value):
        raise PayloadError(f"{value} is not a finite number")
    return repr(value)


def control_ml(kind: str, request_id: str, res: str, payload: ET.Element | None = None,
               sent: str | None = None) -> ET.Element:
    """The ``<control-ml/>`` element: the attributes type, id and res, on a set its send time ``sent`` (section 1;
    now when None), and at most one payload."""
    if kind not in TYPES:
        raise PayloadError(f"type '{kind}' is not one of {', '.join(TYPES)}")
    if not is_request_id(request_id):
        raise PayloadError(f"id '{request_id}' is not YYYYMMDD:UINT32")
    if not _RES_RE.fullmatch(res):
        raise PayloadError(f"res '{res}' is not cm.<word>[.<word>...]")
    attributes = {"type": kind, "id": request_id, "res": res}
    if kind == "set":
        attributes["sent"] = sent or utc_time()
    elif sent is not None:
        raise PayloadError("only a set carries a send time")
    elem = ET.Element(f"{{{CM_NS}}}control-ml", attributes)
    if payload is not None:
        elem.append(payload)
    return elem


def _swe(tag: str, parent: ET.Element | None = None, attrib: dict | None = None) -> ET.Element:
    elem = ET.Element(f"{{{SWE_NS}}}{tag}", attrib or {})
    if parent is not None:
        parent.append(elem)
    return elem


def _scalar(kind: str, unit: str | None, value: Any, with_value: bool = True) -> ET.Element:
    elem = _swe(kind)
    if kind == "Quantity":
        _swe("uom", elem, {"code": unit})
    elif kind == "Time":
        _swe("uom", elem, {f"{{{XLINK_NS}}}href": GREGORIAN})
    if with_value:
        _swe("value", elem).text = _token(kind, value)
    return elem


def _token(kind: str, value: Any) -> str:
    if kind == "Quantity":
        return format_double(value.value if isinstance(value, Measure) else value)
    if kind == "Count":
        if isinstance(value, bool) or not isinstance(value, int):
            raise PayloadError(f"{value!r} is not an integer")
        return str(value)
    if kind == "Boolean":
        if not isinstance(value, bool):
            raise PayloadError(f"{value!r} is not a boolean")
        return "true" if value else "false"
    if kind == "Time":
        if not _TIME_RE.fullmatch(str(value)):
            raise PayloadError(f"'{value}' is not an ISO 8601 time with a zone")
        return str(value)
    return str(value)  # Text, Category


def encode_record(res: str, values: dict[str, Any], text_form: bool = True) -> ET.Element:
    """The payload of a set of ``res`` from ``values`` (field name -> number, bool or str, canonical units). The text
    form (a DataStream referring to the resource's structure) is used when ``text_form`` and the resource has one."""
    structure = STRUCTURES.get(res) if text_form else None
    fields = structure or SETTABLE.get(res) or STRUCTURES.get(res)
    if fields is None:
        raise PayloadError(f"no record structure known for {res}")
    names = [f[0] for f in fields]
    missing = [n for n in names if n not in values]
    extra = [n for n in values if n not in names]
    if missing or extra:
        raise PayloadError(f"{res} needs exactly the fields {', '.join(names)}"
                           + (f"; missing {', '.join(missing)}" if missing else "")
                           + (f"; unknown {', '.join(extra)}" if extra else ""))
    if structure:
        tokens = []
        for name, kind, unit in fields:
            if kind == "DataArray":
                row = values[name][0] if isinstance(values[name], list) else values[name]
                tokens += [_token(k, row[n]) for n, k, _ in unit]
            else:
                token = _token(kind, values[name])
                if kind in ("Text", "Category") and (not token or re.search(r"[,\s]", token)):
                    return encode_record(res, values, text_form=False)  # does not fit a token: XML form
                tokens.append(token)
        stream = _swe("DataStream")
        _swe("elementType", stream, {"name": "value", f"{{{XLINK_NS}}}href": RECORD_PREFIX + res})
        encoding = _swe("encoding", stream)
        _swe("TextEncoding", encoding, {"tokenSeparator": ",", "blockSeparator": " "})
        _swe("values", stream).text = ",".join(tokens)
        return stream
    record = _swe("DataRecord")
    for name, kind, unit in fields:
        field = _swe("field", record, {"name": name})
        if kind == "DataArray":
            field.append(_data_array(name, unit, values[name]))
        else:
            field.append(_scalar(kind, unit, values[name]))
    return record


def _data_array(name: str, columns: tuple, rows: list[dict]) -> ET.Element:
    array = _swe("DataArray")
    count = _swe("Count", _swe("elementCount", array))
    _swe("value", count).text = str(len(rows))
    element_type = _swe("elementType", array, {"name": name})
    record = _swe("DataRecord", element_type)
    for col, kind, unit in columns:
        _swe("field", record, {"name": col}).append(_scalar(kind, unit, None, with_value=False))
    encoding = _swe("encoding", array)
    _swe("TextEncoding", encoding, {"tokenSeparator": ",", "blockSeparator": " "})
    _swe("values", array).text = " ".join(",".join(_token(k, row[c]) for c, k, _ in columns) for row in rows)
    return array


def goal(x: float, y: float, theta: float, position_tolerance: float = 0.1, heading_tolerance: float = 0.2) -> dict:
    """A cm.goal record (m, m, rad, m > 0, rad in (0, 2 pi]); refuses what every robot would refuse."""
    if not position_tolerance > 0:
        raise PayloadError(f"positionTolerance {position_tolerance} m must be > 0")
    if not 0 < heading_tolerance <= 2 * math.pi:
        raise PayloadError(f"headingTolerance {heading_tolerance} rad must be in (0, 2 pi]")
    return {"x": x, "y": y, "theta": theta, "positionTolerance": position_tolerance,
            "headingTolerance": heading_tolerance}


MAX_LINEAR_SPEED, MAX_ANGULAR_SPEED = 10.0, 20.0  # cm.velocity's ranges, m/s and rad/s (section 4)


def utc_time(when: datetime | None = None) -> str:
    """An ISO 8601 UTC Time token to the microsecond, e.g. '2026-11-21T10:15:30.123456Z' (now when ``when`` is None)."""
    when = (when or datetime.now(timezone.utc)).astimezone(timezone.utc)
    return when.strftime("%Y-%m-%dT%H:%M:%S.%fZ")


def velocity(linear: float, angular: float, time: str) -> dict:
    """A cm.velocity record (joystick twist: m/s, rad/s, the ISO 8601 UTC time it is sent); refuses what every robot
    would refuse (a non-finite number, |linear| > 10 m/s, |angular| > 20 rad/s)."""
    for name, value, bound, unit in (("linear", linear, MAX_LINEAR_SPEED, "m/s"),
                                     ("angular", angular, MAX_ANGULAR_SPEED, "rad/s")):
        if not math.isfinite(value) or abs(value) > bound:
            raise PayloadError(f"{name} {value} {unit} must be finite and within +-{bound:g} {unit}")
    return {"time": time, "linear": float(linear), "angular": float(angular)}


MAX_LEASE_S, MAX_RATE_HZ, MAX_STREAMS = 3600.0, 100.0, 16  # cm.telemetry's ranges (section 4)
_RES_RE = re.compile(r"cm(\.[a-z][a-z0-9\-]{0,30}){1,4}")


def lease(seconds: float, rates: dict[str, float]) -> ET.Element:
    """The payload of a cm.telemetry set (section 6, "Leases"): a lease of ``seconds`` (0 ends it) of these rates in
    Hz by resource name; refuses what every device would refuse (an hour or more, over 100 Hz, over 16 resources)."""
    if not (math.isfinite(seconds) and 0 <= seconds <= MAX_LEASE_S):
        raise PayloadError(f"lease {seconds} s must be 0..{MAX_LEASE_S:g} s")
    if len(rates) > MAX_STREAMS:
        raise PayloadError(f"at most {MAX_STREAMS} resources in one lease, not {len(rates)}")
    record = _swe("DataRecord")
    _swe("field", record, {"name": "lease"}).append(_scalar("Quantity", "s", seconds))
    _swe("field", record, {"name": "count"}).append(_scalar("Count", None, len(rates)))
    for i, (res, hz) in enumerate(rates.items()):
        if not _RES_RE.fullmatch(res):
            raise PayloadError(f"'{res}' is not a resource name")
        if not (math.isfinite(hz) and 0 <= hz <= MAX_RATE_HZ):
            raise PayloadError(f"{res}: rate {hz} Hz must be 0..{MAX_RATE_HZ:g} Hz")
        stream = _swe("DataRecord")
        _swe("field", stream, {"name": "resource"}).append(_scalar("Text", None, res))
        _swe("field", stream, {"name": "rate"}).append(_scalar("Quantity", "Hz", hz))
        _swe("field", record, {"name": f"stream{i}"}).append(stream)
    return record


def telemetry_rates(value: dict) -> tuple[float, dict[str, float]]:
    """Reads a decoded cm.telemetry record (a get's answer, or a lease's): the lease in s and each resource's rate
    in Hz."""
    def number(m: Any, unit: str) -> float:
        m = canonical(m) if isinstance(m, Measure) else Measure(float(m), unit)
        if m.uom != unit:
            raise PayloadError(f"{m.uom} is not a unit of {unit}")
        return m.value
    n = value["count"]
    if set(value) != {"lease", "count"} | {f"stream{i}" for i in range(n)}:
        raise PayloadError(f"cm.telemetry fields are lease, count and stream0..stream{n - 1}, not {sorted(value)}")
    return number(value["lease"], "s"), {value[f"stream{i}"]["resource"]: number(value[f"stream{i}"]["rate"], "Hz")
                                          for i in range(n)}


def target(x: float, y: float, theta: float = 0.0, action: str = "stop", wait: float = 0.0,
           position_tolerance: float = 0.1, heading_tolerance: float = 0.3) -> dict:
    """One target of a cm.mission (m, m, rad; action pass|stop|wait|dock; wait s above 0 exactly for 'wait');
    refuses what every robot would refuse."""
    if action not in TARGET_ACTIONS:
        raise PayloadError(f"action '{action}' is not one of {', '.join(TARGET_ACTIONS)}")
    if not (math.isfinite(wait) and 0 <= wait <= MAX_WAIT_S):
        raise PayloadError(f"wait {wait} s must be 0..{MAX_WAIT_S:g} s")
    if (action == "wait") != (wait > 0):
        raise PayloadError("a wait target needs a wait above 0 s" if action == "wait"
                           else f"only a wait target waits (action {action}, wait {wait:g} s)")
    return {**goal(x, y, theta, position_tolerance, heading_tolerance), "action": action, "wait": float(wait)}


def mission(targets: list[dict], queue: bool = False) -> ET.Element:
    """The payload of a cm.mission set that starts a mission of ``targets`` (records of :func:`target`) now, or
    queues it after the robot's running and queued missions (section 4, "Mission commands")."""
    if not 1 <= len(targets) <= MAX_TARGETS:
        raise PayloadError(f"a mission has 1..{MAX_TARGETS} targets, not {len(targets)}")
    record = _swe("DataRecord")
    for name, kind, unit, value in (("state", "Category", None, "queued" if queue else "running"),
                                    ("maintenance", "Boolean", None, False), ("progress", "Quantity", "%", 0),
                                    ("detail", "Text", None, ""), ("current", "Count", None, 0),
                                    ("queued", "Count", None, 0), ("count", "Count", None, len(targets))):
        _swe("field", record, {"name": name}).append(_scalar(kind, unit, value))
    for i, t in enumerate(targets):
        rec = _swe("DataRecord")
        for name, kind, unit in (("x", "Quantity", "m"), ("y", "Quantity", "m"), ("theta", "Quantity", "rad"),
                                 ("positionTolerance", "Quantity", "m"), ("headingTolerance", "Quantity", "rad"),
                                 ("action", "Category", None), ("wait", "Quantity", "s")):
            _swe("field", rec, {"name": name}).append(_scalar(kind, unit, t[name]))
        _swe("field", rec, {"name": "state"}).append(_scalar("Category", None, "pending"))
        _swe("field", record, {"name": f"target{i}"}).append(rec)
    return record


def battery(value: dict) -> dict:
    """Reads a decoded cm.battery record (section 4) into plain numbers: time (text), state_of_charge (0..1),
    voltage (V), current (A, positive discharging), capacity (Ah), docked, charging, full. A field, unit or range the
    spec does not allow is a PayloadError naming it."""
    names = [name for name, _, _ in BATTERY]
    if set(value) != set(names):
        raise PayloadError(f"cm.battery fields are {names}, not {sorted(value)}")
    out: dict[str, Any] = {"time": value["time"]}
    for name, kind, unit in BATTERY[1:5]:
        m = value[name]
        if not isinstance(m, Measure) or m.uom != unit:
            raise PayloadError(f"cm.battery {name} must be a Quantity in {unit}, not {m!r}")
        out[name] = m.value
    for name in ("docked", "charging", "full"):
        if not isinstance(value[name], bool):
            raise PayloadError(f"cm.battery {name} must be a Boolean, not {value[name]!r}")
        out[name] = value[name]
    if not 0 <= out["stateOfCharge"] <= 100:
        raise PayloadError(f"cm.battery stateOfCharge {out['stateOfCharge']:g} % is outside 0..100")
    for name in ("voltage", "capacity"):
        if not 0 < out[name] <= BATTERY_BOUND:
            raise PayloadError(f"cm.battery {name} {out[name]:g} is outside (0, {BATTERY_BOUND:g}]")
    if not -BATTERY_BOUND <= out["current"] <= BATTERY_BOUND:
        raise PayloadError(f"cm.battery current {out['current']:g} A is outside -{BATTERY_BOUND:g}..{BATTERY_BOUND:g}")
    if (out["charging"] or out["full"]) and not out["docked"]:
        raise PayloadError("cm.battery charging or full away from a dock")
    if out["charging"] and out["full"]:
        raise PayloadError("cm.battery both charging and full")
    return {"time": out["time"], "state_of_charge": out["stateOfCharge"] / 100, "voltage": out["voltage"],
            "current": out["current"], "capacity": out["capacity"], "docked": out["docked"],
            "charging": out["charging"], "full": out["full"]}


def battery_line(b: dict) -> str:
    """One line for a person, e.g. 'battery 42.0 % 25.30 V 0.61 A of 10 Ah, docked, charging (at TIME)'."""
    flags = "".join(f", {f}" for f in ("docked", "charging", "full") if b[f])
    return (f"battery {b['state_of_charge'] * 100:.1f} % {b['voltage']:.2f} V {b['current']:.2f} A of "
            f"{b['capacity']:g} Ah{flags} (at {b['time']})")


def passage(value: dict) -> dict:
    """Reads a decoded cm.passage record (section 4) into time and since (text), passage (0: no claim) and state
    (none, waiting, passing). A field, type or range the spec does not allow is a PayloadError naming it."""
    if set(value) != set(PASSAGE_FIELDS):
        raise PayloadError(f"cm.passage fields are {list(PASSAGE_FIELDS)}, not {sorted(value)}")
    number, state = value["passage"], value["state"]
    if isinstance(number, bool) or not isinstance(number, int) or not 0 <= number <= MAX_PASSAGES:
        raise PayloadError(f"cm.passage passage must be a Count 0..{MAX_PASSAGES}, not {number!r}")
    if state not in PASSAGE_STATES:
        raise PayloadError(f"cm.passage state must be one of {PASSAGE_STATES}, not {state!r}")
    if (state == "none") != (number == 0):
        raise PayloadError(f"cm.passage passage {number} with state '{state}': a claim names its passage "
                           f"(1..{MAX_PASSAGES}) and is waiting or passing; no claim is passage 0, state none")
    return {"time": value["time"], "passage": number, "state": state, "since": value["since"]}


def mission_targets(value: dict) -> tuple[int, int, list[tuple[str, str]]]:
    """Reads a decoded cm.mission record's targets: (current target index, missions queued, [(action, state)] in
    order); (0, 0, []) for a mission without targets."""
    if "count" not in value:
        return 0, 0, []
    n = value["count"]
    expected = {"state", "maintenance", "progress", "detail", "current", "queued", "count"} | {
        f"target{i}" for i in range(n)}
    if set(value) != expected:
        raise PayloadError(f"cm.mission fields with targets are {sorted(expected)}, not {sorted(value)}")
    targets = []
    for i in range(n):
        t = value[f"target{i}"]
        if t["action"] not in TARGET_ACTIONS or t["state"] not in TARGET_STATES:
            raise PayloadError(f"target{i}: action '{t['action']}' or state '{t['state']}' unknown")
        targets.append((t["action"], t["state"]))
    return value["current"], value["queued"], targets


# ---------------------------------------------------------------------------------------------------------------
# Reading
# ---------------------------------------------------------------------------------------------------------------
def local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def _ns(tag: str) -> str:
    return tag[1:].split("}", 1)[0] if tag.startswith("{") else ""


def _children(elem: ET.Element) -> list[ET.Element]:
    if elem.text and elem.text.strip():
        raise PayloadError(f"text where an element belongs in <{local(elem.tag)}>")
    for child in elem:
        if _ns(child.tag) != SWE_NS:
            raise PayloadError(f"<{local(child.tag)}> is not a SWE Common element")
        if child.tail and child.tail.strip():
            raise PayloadError(f"text where an element belongs after <{local(child.tag)}>")
    return list(elem)


def _only(elem: ET.Element, *names: str) -> list[ET.Element]:
    kids = _children(elem)
    if [local(k.tag) for k in kids] != list(names):
        raise PayloadError(f"<{local(elem.tag)}> holds {[local(k.tag) for k in kids]}, expected {list(names)}")
    return kids


def parse_double(text: str) -> float:
    t = text.strip()
    if not _DOUBLE_RE.fullmatch(t):
        raise PayloadError(f"'{text}' is not an xs:double")
    return float({"INF": "inf", "+INF": "inf", "-INF": "-inf"}.get(t, t))


def _parse_token(kind: str, text: str, unit: str | None) -> Any:
    if kind == "Quantity":
        return canonical(Measure(parse_double(text), unit))
    if kind == "Count":
        if not re.fullmatch(r"[+-]?[0-9]+", text.strip()):
            raise PayloadError(f"'{text}' is not a Count")
        return int(text)
    if kind == "Boolean":
        t = text.strip()
        if t not in ("true", "false", "1", "0"):
            raise PayloadError(f"'{text}' is not a Boolean")
        return t in ("true", "1")
    if kind == "Time":
        if not _TIME_RE.fullmatch(text.strip()):
            raise PayloadError(f"'{text}' is not an ISO 8601 time with a zone")
        return text.strip()
    return text  # Text, Category


def _unit(kind: str, uom: ET.Element) -> str | None:
    if kind == "Quantity":
        code = uom.get("code")
        if not code:
            raise PayloadError("a Quantity's <uom/> has no code")
        return code
    if uom.get(f"{{{XLINK_NS}}}href") != GREGORIAN:
        raise PayloadError("a Time's <uom/> must refer to the ISO 8601 Gregorian calendar")
    return None


def decode_component(elem: ET.Element, depth: int = 1) -> Any:
    """Decodes one SWE Common component of the ControlML subset (section 3)."""
    kind = local(elem.tag)
    if _ns(elem.tag) != SWE_NS:
        raise PayloadError(f"<{kind}> is not a SWE Common element")
    if kind == "DataRecord":
        if depth > MAX_RECORD_DEPTH:
            raise PayloadError(f"DataRecords nest more than {MAX_RECORD_DEPTH} deep")
        out: dict[str, Any] = {}
        for field in _children(elem):
            name = field.get("name")
            if local(field.tag) != "field" or not name:
                raise PayloadError("a DataRecord holds only named <field/>s")
            if name in out:
                raise PayloadError(f"field '{name}' twice")
            kids = _children(field)
            if len(kids) != 1:
                raise PayloadError(f"field '{name}' must hold exactly one component")
            out[name] = decode_component(kids[0], depth + 1)
        return out
    if kind == "DataArray":
        return _decode_array(elem)
    if kind in ("Quantity", "Time"):
        uom, value = _only(elem, "uom", "value")
        return _parse_token(kind, value.text or "", _unit(kind, uom))
    if kind in ("Count", "Boolean", "Text", "Category"):
        (value,) = _only(elem, "value")
        return _parse_token(kind, value.text or "", None)
    raise PayloadError(f"<{kind}> is not in ControlML's SWE subset")


def _text_encoding(encoding: ET.Element) -> None:
    (te,) = _only(encoding, "TextEncoding")
    if te.get("tokenSeparator") != "," or te.get("blockSeparator") != " ":
        raise PayloadError("only tokenSeparator=',' and blockSeparator=' ' are allowed")


def _decode_array(elem: ET.Element) -> list[dict]:
    count_el, element_type, encoding, values = _only(elem, "elementCount", "elementType", "encoding", "values")
    (count,) = _only(count_el, "Count")
    n = decode_component(count)
    (record,) = _only(element_type, "DataRecord")
    columns = []
    for field in _children(record):
        (comp,) = _children(field)
        kind = local(comp.tag)
        if kind not in ("Quantity", "Count"):
            raise PayloadError(f"a DataArray column is a Quantity or a Count, not a {kind}")
        uom = _children(comp)
        if [local(u.tag) for u in uom] != (["uom"] if kind == "Quantity" else []):
            raise PayloadError(f"column '{field.get('name')}' must declare its unit once and hold no value")
        columns.append((field.get("name"), kind, _unit(kind, uom[0]) if kind == "Quantity" else None))
    _text_encoding(encoding)
    blocks = (values.text or "").split()
    if len(blocks) != n:
        raise PayloadError(f"elementCount {n} but {len(blocks)} blocks")
    rows = []
    for block in blocks:
        tokens = block.split(",")
        if len(tokens) != len(columns):
            raise PayloadError(f"block '{block}' has {len(tokens)} tokens, expected {len(columns)}")
        rows.append({c: _parse_token(k, t, u) for (c, k, u), t in zip(columns, tokens)})
    return rows


def decode_text_form(stream: ET.Element, res: str) -> dict:
    """Decodes a DataStream (the text form of section 3) into the record the XML form gives."""
    element_type, encoding, values = _only(stream, "elementType", "encoding", "values")
    href = element_type.get(f"{{{XLINK_NS}}}href")
    if href != RECORD_PREFIX + res or res not in STRUCTURES:
        raise PayloadError(f"elementType refers to '{href}', not to {RECORD_PREFIX + res}")
    if not element_type.get("name") or len(element_type) or (element_type.text or "").strip():
        raise PayloadError("the elementType must have a name and no inline content")
    _text_encoding(encoding)
    blocks = (values.text or "").split(" ")
    if len(blocks) != 1 or not blocks[0]:
        raise PayloadError("the text form holds exactly one block")
    tokens = blocks[0].split(",")
    fields = STRUCTURES[res]
    expected = sum(len(u) if k == "DataArray" else 1 for _, k, u in fields)
    if len(tokens) != expected:
        raise PayloadError(f"{len(tokens)} tokens, {res} has {expected}")
    out: dict[str, Any] = {}
    it = iter(tokens)
    for name, kind, unit in fields:
        if kind == "DataArray":
            out[name] = [{c: _parse_token(k, next(it), u) for c, k, u in unit}]
        else:
            out[name] = _parse_token(kind, next(it), unit)
    return out


class Element(NamedTuple):
    """A received ``<control-ml/>``: its attributes and decoded payload (None when there is none)."""

    type: str
    id: str
    res: str
    value: Any


def decode(elem: ET.Element) -> Element:
    """Decodes a ``<control-ml/>`` element (attributes checked, payload decoded)."""
    if elem.tag != f"{{{CM_NS}}}control-ml":
        raise PayloadError(f"<{local(elem.tag)}> is not a control-ml element")
    kind, rid, res = elem.get("type"), elem.get("id"), elem.get("res")
    allowed = {"type", "id", "res", "sent"} if kind == "set" else {"type", "id", "res"}
    if not {"type", "id", "res"} <= set(elem.attrib) <= allowed:
        raise PayloadError(f"attributes {sorted(elem.attrib)}: type, id, res and on a set sent are allowed")
    if "sent" in elem.attrib and not _UTC_RE.fullmatch(elem.get("sent")):
        raise PayloadError(f"sent '{elem.get('sent')}' is not an ISO 8601 UTC time stamp")
    if kind not in TYPES or not is_request_id(rid) or not _RES_RE.fullmatch(res):
        raise PayloadError(f"bad attributes type='{kind}' id='{rid}' res='{res}'")
    kids = list(elem)
    if len(kids) > 1:
        raise PayloadError("more than one payload")
    if not kids:
        return Element(kind, rid, res, None)
    payload = kids[0]
    if local(payload.tag) == "DataStream" and _ns(payload.tag) == SWE_NS:
        return Element(kind, rid, res, decode_text_form(payload, res))
    if local(payload.tag) == "failure" and _ns(payload.tag) == CM_NS:
        return Element(kind, rid, res, Refusal(payload.get("condition", ""), payload.get("reason", ""),
                                               payload.text or ""))
    return Element(kind, rid, res, decode_component(payload))


def find_control_ml(stanza: ET.Element) -> ET.Element | None:
    return stanza.find(f"{{{CM_NS}}}control-ml")


# ---------------------------------------------------------------------------------------------------------------
# Errors (section 8) and presence levels (section 7)
# ---------------------------------------------------------------------------------------------------------------
class Refusal(NamedTuple):
    """Why a device refused: the RFC 6120 condition, the ControlML reason and the human-readable text."""

    condition: str
    reason: str
    text: str

    def __str__(self) -> str:
        return f"{self.condition} ({self.reason or 'no ControlML reason'}): {self.text or 'no text'}"


def decode_error(stanza: ET.Element) -> Refusal:
    """The refusal carried by an ``<iq type='error'/>`` or an answer message: the echoed ``<failure/>`` when there is
    one, else the ``<error/>``'s condition, ControlML reason element and text (qualified or not, see section 8)."""
    cm = find_control_ml(stanza)
    failure = cm.find(f"{{{CM_NS}}}failure") if cm is not None else None
    if failure is not None:
        return Refusal(failure.get("condition", ""), failure.get("reason", ""), (failure.text or "").strip())
    error = next((c for c in stanza if local(c.tag) == "error"), None)
    if error is None:
        return Refusal("", "", "no error element")
    condition = reason = text = ""
    for child in error:
        ns, name = _ns(child.tag), local(child.tag)
        if name == "text":
            text = (child.text or "").strip()
        elif ns == STANZAS_NS and not condition:
            condition = name
        elif ns == ERRORS_NS:
            reason = name
    return Refusal(condition, reason, text)


class PresenceLevel(NamedTuple):
    level: str
    mission: str
    maintenance: bool


def decode_presence_level(presence: ET.Element) -> PresenceLevel | None:
    """The ``<presence-level/>`` of a presence (section 7), or None when it carries none."""
    pl = presence.find(f"{{{CM_NS}}}presence-level")
    if pl is None:
        return None
    return PresenceLevel(pl.get("level", ""), pl.get("mission", ""), pl.get("maintenance", "false") in ("true", "1"))


# ---------------------------------------------------------------------------------------------------------------
# Printing
# ---------------------------------------------------------------------------------------------------------------
def flatten(value: Any, prefix: str = "") -> list[tuple[str, str]]:
    """(path, text) lines of a decoded value, e.g. ('x', '1.25 m'), ('covariance[0].xx', '0.01 m2')."""
    if isinstance(value, dict):
        out = []
        for k, v in value.items():
            out += flatten(v, f"{prefix}.{k}" if prefix else k)
        return out
    if isinstance(value, list):
        out = []
        for i, row in enumerate(value):
            out += flatten(row, f"{prefix}[{i}]")
        return out
    if isinstance(value, Measure):
        return [(prefix, f"{value.value:g} {value.uom}")]
    if isinstance(value, bool):
        return [(prefix, "true" if value else "false")]
    return [(prefix, str(value))]
