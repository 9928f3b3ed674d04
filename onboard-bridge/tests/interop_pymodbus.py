#!/usr/bin/env python3
"""Interoperability: pymodbus (an independent Modbus implementation) as the master.

Starts sabot-sim, then reads and writes the SACT, inertial, sonar, landmark and power file records over
the robot's pseudo-terminal and over Modbus RTU framing on loopback TCP. Expected
values come from docs/sact-modbus-map.json, the same file the firmware is built from.
(pymodbus's own server ignores file-record contents, so it can only be the client.)

usage: interop_pymodbus.py PATH/TO/sabot-sim     prints "interop_pymodbus: N passed, N failed"
"""
import json
import os
import select
import signal
import struct
import subprocess
import sys
import time
import unittest

from pymodbus import FramerType
from pymodbus.client import ModbusSerialClient, ModbusTcpClient
from pymodbus.pdu.file_message import FileRecord

HERE = os.path.dirname(os.path.abspath(__file__))
MAP = json.load(open(os.path.join(HERE, "..", "..", "docs", "sact-modbus-map.json"), encoding="utf-8"))


def robot_description(path):
    """docs/sabot-robot.properties: key = value lines, # comments."""
    with open(path, encoding="utf-8") as f:
        pairs = (line.split("=", 1) for line in f if "=" in line and not line.lstrip().startswith("#"))
        return {k.strip(): v.strip() for k, v in pairs}


ROBOT = robot_description(os.path.join(HERE, "..", "..", "docs", "sabot-robot.properties"))


def resolve_defaults(node):
    """Records whose default is a robot constant name it ("default_from"); fill in the number."""
    if isinstance(node, dict):
        ref = node.get("default_from")
        if ref is not None:
            node["default"] = round(float(ROBOT[ref["robot"]]) * ref["factor"])
        for v in node.values():
            resolve_defaults(v)
    elif isinstance(node, list):
        for v in node:
            resolve_defaults(v)


resolve_defaults(MAP)
SIM = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "build", "sabot-sim")
TMP = os.path.join(HERE, "..", "build", "tmp")


def board(name):
    return next(b for b in MAP["boards"] if b["name"] == name)


def records(board_name, file_name):
    b = board(board_name)
    f = next(f for f in b["files"] if f["name"] == file_name)
    return f, (b["templates"][f["template"]] if "template" in f else f["records"])


SACT = board("sact")["slave_address"]
INS = board("ins")["slave_address"]
SONAR = board("sonar")["slave_address"]
LANDMARK = board("landmark")["slave_address"]
LANDMARK_LATEST, LANDMARK_LATEST_RECORDS = records("landmark", "latest")
LANDMARK_CONFIG, LANDMARK_CONFIG_RECORDS = records("landmark", "config")
POWER = board("power")["slave_address"]
POWER_LATEST, POWER_LATEST_RECORDS = records("power", "latest")
POWER_CONFIG, POWER_CONFIG_RECORDS = records("power", "config")
MOTOR_LEFT, MOTOR = records("sact", "motor_left")
CONFIG, CONFIG_RECORDS = records("sact", "config")
DRIVE, _ = records("sact", "drive")
REC = {r["name"]: r["record"] for r in MOTOR}
EXC = MAP["protocol"]["exceptions"]


class Simulator:
    """sabot-sim as a child process; its first stdout line describes the transports."""

    def __init__(self, *extra, link="interop-robot"):
        os.makedirs(TMP, exist_ok=True)
        self.link_prefix = os.path.join(TMP, link)
        self.proc = subprocess.Popen(
            [SIM, "--seed", "3", "--speed", "1", "--tcp", "0", "--link", self.link_prefix,
             "--duration", "600", *extra],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL)
        ready, _, _ = select.select([self.proc.stdout], [], [], 10.0)
        if not ready:
            self.stop()
            raise RuntimeError("sabot-sim printed nothing within 10 s")
        self.info = json.loads(self.proc.stdout.readline())
        self.robot = self.info["robots"][0]

    def stop(self):
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
        try:
            return self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            return self.proc.wait()


def u16(value):
    return struct.pack(">H", value & 0xFFFF)


def read(client, device, file, record, count=1):
    res = client.read_file_record([FileRecord(file_number=file, record_number=record, record_length=2 * count)],
                                  device_id=device)
    if res.isError():
        return res
    return list(struct.unpack(">%dH" % count, res.records[0].record_data))


def write(client, device, file, record, *values):
    data = b"".join(u16(v) for v in values)
    return client.write_file_record([FileRecord(file_number=file, record_number=record, record_data=data)],
                                    device_id=device)


def signed(v):
    return v - 0x10000 if v >= 0x8000 else v


class Transport:
    """The same checks over both transports."""
    client = None

    def test_config_reads_the_map_defaults(self):
        values = read(self.client, SACT, CONFIG["file"], 0, len(CONFIG_RECORDS))
        self.assertIsInstance(values, list, values)
        for r in CONFIG_RECORDS:
            if r["name"] != "command_sequence":  # the last key applied (state, not a setting)
                self.assertEqual(values[r["record"]], r["default"], r["name"])

    def test_velocity_write_reads_back(self):
        res = write(self.client, SACT, MOTOR_LEFT["file"], REC["velocity_setpoint"], 321)
        self.assertFalse(res.isError(), res)
        self.assertEqual(read(self.client, SACT, MOTOR_LEFT["file"], REC["velocity_setpoint"]), [321])
        write(self.client, SACT, MOTOR_LEFT["file"], REC["velocity_setpoint"], 0)

    def test_gains_write_read_back_in_one_request(self):
        res = write(self.client, SACT, 2, REC["kp"], 170, 9, 1700)
        self.assertFalse(res.isError(), res)
        self.assertEqual(read(self.client, SACT, 2, REC["kp"], 3), [170, 9, 1700])
        defaults = [next(r["default"] for r in MOTOR if r["name"] == n) for n in ("kp", "ki", "kd")]
        write(self.client, SACT, 2, REC["kp"], *defaults)

    def test_speed_above_limit_is_illegal_data_value_and_changes_nothing(self):
        before = read(self.client, SACT, MOTOR_LEFT["file"], REC["velocity_setpoint"])
        res = write(self.client, SACT, MOTOR_LEFT["file"], REC["velocity_setpoint"], 5000)
        self.assertTrue(res.isError())
        self.assertEqual(res.exception_code, EXC["illegal_data_value"])
        self.assertEqual(read(self.client, SACT, MOTOR_LEFT["file"], REC["velocity_setpoint"]), before)

    def test_a_keyed_step_sent_twice_is_applied_once(self):
        """A retry (the same request again: its answer was lost) under the same command_sequence key."""
        key_record = next(r["record"] for r in CONFIG_RECORDS if r["name"] == "command_sequence")

        def commanded():
            hi, lo = read(self.client, SACT, MOTOR_LEFT["file"], REC["commanded_position"], 2)
            return struct.unpack(">i", u16(hi) + u16(lo))[0]

        last = read(self.client, SACT, CONFIG["file"], key_record)[0]
        key = last % 65535 + 1
        step = [FileRecord(file_number=CONFIG["file"], record_number=key_record, record_data=u16(key)),
                FileRecord(file_number=MOTOR_LEFT["file"], record_number=REC["position_step"], record_data=u16(3))]
        before = commanded()
        for _ in range(2):
            res = self.client.write_file_record(step, device_id=SACT)
            self.assertFalse(res.isError(), res)
        self.assertEqual(commanded() - before, 3)
        self.assertEqual(read(self.client, SACT, CONFIG["file"], key_record), [key])

    def test_negative_gain_is_illegal_data_value(self):
        res = write(self.client, SACT, MOTOR_LEFT["file"], REC["kp"], -1)
        self.assertTrue(res.isError())
        self.assertEqual(res.exception_code, EXC["illegal_data_value"])

    def test_read_only_record_is_illegal_data_address(self):
        res = write(self.client, SACT, MOTOR_LEFT["file"], REC["position"], 1)
        self.assertTrue(res.isError())
        self.assertEqual(res.exception_code, EXC["illegal_data_address"])

    def test_unknown_file_is_illegal_data_address(self):
        res = read(self.client, SACT, 42, 0)
        self.assertFalse(isinstance(res, list))
        self.assertEqual(res.exception_code, EXC["illegal_data_address"])

    def test_inertial_board_samples_gravity(self):
        first = read(self.client, INS, 1, 0, 11)
        self.assertIsInstance(first, list, first)
        accel_z = signed(first[6])
        self.assertLess(abs(accel_z - 16384), 0.1 * 16384, "accel z %d LSB" % accel_z)
        deadline = time.monotonic() + 5
        while time.monotonic() < deadline:
            again = read(self.client, INS, 1, 0, 1)
            if again[0] != first[0]:
                break
        self.assertNotEqual(again[0], first[0], "sample counter does not advance")

    def test_sonar_board_answers(self):
        latest = read(self.client, SONAR, 1, 0, 18)
        self.assertIsInstance(latest, list, latest)
        points = read(self.client, SONAR, 2, 0, 65)
        self.assertIsInstance(points, list, points)

    def test_landmark_board_measures_and_holds_its_config_bounds(self):
        latest = read(self.client, LANDMARK, LANDMARK_LATEST["file"], 0, len(LANDMARK_LATEST_RECORDS))
        self.assertIsInstance(latest, list, latest)
        config = read(self.client, LANDMARK, LANDMARK_CONFIG["file"], 0, len(LANDMARK_CONFIG_RECORDS))
        self.assertEqual(config, [r["default"] for r in LANDMARK_CONFIG_RECORDS])
        radius = next(r for r in LANDMARK_CONFIG_RECORDS if r["name"] == "view_radius")
        res = write(self.client, LANDMARK, LANDMARK_CONFIG["file"], radius["record"], radius["max"] + 1)
        self.assertTrue(res.isError())
        self.assertEqual(res.exception_code, EXC["illegal_data_value"])
        deadline = time.monotonic() + 5
        while time.monotonic() < deadline:
            again = read(self.client, LANDMARK, LANDMARK_LATEST["file"], 0, 1)
            if again[0] != latest[0]:
                break
        self.assertNotEqual(again[0], latest[0], "measurement sequence does not advance")

    def test_power_board_reports_a_full_battery_at_rest_and_holds_its_period_bounds(self):
        rec = {r["name"]: r for r in POWER_LATEST_RECORDS}
        latest = read(self.client, POWER, POWER_LATEST["file"], 0, len(POWER_LATEST_RECORDS))
        self.assertIsInstance(latest, list, latest)
        volts = latest[rec["voltage"]["record"]] * rec["voltage"]["scale"]
        amps = signed(latest[rec["current"]["record"]]) * rec["current"]["scale"]
        soc = latest[rec["state_of_charge"]["record"]] * rec["state_of_charge"]["scale"]
        # 7 lithium-ion cells near full (the simulator's default charge), the base load drawn, no dock
        self.assertTrue(28.5 < volts < 29.4, volts)
        self.assertTrue(0.3 < amps < 1.0, amps)
        self.assertTrue(0.99 < soc <= 1.0, soc)
        self.assertEqual(latest[rec["status"]["record"]], 0)
        config = read(self.client, POWER, POWER_CONFIG["file"], 0, len(POWER_CONFIG_RECORDS))
        self.assertEqual(config, [r["default"] for r in POWER_CONFIG_RECORDS])
        period = next(r for r in POWER_CONFIG_RECORDS if r["name"] == "period")
        res = write(self.client, POWER, POWER_CONFIG["file"], period["record"], period["min"] - 1)
        self.assertTrue(res.isError())
        self.assertEqual(res.exception_code, EXC["illegal_data_value"])
        capacity = next(r for r in POWER_CONFIG_RECORDS if r["name"] == "design_capacity")
        res = write(self.client, POWER, POWER_CONFIG["file"], capacity["record"], 5000)
        self.assertTrue(res.isError())
        self.assertEqual(res.exception_code, EXC["illegal_data_address"])
        deadline = time.monotonic() + 5
        while time.monotonic() < deadline:
            again = read(self.client, POWER, POWER_LATEST["file"], 0, 1)
            if again[0] != latest[0]:
                break
        self.assertNotEqual(again[0], latest[0], "measurement sequence does not advance")


class PtyTransport(Transport, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sim = Simulator(link="interop-pty")
        # A pty has no parity: Linux refuses PARENB on it (EINVAL), so open it 8N1.
        cls.client = ModbusSerialClient(cls.sim.robot["link"], baudrate=115200, parity="N", timeout=1, retries=0)
        assert cls.client.connect(), "cannot open " + cls.sim.robot["link"]

    @classmethod
    def tearDownClass(cls):
        cls.client.close()
        cls.sim.stop()

    def test_robot_drives_when_both_set_points_are_written(self):
        start = read(self.client, SACT, MOTOR_LEFT["file"], REC["position"], 2)
        res = write(self.client, SACT, DRIVE["file"], 0, 600, 600)
        self.assertFalse(res.isError(), res)
        deadline = time.monotonic() + 5
        moved = 0
        while time.monotonic() < deadline and moved < 2000:
            now = read(self.client, SACT, MOTOR_LEFT["file"], REC["position"], 2)
            moved = ((now[0] << 16 | now[1]) - (start[0] << 16 | start[1])) & 0xFFFFFFFF
        write(self.client, SACT, DRIVE["file"], 0, 0, 0)
        self.assertGreaterEqual(moved, 2000, "the wheel did not turn")


class TcpTransport(Transport, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sim = Simulator(link="interop-tcp")
        cls.client = ModbusTcpClient("127.0.0.1", port=cls.sim.robot["tcp"], framer=FramerType.RTU, timeout=1,
                                     retries=0)
        assert cls.client.connect()

    @classmethod
    def tearDownClass(cls):
        cls.client.close()
        cls.sim.stop()


class Lifecycle(unittest.TestCase):
    def test_dropped_answers_time_out_at_the_master(self):
        sim = Simulator("--fault-drop", "1", link="interop-drop")
        client = ModbusTcpClient("127.0.0.1", port=sim.robot["tcp"], framer=FramerType.RTU, timeout=0.3, retries=0)
        try:
            self.assertTrue(client.connect())
            with self.assertRaises(Exception):
                res = read(client, SACT, CONFIG["file"], 0)
                if not isinstance(res, list):
                    raise RuntimeError(res)
        finally:
            client.close()
            sim.stop()

    def test_sigterm_stops_cleanly_and_removes_the_link(self):
        sim = Simulator("--robots", "2", link="interop-term")
        links = [r["link"] for r in sim.info["robots"]]
        self.assertEqual(len(links), 2)
        self.assertTrue(all(os.path.islink(l) for l in links))
        self.assertEqual(len({r["pty"] for r in sim.info["robots"]}), 2, "robots share a bus")
        self.assertEqual(sim.stop(), 0)
        self.assertFalse(any(os.path.lexists(l) for l in links))


if __name__ == "__main__":
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(
        unittest.defaultTestLoader.loadTestsFromModule(sys.modules[__name__]))
    failed = len(result.failures) + len(result.errors)
    print("interop_pymodbus: %d passed, %d failed" % (result.testsRun - failed, failed))
    sys.exit(1 if failed else 0)
