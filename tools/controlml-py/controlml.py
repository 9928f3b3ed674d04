#!/usr/bin/env python3
"""controlml.py: a ControlML client over XMPP (slixmpp), written from docs/CONTROLML.md.

  controlml.py --jid operator@sabot.local --password sabot get sabot-01@sabot.local cm.position
  controlml.py ... set-goal sabot-01@sabot.local 1.5 4.0 3.14 [--tol 0.1] [--heading-tol 0.2] [--xml-form]
  controlml.py ... mission sabot-01@sabot.local pause|resume|abort
  controlml.py ... watch sabot-01@sabot.local [--count N]
  controlml.py ... joystick sabot-01@sabot.local 0.2 0.5 [--rate 10] [--duration 5]

A robot given as a bare JID is reached at the full JID of its presence (resource 'onboard' preferred): the client
subscribes to the robot's presence and waits for it. Exit status: 0 done, 1 the robot refused (its condition,
reason and text on stderr), 2 bad usage, 3 no connection, no login, robot offline or no answer in time.

The session always uses STARTTLS on the server's port (--server, --port) and checks the server's certificate
against --ca-file only (the lab CA of `sabot-xmpp start`, DIR/ca/ca.pem; default $SABOT_XMPP_CA) or, without it,
the system's trusted CAs, and its name against the JID's domain. A refusal is one line on stderr and exit 3:

  controlml: the certificate for sabot.local is not signed by the CA of /path/ca.pem (SHA-256 ...) (JID on HOST:PORT)

--plain (no TLS) is only for a server started with --tls off; it is never a fallback.
"""

from __future__ import annotations

import argparse
import asyncio
import datetime as dt
import hashlib
import json
import logging
import math
import os
import signal
import ssl
import sys
import time
import xml.etree.ElementTree as ET
from typing import Awaitable, Callable, NamedTuple

import slixmpp
from slixmpp.exceptions import IqError, IqTimeout
from slixmpp.xmlstream.handler import Callback
from slixmpp.xmlstream.matcher import StanzaPath

import controlml_codec as cm

EXIT_REFUSED, EXIT_USAGE, EXIT_UNREACHABLE = 1, 2, 3
ROBOT_RESOURCE = "onboard"  # the onboard product's XMPP resource


class Failure(Exception):
    def __init__(self, status: int, message: str):
        super().__init__(message)
        self.status = status


def ssl_context(ca_file: str | None) -> ssl.SSLContext:
    """A client TLS context that checks the server's certificate and host name against ``ca_file``'s CAs only, or
    against the system's trusted CAs when it is None."""
    try:
        return ssl.create_default_context(cafile=ca_file)
    except ssl.SSLError as e:  # (an OSError too)
        raise Failure(EXIT_USAGE, f"--ca-file {ca_file}: not a PEM file of CA certificates ({e.reason or e})") \
            from None
    except OSError as e:
        raise Failure(EXIT_USAGE, f"--ca-file {ca_file}: {e.strerror or e}") from None


# OpenSSL's verify codes (X509_V_ERR_*) that say the chain does not end at a trusted CA
NOT_SIGNED = {2, 7, 18, 19, 20, 21}  # issuer not found, bad signature, self-signed, self-signed in chain, no local
#                                      issuer, leaf signature unverifiable
NOT_YET_VALID, EXPIRED, HOSTNAME_MISMATCH = 9, 10, 62
TLS_NS = "urn:ietf:params:xml:ns:xmpp-tls"


def tls_refusal(error: BaseException, domain: str, trust: str) -> str:
    """The one line saying why the TLS handshake for ``domain`` failed: ``error`` is what ssl raised (the certificate
    refused, with OpenSSL's verify code, or another failure of the handshake); ``trust``: trust_description()."""
    if isinstance(error, ssl.SSLCertVerificationError):
        code = error.verify_code
        if code in NOT_SIGNED:
            return f"the certificate for {domain} is not signed by {trust}"
        if code == HOSTNAME_MISMATCH:
            return f"the server's certificate does not name {domain} (trusted: {trust})"
        if code == EXPIRED:
            return f"the certificate for {domain} or its CA has expired (trusted: {trust})"
        if code == NOT_YET_VALID:
            return f"the certificate for {domain} or its CA is not valid yet (is this machine's clock right?)"
        return f"the certificate for {domain} was refused: {error.verify_message} (trusted: {trust})"
    reason = getattr(error, "reason", None) or str(error) or type(error).__name__
    return f"the TLS handshake for {domain} failed: {reason}"


def trust_description(ca_file: str | None) -> str:
    """What a client trusts, in the words of a refusal: the CA file and its SHA-256 fingerprint, or the system's."""
    if ca_file is None:
        return "the system's trusted CAs"
    try:
        with open(ca_file, encoding="ascii") as f:
            der = ssl.PEM_cert_to_DER_cert(f.read())
        fingerprint = hashlib.sha256(der).hexdigest().upper()
        return f"the CA of {ca_file} (SHA-256 " + ":".join(fingerprint[i:i + 2] for i in range(0, 64, 2)) + ")"
    except (OSError, ValueError):
        return f"the CA of {ca_file}"


class _SlixmppTlsLine(logging.Filter):
    """Drops slixmpp's own line for a failed STARTTLS handshake ("CERT: Invalid certificate trust chain.", also said
    of a wrong name or a failure that is no certificate's): the client says what failed in its own one line."""

    def filter(self, record: logging.LogRecord) -> bool:
        return not str(record.msg).startswith("CERT: Invalid certificate trust chain")


logging.getLogger("slixmpp.xmlstream.xmlstream").addFilter(_SlixmppTlsLine())


def time_answer(iq, now: dt.datetime | None = None):
    """The XEP-0202 answer to the entity time request ``iq``: this clock's UTC time to the microsecond, zone offset Z
    (the offset does not matter to a robot: it compares UTC times)."""
    utc = (now or dt.datetime.now(dt.timezone.utc)).astimezone(dt.timezone.utc)
    reply = iq.reply(clear=True)
    answer = reply["entity_time"]
    answer._set_sub_text("tzo", "Z")
    answer._set_sub_text("utc", utc.strftime("%Y-%m-%dT%H:%M:%S.%fZ"))
    return reply


class Client(slixmpp.ClientXMPP):
    """One XMPP session: login, robot presence tracking, ControlML request/answer."""

    def __init__(self, jid: str, password: str, ca_file: str | None = None, plain: bool = False):
        """``ca_file``: PEM of the CA that must sign the server's certificate (the lab CA of ``./sabot xmpp start``);
        None: the system's trusted CAs. ``plain``: no TLS at all, for the benchmark that compares the two only."""
        super().__init__(jid, password)
        # slixmpp writes a namespaced attribute only when its namespace has a prefix here (xlink:href of the text
        # form and of Time units would be dropped otherwise)
        self.namespace_map[cm.XLINK_NS] = "xlink"
        # one way in: the server's c2s port, upgraded with STARTTLS (slixmpp would otherwise try direct TLS first and
        # report its failure as a failed connection); never a silent fallback to a plain stream
        self.enable_direct_tls = False
        self.enable_starttls = not plain
        self.enable_plaintext = plain
        # on a plain stream only SCRAM, which never sends the password (PLAIN stays refused)
        self.plugin["feature_mechanisms"].unencrypted_scram = plain
        self.plain = plain
        self.trust = trust_description(ca_file)
        if not plain:
            # the lab CA only (not added to the system's store, as slixmpp's ca_certs would), and the certificate must
            # name the XMPP domain: slixmpp's STARTTLS gives the JID's domain as the server name to check
            self.ssl_context = ssl_context(ca_file)
        # slixmpp 1.17 raises every failed STARTTLS handshake (a certificate refused, or not) as this event, with the
        # ssl error; without a handler it would disconnect silently
        self.add_event_handler("ssl_invalid_chain", lambda e: self._fail(
            tls_refusal(e, self.boundjid.domain, self.trust)))
        # XEP-0202: a robot measures its requesters' clocks to judge their commands' send times (spec section 5).
        # The plugin announces the feature; its own answer is replaced: slixmpp 1.17 fails while writing the answer's
        # zone offset (it parses a time without a date: ValueError), so the robot would never measure this clock.
        self.register_plugin("xep_0202")
        self.remove_handler("Entity Time")
        self.register_handler(Callback("Entity Time", StanzaPath("iq@type=get/entity_time"),
                                       lambda iq: time_answer(iq).send()))
        self.ids = cm.RequestIds()
        self.started = asyncio.Event()
        self.failed: str | None = None
        self.presences: dict[str, tuple[str, cm.PresenceLevel | None, str]] = {}  # full JID -> (show, level, status)
        self.presence_changed = asyncio.Event()
        self.add_event_handler("session_start", self._on_start)
        self.add_event_handler("failed_all_auth", lambda _: self._fail("authentication failed"))
        self.add_event_handler("connection_failed", lambda e: self._fail(f"connection failed: {e}"))
        # 'presence' sees every presence; slixmpp's presence_available misses a robot that is busy (show dnd)
        self.add_event_handler("presence", self._on_presence)

    def _fail(self, why: str) -> None:
        if self.failed is None:  # the first reason: what follows it (a disconnection) is its consequence
            self.failed = why
        self.started.set()

    async def _handle_stream_features(self, features):
        """slixmpp's negotiation, after the check that it cannot fall back to a plain stream: without STARTTLS done,
        a server that does not offer it is refused (slixmpp would go on with SASL); with ``plain``, a server that
        requires STARTTLS is said so (slixmpp would wait for mechanisms that never come)."""
        starttls = features.xml.find(f"{{{TLS_NS}}}starttls")
        if not self.plain and "starttls" not in self.features and starttls is None:
            self._fail("the server offers no STARTTLS, and this client never logs in without TLS (a server started "
                       "with --tls off takes --plain)")
            return True
        if self.plain and starttls is not None and starttls.find(f"{{{TLS_NS}}}required") is not None:
            self._fail("the server requires STARTTLS (--plain is only for a server started with --tls off)")
            return True
        return await super()._handle_stream_features(features)

    async def _on_start(self, _event) -> None:
        self.send_presence()
        self.started.set()

    def _on_presence(self, pres) -> None:
        full = str(pres["from"])
        kind = pres["type"]  # slixmpp gives the show (away, dnd, ...) as the type of an available presence
        if kind == "unavailable":
            self.presences.pop(full, None)
        elif kind in ("available", "chat", "away", "xa", "dnd"):
            self.presences[full] = (pres["show"] or "available", cm.decode_presence_level(pres.xml), pres["status"])
        else:
            return  # subscription requests and answers
        self.presence_changed.set()

    async def login(self, server: str, port: int, timeout: float) -> None:
        self.connect(server, port)
        try:
            await asyncio.wait_for(self.started.wait(), timeout)
        except asyncio.TimeoutError:
            raise Failure(EXIT_UNREACHABLE, f"no XMPP session with {server}:{port} within {timeout:g} s") from None
        if self.failed:
            raise Failure(EXIT_UNREACHABLE, f"{self.failed} ({self.boundjid.bare} on {server}:{port})")

    def robot_jid(self, robot: slixmpp.JID) -> str | None:
        """The full JID to address: the onboard resource when it is online, else any online resource of ``robot``."""
        online = [j for j in self.presences if slixmpp.JID(j).bare == robot.bare]
        preferred = [j for j in online if slixmpp.JID(j).resource == ROBOT_RESOURCE]
        return (preferred or online or [None])[0]

    async def find_robot(self, robot: str, timeout: float) -> str:
        jid = slixmpp.JID(robot)
        if jid.resource:
            return str(jid)
        # presence subscription: the robot approves anyone it lets read (spec section 9), then sends its presence
        self.send_presence(pto=jid.bare, ptype="subscribe")
        deadline = time.monotonic() + timeout
        while (full := self.robot_jid(jid)) is None:
            left = deadline - time.monotonic()
            if left <= 0:
                raise Failure(EXIT_UNREACHABLE, f"{jid.bare} is offline (no presence within {timeout:g} s)")
            self.presence_changed.clear()
            try:
                await asyncio.wait_for(self.presence_changed.wait(), left)
            except asyncio.TimeoutError:
                pass
        return full

    async def request(self, to: str, kind: str, res: str, payload: ET.Element | None, timeout: float) -> cm.Element:
        """Sends a get or set and returns the decoded result; a refusal raises Failure(EXIT_REFUSED)."""
        iq = self.make_iq(ito=to, itype=kind)
        iq.append(cm.control_ml(kind, self.ids.next(), res, payload))
        try:
            answer = await iq.send(timeout=timeout)
        except IqError as e:
            raise Failure(EXIT_REFUSED, f"{to} refused {kind} {res}: {cm.decode_error(e.iq.xml)}") from None
        except IqTimeout:
            raise Failure(EXIT_UNREACHABLE, f"no answer from {to} to {kind} {res} within {timeout:g} s") from None
        elem = cm.find_control_ml(answer.xml)
        if elem is None:
            raise Failure(EXIT_REFUSED, f"{to} answered {kind} {res} without a control-ml element")
        try:
            return cm.decode(elem)
        except cm.PayloadError as e:
            raise Failure(EXIT_REFUSED, f"{to}'s answer to {kind} {res} is malformed: {e}") from None


def measure(record: dict, name: str) -> float:
    value = record.get(name)
    return value.value if isinstance(value, cm.Measure) else float("nan")


MAX_JOYSTICK_RATE = 100.0  # Hz: the onboard's control loop runs at 50 Hz; more than twice that only loads the server


class JoystickReport(NamedTuple):
    """What a joystick session sent: the twists at the rate (the stop not counted), the ticks skipped because an
    answer came later than the next tick, and each answer's round trip in ms (the stop's included)."""

    twists: int
    skipped: int
    round_trips_ms: list[float]


async def joystick(send: Callable[[ET.Element], Awaitable[object]], linear: float, angular: float, rate: float,
                   duration: float, clock: Callable[[], float] = time.monotonic) -> JoystickReport:
    """Sends the twist (``linear`` m/s, ``angular`` rad/s) as cm.velocity sets ``rate`` times a second for ``duration``
    seconds, then one zero twist so that the robot stops at once rather than at its deadman timeout. Each set carries
    the time it is sent (the robot measures twist sent -> wheel set-point with it) and its answer is awaited before the
    next; a tick whose time has passed while waiting is skipped, not sent late in a burst. A refusal (Failure) ends
    the session where it happened."""
    period = 1.0 / rate
    trips: list[float] = []

    async def one(v: float, w: float) -> None:
        payload = cm.encode_record("cm.velocity", cm.velocity(v, w, cm.utc_time()))
        t0 = clock()
        await send(payload)
        trips.append((clock() - t0) * 1000.0)

    start = clock()
    ticks = max(1, round(rate * duration))
    sent = skipped = 0
    for k in range(ticks):
        due = start + k * period
        now = clock()
        if now - due >= period:  # the previous answer took longer than a period: this tick's twist would be stale
            skipped += 1
            continue
        if due > now:
            await asyncio.sleep(due - now)
        await one(linear, angular)
        sent += 1
    end = start + ticks * period
    if end > clock():
        await asyncio.sleep(end - clock())
    await one(0.0, 0.0)
    return JoystickReport(sent, skipped, trips)


def percentile(values: list[float], q: float) -> float:
    """The ``q`` quantile (nearest rank) of ``values``; NaN when empty."""
    if not values:
        return float("nan")
    ordered = sorted(values)
    return ordered[max(0, math.ceil(q * len(ordered)) - 1)]


def status_line(pose: cm.Element | Failure, mission: cm.Element | Failure, presence) -> str:
    """One line of 'watch', in the onboard product's status format: pose | mission | presence."""
    if isinstance(pose, Failure):
        p = f"pose unavailable ({pose})"
    else:
        v = pose.value
        p = f"pose x={measure(v, 'x'):.3f} y={measure(v, 'y'):.3f} theta={measure(v, 'theta'):.3f}"
    if isinstance(mission, Failure):
        m = f"mission unavailable ({mission})"
    else:
        v = mission.value
        m = f"mission {v.get('state')} {measure(v, 'progress'):.0f}%"
        if v.get("detail"):
            m += f" ({v['detail']})"
    if presence is None:
        pr = "presence offline"
    else:
        show, level, _ = presence
        pr = f"presence {level.level if level else show}" + (" maintenance" if level and level.maintenance else "")
    return f"{p} | {m} | {pr}"


PATROL_POLL_S = 0.5  # s between two gets of cm.mission while a patrol's round runs
PATROL_RETRY_S = 5.0  # s a patrol waits after a failed round before it starts the next


async def patrol(client, robot: str, targets: list[dict], args: argparse.Namespace) -> dict:
    """Runs the mission of ``targets`` again each time it is done, for ``args.rounds`` rounds or ``args.duration``
    seconds (whichever ends first; 0: no limit). A failed round, or one the robot refuses (e.g. a target it cannot
    reach now: an echo of a passing robot on it), is reported and the next starts after PATROL_RETRY_S. One line per
    round; returns the summary (rounds, targets reached, per minute, failures)."""
    start = time.monotonic()
    rounds = failed = reached = 0
    limit_s = args.duration if args.duration > 0 else float("inf")

    def over() -> bool:
        return (args.rounds and rounds + failed >= args.rounds) or time.monotonic() - start >= limit_s

    while not over():
        t0 = time.monotonic()
        try:
            await client.request(robot, "set", "cm.mission", cm.mission(targets), args.timeout)
        except Failure as e:
            if e.status != EXIT_REFUSED:
                raise
            failed += 1
            print(f"round refused: {e}", flush=True)
            await asyncio.sleep(PATROL_RETRY_S)
            continue
        state, value = "running", {}
        while state in ("running", "paused") and time.monotonic() - start < limit_s:
            await asyncio.sleep(PATROL_POLL_S)
            value = (await client.request(robot, "get", "cm.mission", None, args.timeout)).value
            state = value.get("state")
        current, _, _ = cm.mission_targets(value) if value else (0, 0, [])
        if state == "done":
            rounds += 1
            reached += len(targets)
            print(f"round {rounds} done: {len(targets)} targets in {time.monotonic() - t0:.1f} s", flush=True)
        elif state in ("running", "paused"):
            reached += current  # the time is up mid-round: the targets reached so far count
            break
        else:
            failed += 1
            reached += current
            print(f"round failed ({state}): {value.get('detail', '')}", flush=True)
            await asyncio.sleep(PATROL_RETRY_S)
    minutes = (time.monotonic() - start) / 60
    return {"robot": robot, "rounds": rounds, "rounds_failed": failed, "targets_reached": reached,
            "minutes": round(minutes, 3), "targets_per_minute": round(reached / minutes, 2) if minutes else 0.0}


def parse_target(text: str) -> dict:
    """A mission target from 'X,Y[,THETA[,ACTION[,WAIT]]]' (m, m, rad, pass|stop|wait|dock, s)."""
    parts = text.split(",")
    if not 2 <= len(parts) <= 5:
        raise Failure(2, f"target '{text}' is not X,Y[,THETA[,ACTION[,WAIT]]]")
    try:
        x, y = float(parts[0]), float(parts[1])
        theta = float(parts[2]) if len(parts) > 2 else 0.0
        wait = float(parts[4]) if len(parts) > 4 else 0.0
        return cm.target(x, y, theta, parts[3] if len(parts) > 3 else "stop", wait)
    except (ValueError, cm.PayloadError) as e:
        raise Failure(2, f"target '{text}': {e}") from None


async def run(args: argparse.Namespace) -> int:
    try:
        client = Client(args.jid, args.password, args.ca_file, args.plain)
    except Failure as f:
        print(f"controlml: {f}", file=sys.stderr)
        return f.status
    try:
        await client.login(args.server, args.port, args.timeout)
        robot = await client.find_robot(args.robot, args.timeout)
        if args.command == "get":
            answer = await client.request(robot, "get", args.res, None, args.timeout)
            for path, text in cm.flatten(answer.value):
                print(f"{path} = {text}")
        elif args.command == "battery":
            answer = await client.request(robot, "get", "cm.battery", None, args.timeout)
            try:
                print(cm.battery_line(cm.battery(answer.value)))
            except cm.PayloadError as e:
                raise Failure(1, f"{robot} answered a cm.battery the spec refuses: {e}") from None
        elif args.command == "set-goal":
            payload = cm.encode_record("cm.goal", cm.goal(args.x, args.y, args.theta, args.tol, args.heading_tol),
                                       text_form=not args.xml_form)
            await client.request(robot, "set", "cm.goal", payload, args.timeout)
            print(f"goal ({args.x:g}, {args.y:g}, {args.theta:g}) accepted by {robot}")
        elif args.command == "mission" and args.action in ("start", "queue"):
            targets = [parse_target(t) for t in args.targets]
            await client.request(robot, "set", "cm.mission", cm.mission(targets, queue=args.action == "queue"),
                                 args.timeout)
            print(f"mission of {len(targets)} targets {'queued' if args.action == 'queue' else 'started'} by "
                  f"{robot}")
        elif args.command == "mission":
            if args.targets:
                raise Failure(2, f"mission {args.action} takes no targets")
            state = {"pause": "paused", "resume": "running", "abort": "aborted"}[args.action]
            current = (await client.request(robot, "get", "cm.mission", None, args.timeout)).value
            payload = cm.encode_record("cm.mission", {"state": state, "maintenance": bool(current["maintenance"]),
                                                      "progress": measure(current, "progress"),
                                                      "detail": f"operator {args.action}"})
            await client.request(robot, "set", "cm.mission", payload, args.timeout)
            print(f"mission {args.action} accepted by {robot}")
        elif args.command == "joystick":
            report = await joystick(lambda payload: client.request(robot, "set", "cm.velocity", payload,
                                                                   args.timeout),
                                    args.linear, args.angular, args.rate, args.duration)
            trips = report.round_trips_ms
            print(f"joystick: {report.twists} twists ({args.linear:g} m/s, {args.angular:g} rad/s) at {args.rate:g} Hz "
                  f"for {args.duration:g} s, then a stop, accepted by {robot}"
                  + (f" ({report.skipped} ticks skipped: answers slower than a period)" if report.skipped else "")
                  + f"; answer round trip p50 {percentile(trips, 0.5):.1f} ms p99 {percentile(trips, 0.99):.1f} ms"
                  f" max {max(trips):.1f} ms")
        elif args.command == "lease":
            answer = await client.request(robot, "set", "cm.telemetry", cm.lease(args.seconds, args.rates),
                                          args.timeout)
            seconds, granted = cm.telemetry_rates(answer.value)
            print(f"lease of {robot} for {seconds:g} s: " + ", ".join(f"{r} {hz:g} Hz" for r, hz in granted.items())
                  if seconds > 0 else f"no lease on {robot}: " + ", ".join(f"{r} {hz:g} Hz (base)"
                                                                          for r, hz in granted.items()))
        elif args.command == "patrol":
            targets = [parse_target(t) for t in args.targets]
            if args.rounds < 0 or not (math.isfinite(args.duration) and args.duration >= 0):
                raise Failure(2, "--rounds and --duration must be 0 or more")
            summary = await patrol(client, robot, targets, args)
            print(json.dumps(summary), flush=True)
            return 0 if summary["rounds_failed"] == 0 else 1
        elif args.command == "watch":
            n = 0
            next_tick = time.monotonic()
            while args.count == 0 or n < args.count:
                pose, mission = await asyncio.gather(
                    client.request(robot, "get", "cm.position", None, args.timeout),
                    client.request(robot, "get", "cm.mission", None, args.timeout), return_exceptions=True)
                for r in (pose, mission):
                    if isinstance(r, BaseException) and not isinstance(r, Failure):
                        raise r
                print(time.strftime("%H:%M:%S ") + status_line(pose, mission, client.presences.get(robot)),
                      flush=True)
                n += 1
                next_tick += 1.0
                await asyncio.sleep(max(0.0, next_tick - time.monotonic()))
        return 0
    except Failure as f:
        print(f"controlml: {f}", file=sys.stderr)
        return f.status
    finally:
        client.cancel_connection_attempt()
        if client.transport is not None:
            try:
                await asyncio.wait_for(client.disconnect(wait=0.5), 1.0)
            except (asyncio.TimeoutError, asyncio.CancelledError):
                pass
        client.abort()


def parse_args(argv: list[str]) -> argparse.Namespace:
    p = argparse.ArgumentParser(prog="controlml", description="ControlML client (docs/CONTROLML.md) over XMPP.")
    p.add_argument("--jid", default=os.environ.get("CONTROLML_JID", "operator@sabot.local"),
                   help="the operator's account (default $CONTROLML_JID or operator@sabot.local)")
    pw = p.add_mutually_exclusive_group()
    pw.add_argument("--password", help="the account's password")
    pw.add_argument("--password-file", help="a file whose first line is the password")
    p.add_argument("--server", default=os.environ.get("CONTROLML_SERVER", "127.0.0.1"))
    p.add_argument("--port", type=int, default=int(os.environ.get("SABOT_XMPP_PORT", "15222")))
    p.add_argument("--timeout", type=float, default=10.0, help="seconds for login, presence and each answer")
    p.add_argument("--ca-file", metavar="PEM",
                   help="the CA that must sign the server's certificate, and the only one trusted: the lab CA of "
                        "./sabot xmpp start (DIR/ca/ca.pem; default $SABOT_XMPP_CA); without it (or given empty), the "
                        "system's trusted CAs. The connection always uses STARTTLS and checks that the certificate names the JID's "
                        "domain; a refused certificate ends the command (exit 3)")
    p.add_argument("--plain", action="store_true",
                   help="no TLS: only for a server started with --tls off (the benchmark that compares the two); "
                        "SCRAM only, the password never travels in clear. Ignores $SABOT_XMPP_CA")
    p.add_argument("-v", "--verbose", action="store_true", help="log the XMPP traffic")
    sub = p.add_subparsers(dest="command", required=True)
    g = sub.add_parser("get", help="get a resource and print its fields")
    g.add_argument("robot", help="robot JID (bare: its presence gives the resource)")
    g.add_argument("res", help="resource, e.g. cm.position, cm.mission, cm.goal, cm.limits")
    b = sub.add_parser("battery", help="print the robot's battery in one line (cm.battery)")
    b.add_argument("robot")
    s = sub.add_parser("set-goal", help="send a navigation goal (m, m, rad)")
    s.add_argument("robot")
    for name in ("x", "y", "theta"):
        s.add_argument(name, type=float)
    s.add_argument("--tol", type=float, default=0.1, help="position tolerance in m (default 0.1)")
    s.add_argument("--heading-tol", type=float, default=0.2, help="heading tolerance in rad (default 0.2)")
    s.add_argument("--xml-form", action="store_true", help="send the XML form instead of the text form")
    m = sub.add_parser("mission", help="start or queue a mission of targets; pause, resume or abort the running one")
    m.add_argument("robot")
    m.add_argument("action", choices=("start", "queue", "pause", "resume", "abort"))
    m.add_argument("targets", nargs="*", metavar="X,Y[,THETA[,ACTION[,WAIT]]]",
                   help="start/queue: targets in order (m, m, rad; action pass|stop|wait|dock, default stop; "
                        "wait s for 'wait')")
    pa = sub.add_parser("patrol", help="run a mission of targets again each time it is done; prints a line per round "
                        "and a JSON summary (targets reached per minute)")
    pa.add_argument("robot")
    pa.add_argument("targets", nargs="+", metavar="X,Y[,THETA[,ACTION[,WAIT]]]", help="the round's targets in order")
    pa.add_argument("--rounds", type=int, default=0, help="rounds to run (default 0: until --duration or Ctrl-C)")
    pa.add_argument("--duration", type=float, default=0.0, help="seconds to run (default 0: no limit)")
    w = sub.add_parser("watch", help="print pose, mission and presence once a second")
    w.add_argument("robot")
    w.add_argument("--count", type=int, default=0, help="lines to print (default: until interrupted)")
    le = sub.add_parser("lease", help="lease faster telemetry (docs/CONTROLML.md section 6): RES=HZ ..., for a while")
    le.add_argument("robot")
    le.add_argument("rates", nargs="*", metavar="RES=HZ", help="e.g. cm.position=10 (none, or --seconds 0: end the "
                    "lease)")
    le.add_argument("--seconds", type=float, default=30.0, help="the lease asked for (default 30; the robot may cut "
                    "it); 0 ends it")
    j = sub.add_parser("joystick", help="drive by joystick: a twist (m/s, rad/s) at a rate for a duration, then stop")
    j.add_argument("robot")
    j.add_argument("linear", type=float, help="linear speed, m/s (|v| <= 10; the robot clamps to its limits)")
    j.add_argument("angular", type=float, help="angular speed, rad/s (|w| <= 20)")
    j.add_argument("--rate", type=float, default=10.0, help=f"twists per second, 0 < rate <= {MAX_JOYSTICK_RATE:g} "
                   "(default 10; keep it above 1 / the robot's deadman timeout, 2 Hz for 0.5 s)")
    j.add_argument("--duration", type=float, default=5.0, help="seconds of driving, > 0 (default 5)")
    args = p.parse_args(argv)
    if args.password_file:
        try:
            with open(args.password_file, encoding="utf-8") as f:
                args.password = f.readline().rstrip("\n")
        except OSError as e:
            p.error(f"--password-file: {e}")
    if args.plain and args.ca_file:
        p.error("--plain and --ca-file exclude each other")
    if args.ca_file == "":  # given empty, like an empty $SABOT_XMPP_CA: the system's trusted CAs
        args.ca_file = None
    elif args.ca_file is None and not args.plain:
        args.ca_file = os.environ.get("SABOT_XMPP_CA") or None
    if args.ca_file and not os.path.isfile(args.ca_file):
        p.error(f"--ca-file {args.ca_file}: no such file")
    if args.password is None:
        p.error("give --password or --password-file")
    if args.command in ("get",) and not cm.is_resource(args.res):
        p.error(f"'{args.res}' is not a resource name (cm.<word>[.<word>...])")
    if args.command == "set-goal":
        try:
            cm.encode_record("cm.goal", cm.goal(args.x, args.y, args.theta, args.tol, args.heading_tol))
        except cm.PayloadError as e:
            p.error(f"set-goal: {e}")
    if args.command == "joystick":
        try:
            cm.velocity(args.linear, args.angular, cm.utc_time())
        except cm.PayloadError as e:
            p.error(f"joystick: {e}")
        if not 0 < args.rate <= MAX_JOYSTICK_RATE:
            p.error(f"joystick: --rate {args.rate:g} must be in (0, {MAX_JOYSTICK_RATE:g}] Hz")
        if not (math.isfinite(args.duration) and args.duration > 0):
            p.error(f"joystick: --duration {args.duration:g} must be a finite number of seconds > 0")
    if args.command == "lease":
        rates = {}
        for item in args.rates:
            res, _, hz = item.partition("=")
            try:
                rates[res] = float(hz)
            except ValueError:
                p.error(f"lease: '{item}' is not RES=HZ")
        try:
            cm.lease(args.seconds, rates)
        except cm.PayloadError as e:
            p.error(f"lease: {e}")
        args.rates = rates
    if args.command == "watch" and args.count < 0:
        p.error("--count must be >= 0")
    return args


def main(argv: list[str]) -> int:
    args = parse_args(argv)
    logging.basicConfig(level=logging.DEBUG if args.verbose else logging.CRITICAL,
                        format="%(levelname)s %(name)s: %(message)s")
    loop = asyncio.new_event_loop()
    asyncio.set_event_loop(loop)
    task = loop.create_task(run(args))
    for sig in (signal.SIGINT, signal.SIGTERM):  # stop at once, leaving the session cleanly
        loop.add_signal_handler(sig, task.cancel)
    try:
        return loop.run_until_complete(task)
    except asyncio.CancelledError:
        return 0
    finally:
        # what slixmpp leaves running (its filter of the outgoing stream) ends before the loop closes: a client
        # collected later must not cancel it on a closed loop (an "Exception ignored" on stderr)
        for sig in (signal.SIGINT, signal.SIGTERM):
            loop.remove_signal_handler(sig)
        pending = asyncio.all_tasks(loop)
        for t in pending:
            t.cancel()
        if pending:
            loop.run_until_complete(asyncio.wait(pending, timeout=1.0))
        loop.close()


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
