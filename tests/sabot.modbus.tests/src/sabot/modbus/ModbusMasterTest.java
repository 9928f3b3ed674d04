package sabot.modbus;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.io.Reader;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.Properties;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.EnumSource;

import sabot.model.map.MapLandmark;
import sabot.model.map.MapServerFormat;
import sabot.modbus.internal.ModbusMap;
import sabot.testsupport.robot.SimProcess;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * The Modbus master against a real {@code sabot-sim}: over its pty (j2mod's serial transport, jSerialComm) and over
 * RTU-over-TCP. Each test starts its own simulator (fixed seed) so that no test sees another's writes.
 */
class ModbusMasterTest {

    enum Via {
        PTY, TCP
    }

    private static final ModbusMap MAP = ModbusMap.standard();

    @TempDir
    Path dir;

    /** The bus's default settings (50 ms response timeout, one retry): for the tests of its timing. */
    private static BusSettings defaults(SimProcess sim, Via via) {
        // the pty carries bytes, not bits: Linux refuses parity on it, so 8N1 (the simulator models 8E1 timing)
        return via == Via.PTY ? BusSettings.serial(sim.pty()).withParity(Parity.NONE)
                : BusSettings.tcp("127.0.0.1", sim.tcpPort());
    }

    /**
     * For the tests of what the boards answer: a response timeout and retries that a simulator starved by a busy
     * machine (a CI host running the whole build) still meets; the timing itself is {@link #defaults}' tests'.
     */
    private static BusSettings settings(SimProcess sim, Via via) {
        return defaults(sim, via).withResponseTimeout(Duration.ofMillis(250)).withRetries(2);
    }

    /** The power-on value of a record: the map's literal default, or the robot description's value × factor. */
    private static double mapDefault(String board, String file, String record) throws IOException {
        ModbusMap.Field f = MAP.field(board, file, record);
        if (f.defaultFrom() == null) {
            return f.si(f.defaultValue());
        }
        Properties robot = new Properties();
        try (Reader r = Files.newBufferedReader(PrivateXmppServer.repositoryRoot().resolve(
                "docs/sabot-robot.properties"))) {
            robot.load(r);
        }
        String value = robot.getProperty(f.defaultFrom());
        if (value == null) {
            throw new IllegalStateException("docs/sabot-robot.properties has no " + f.defaultFrom());
        }
        return f.si(Math.round(Double.parseDouble(value.trim()) * f.defaultFactor()));
    }

    @ParameterizedTest
    @EnumSource(Via.class)
    void configReadAtOpenMatchesTheMapDefaults(Via via) throws Exception {
        try (SimProcess sim = SimProcess.start(dir); ModbusBus bus = ModbusBuses.open(settings(sim, via))) {
            SactConfig c = bus.sact().config();
            assertEquals(mapDefault("sact", "config", "encoder_lines"), c.encoderLines());
            assertEquals(mapDefault("sact", "config", "gear_ratio"), c.gearRatio(), 1e-9);
            assertEquals(mapDefault("sact", "config", "wheel_radius"), c.wheelRadius(), 1e-9);
            assertEquals(mapDefault("sact", "config", "no_load_speed"), c.noLoadSpeed(), 1e-9);
            assertEquals(mapDefault("sact", "config", "max_speed"), c.maxSpeed(), 1e-9);
            assertEquals(mapDefault("sact", "config", "max_accel"), c.maxAccel(), 1e-9);
            assertEquals(Duration.ofMillis(Math.round(mapDefault("sact", "config", "command_timeout") * 1000)),
                    c.commandTimeout());
            assertEquals((int) mapDefault("sact", "config", "firmware_version"), c.firmwareVersion());
            // 512 lines x 4 x 43 / 2 pi
            assertEquals(512 * 4 * 43 / (2 * Math.PI), c.countsPerWheelRadian(), 1e-6);
            assertEquals(1, bus.statistics().sact().framesSent());
            assertEquals(1, bus.statistics().sact().answers());
        }
    }

    @ParameterizedTest
    @EnumSource(Via.class)
    void wheelsFollowTheSetPointsAndTheTruthAgrees(Via via) throws Exception {
        double rate = 2.0; // rad/s = 0.15 m/s at r = 7.5 cm
        List<String[]> truth;
        try (SimProcess sim = SimProcess.start(dir)) {
            try (ModbusBus bus = ModbusBuses.open(settings(sim, via))) {
                SactClient sact = bus.sact();
                Wheels before = sact.readWheels();
                sact.setWheelSpeeds(rate, -rate);
                Wheels w = awaitWheels(sact, x -> Math.abs(x.left().speed() - rate) < 0.1 * rate
                        && Math.abs(x.right().speed() + rate) < 0.1 * rate, 3000);
                assertTrue(w.left().position() - before.left().position() > 0, "left counts forward");
                assertTrue(w.right().position() - before.right().position() < 0, "right counts backward");
                assertTrue(w.left().current() > 0, "a turning motor draws current: " + w.left());
                assertFalse(w.left().faultLatched());
                Wheels later = sact.readWheels();
                assertTrue(later.left().position() - w.left().position() >= 0);

                sact.brake(true);
                Wheels braked = awaitWheels(sact, x -> x.left().braking() && x.right().braking()
                        && Math.abs(x.left().speed()) < 0.05 && Math.abs(x.right().speed()) < 0.05, 3000);
                assertTrue(braked.left().braking());
                sact.brake(false);
                assertFalse(sact.readWheels().left().braking());
            }
            sim.close();
            truth = sim.truthRows();
        }
        double maxLeft = truth.stream().mapToDouble(r -> Double.parseDouble(r[7])).max().orElseThrow();
        double minRight = truth.stream().mapToDouble(r -> Double.parseDouble(r[8])).min().orElseThrow();
        assertEquals(rate, maxLeft, 0.15 * rate, "true left wheel rate");
        assertEquals(-rate, minRight, 0.15 * rate, "true right wheel rate");
        String[] last = truth.get(truth.size() - 1);
        assertEquals(0.0, Double.parseDouble(last[7]), 0.05, "braked: the true wheel is still");
    }

    private interface Condition {
        boolean holds(Wheels w);
    }

    private static Wheels awaitWheels(SactClient sact, Condition c, long timeoutMs) throws IOException {
        long deadline = System.nanoTime() + timeoutMs * 1_000_000;
        Wheels w;
        do {
            w = sact.readWheels(); // each read is one bus transaction: the poll is paced by the line
            if (c.holds(w)) {
                return w;
            }
        } while (System.nanoTime() < deadline);
        throw new AssertionError("condition not reached within " + timeoutMs + " ms; last " + w);
    }

    @ParameterizedTest
    @EnumSource(Via.class)
    void gainsAreWrittenAndReadBackAndABadGainChangesNothing(Via via) throws Exception {
        try (SimProcess sim = SimProcess.start(dir); ModbusBus bus = ModbusBuses.open(settings(sim, via))) {
            SactClient sact = bus.sact();
            SactGains defaults = sact.readGains(Motor.RIGHT);
            assertEquals(new SactGains((int) MAP.field("sact", "motor_right", "kp").defaultValue(),
                    (int) MAP.field("sact", "motor_right", "ki").defaultValue(),
                    (int) MAP.field("sact", "motor_right", "kd").defaultValue(),
                    (int) MAP.field("sact", "motor_right", "integral_limit").defaultValue()), defaults);
            SactGains tuned = new SactGains(200, 10, 1700, 300);
            sact.writeGains(Motor.LEFT, tuned);
            assertEquals(tuned, sact.readGains(Motor.LEFT));
            assertEquals(defaults, sact.readGains(Motor.RIGHT), "the other motor is untouched");

            long sent = bus.statistics().sact().framesSent();
            IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                    () -> sact.writeGains(Motor.LEFT, new SactGains(100, 5, 1000, 492)));
            assertEquals("LEFT integral_limit: 492 is outside sact/motor_left/integral_limit's bounds [0, 491]",
                    e.getMessage());
            assertEquals(sent, bus.statistics().sact().framesSent(), "nothing sent");
            assertEquals(tuned, sact.readGains(Motor.LEFT), "board unchanged");
        }
    }

    @ParameterizedTest
    @EnumSource(Via.class)
    void aSpeedOverTheBoardsLimitIsItsException3(Via via) throws Exception {
        try (SimProcess sim = SimProcess.start(dir); ModbusBus bus = ModbusBuses.open(settings(sim, via))) {
            SactClient sact = bus.sact();
            double over = 1.1 * sact.config().maxWheelRate();
            BoardException e = assertThrows(BoardException.class, () -> sact.setWheelSpeeds(over, 0));
            assertEquals(BoardException.Kind.EXCEPTION, e.kind());
            assertEquals(MAP.exception("illegal_data_value"), e.exceptionCode());
            assertEquals("sact", e.board());
            assertEquals(1, bus.statistics().sact().exceptions());
            assertFalse(sact.faulted(), "an exception is an answer");
            // the limit itself is accepted; writing tighter limits clamps later commands too
            sact.writeLimits(0.3, 0.4);
            assertEquals(0.3, sact.config().maxSpeed(), 1e-9);
            assertEquals(0.4, sact.config().maxAccel(), 1e-9);
            assertThrows(BoardException.class, () -> sact.setWheelSpeeds(0.35 / 0.075, 0));
            sact.setWheelSpeeds(0.25 / 0.075, 0);
            sact.setCommandTimeout(Duration.ofMillis(250));
            assertEquals(Duration.ofMillis(250), sact.config().commandTimeout());
            IllegalArgumentException bad = assertThrows(IllegalArgumentException.class,
                    () -> sact.writeLimits(0.001, 0.4));
            assertTrue(bad.getMessage().contains("max_speed"), bad.getMessage());
            sact.acknowledgeFaults();
            sact.positionStep(Motor.LEFT, 100);
            assertThrows(IllegalArgumentException.class, () -> sact.positionStep(Motor.LEFT, 4096));
        }
    }

    @ParameterizedTest
    @EnumSource(Via.class)
    void insAndSonarRead(Via via) throws Exception {
        try (SimProcess sim = SimProcess.start(dir); ModbusBus bus = ModbusBuses.open(settings(sim, via))) {
            InsSample s = bus.ins().read();
            assertEquals(9.81, s.accelZ(), 0.3, "+1 g at rest: " + s);
            assertEquals(0.0, s.gyroZ(), 0.05);
            assertTrue(s.temperature() > 0 && s.temperature() < 60, "temperature " + s.temperature());
            InsMotion m = bus.ins().readMotion();
            assertEquals(0.0, m.gyroZ(), 0.05);
            assertEquals(3, bus.sonar().sensorCount());
            List<SonarReading> all = bus.sonar().readSensors();
            assertEquals(3, all.size());
            SonarReading centre = bus.sonar().readSensor(1);
            assertEquals(1, centre.sensor());
            assertTrue(Math.abs(centre.angle()) < 1.0, "centre sensor looks forward: " + centre);
            if (centre.valid()) {
                double r = centre.range().orElseThrow();
                assertEquals(r, Math.hypot(centre.x(), centre.y()), 0.3, "obstacle point at the range: " + centre);
            }
            assertThrows(IllegalArgumentException.class, () -> bus.sonar().readSensor(3));
            assertEquals(0, bus.statistics().ins().timeouts() + bus.statistics().sonar().timeouts());
        }
    }

    @ParameterizedTest
    @EnumSource(Via.class)
    void corruptAndLostAnswersAreRetriedAndCounted(Via via) throws Exception {
        try (SimProcess sim = SimProcess.start(dir, "--fault-crc", "0.05", "--fault-drop", "0.05");
                ModbusBus bus = ModbusBuses.open(settings(sim, via).withRetries(3))) {
            for (int i = 0; i < 150; i++) {
                bus.sact().readWheels();
                bus.ins().readMotion();
            }
            BoardCounters sact = bus.statistics().sact();
            BoardCounters ins = bus.statistics().ins();
            assertTrue(sact.crcErrors() + ins.crcErrors() > 0, "CRC errors counted: " + sact + ins);
            assertTrue(sact.timeouts() + ins.timeouts() > 0, "timeouts counted: " + sact + ins);
            assertEquals(151, sact.answers(), "every transaction answered in the end (config + 150)");
            assertEquals(sact.framesSent(), sact.answers() + sact.crcErrors() + sact.timeouts());
            assertFalse(bus.sact().faulted());
        }
    }

    @Test
    void aStoppedSimulatorIsATimeoutWithinTheBoundThenAFault() throws Exception {
        try (SimProcess sim = SimProcess.start(dir)) {
            BusSettings s = defaults(sim, Via.PTY);
            try (ModbusBus bus = ModbusBuses.open(s)) {
                bus.sact().readWheels();
                sim.signal("STOP");
                try {
                    BoardCounters before = bus.statistics().sact();
                    long t0 = System.nanoTime();
                    BoardException e = assertThrows(BoardException.class, () -> bus.sact().readWheels());
                    Duration took = Duration.ofNanos(System.nanoTime() - t0);
                    assertBound(s, took, before, bus.statistics().sact());
                    assertEquals(BoardException.Kind.TIMEOUT, e.kind(), e.getMessage());
                    assertFalse(bus.sact().faulted(), "not yet: faultAfter is " + s.faultAfter());
                    awaitFault(bus, s);
                } finally {
                    sim.signal("CONT");
                }
                awaitRecovery(bus);
            }
        }
    }

    /**
     * A failed transaction made exactly its attempts, each waited its full response timeout, and it gave up: the
     * attempts are counted exactly; the clock only shows that it neither gave up early nor hung (the slack is the
     * scheduling of a shared 2-core CI host, where 40 ms was once exceeded; a hang is seconds or forever).
     */
    private static void assertBound(BusSettings s, Duration took, BoardCounters before, BoardCounters after) {
        int attempts = s.retries() + 1;
        assertEquals(attempts, after.framesSent() - before.framesSent(), "frames sent: " + before + " -> " + after);
        assertEquals(attempts, after.timeouts() - before.timeouts(), "timeouts: " + before + " -> " + after);
        assertEquals(before.answers(), after.answers(), "no answer counted");
        assertTrue(took.compareTo(s.transactionBound().plusMillis(500)) <= 0,
                "took " + took.toMillis() + " ms, bound " + s.transactionBound().toMillis() + " ms");
        assertTrue(took.compareTo(s.transactionBound()) >= 0, "gave up early: " + took.toMillis() + " ms");
    }

    private static void awaitFault(ModbusBus bus, BusSettings s) {
        long t0 = System.nanoTime();
        BoardException last = null;
        while (!bus.sact().faulted()) {
            last = assertThrows(BoardException.class, () -> bus.sact().readWheels());
            assertTrue(System.nanoTime() - t0 < s.faultAfter().multipliedBy(3).toNanos(), "no fault in time");
        }
        BoardException faulted = assertThrows(BoardException.class, () -> bus.sact().readWheels());
        assertEquals(BoardException.Kind.FAULTED, faulted.kind(), faulted.getMessage());
        assertTrue(bus.statistics().sact().faulted());
        assertTrue(bus.statistics().sact().timeouts() >= 2 * (s.retries() + 1), "" + last);
    }

    private static void awaitRecovery(ModbusBus bus) throws IOException {
        // the simulator runs again: the next transaction answers and the fault clears
        bus.sact().readWheels();
        assertFalse(bus.sact().faulted());
    }

    @Test
    void aTcpPeerThatNeverAnswersIsATimeoutNeverAHang() throws Exception {
        try (ServerSocket listener = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            // the config read at open already takes the bound: the fault comes later than that
            BusSettings s = BusSettings.tcp("127.0.0.1", listener.getLocalPort()).withFaultAfter(Duration.ofMillis(400));
            try (ModbusBus bus = ModbusBuses.open(s); Socket accepted = listener.accept()) {
                assertEquals(s.retries() + 1, bus.statistics().sact().timeouts(), "the config read at open");
                BoardCounters before = bus.statistics().ins();
                long t0 = System.nanoTime();
                BoardException e = assertThrows(BoardException.class, () -> bus.ins().read());
                assertBound(s, Duration.ofNanos(System.nanoTime() - t0), before, bus.statistics().ins());
                assertEquals(BoardException.Kind.TIMEOUT, e.kind());
                assertEquals("ins", e.board());
                IOException noConfig = assertThrows(IOException.class, () -> bus.sact().config());
                assertTrue(noConfig instanceof BoardException);
                long t1 = System.nanoTime();
                while (!bus.ins().faulted()) {
                    assertThrows(BoardException.class, () -> bus.ins().readMotion());
                    assertTrue(System.nanoTime() - t1 < s.faultAfter().multipliedBy(3).toNanos());
                }
            }
        }
    }

    @Test
    void anUnknownPortIsAClearError() {
        IOException e = assertThrows(IOException.class,
                () -> ModbusBuses.open(BusSettings.serial(dir.resolve("ttyUSB9").toString())));
        assertEquals("serial port " + dir.resolve("ttyUSB9") + " does not exist", e.getMessage());
        IOException refused = assertThrows(IOException.class, () -> {
            int port;
            try (ServerSocket free = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
                port = free.getLocalPort();
            }
            ModbusBuses.open(BusSettings.tcp("127.0.0.1", port));
        });
        assertTrue(refused.getMessage().startsWith("cannot connect to the RTU-over-TCP bus 127.0.0.1:"),
                refused.getMessage());
    }

    @Test
    void settingsAreValidatedWithPreciseMessages() {
        BusSettings ok = BusSettings.serial("/dev/ttyUSB0");
        assertEquals(115200, ok.baud());
        assertEquals(Parity.EVEN, ok.parity());
        assertEquals(Duration.ofMillis(50), ok.responseTimeout());
        assertEquals(1, ok.retries());
        assertEquals(Duration.ofNanos(1_750_000), ok.interFrameDelay());
        assertEquals(Duration.ofMillis(200), ok.faultAfter());
        assertEquals(Duration.ofMillis(100), ok.transactionBound());
        assertMessage("BusSettings: give a serial port or a TCP host",
                () -> new BusSettings(null, null, 0, 115200, Parity.EVEN, ok.responseTimeout(), 1,
                        ok.interFrameDelay(), ok.faultAfter()));
        assertMessage("BusSettings: give a serial port or a TCP host, not both (serialPort /dev/x, tcpHost h)",
                () -> new BusSettings("/dev/x", "h", 502, 115200, Parity.EVEN, ok.responseTimeout(), 1,
                        ok.interFrameDelay(), ok.faultAfter()));
        assertMessage("BusSettings: serialPort is blank", () -> BusSettings.serial(" "));
        assertMessage("BusSettings: tcpPort must be 1-65535, got 70000", () -> BusSettings.tcp("localhost", 70000));
        assertMessage("BusSettings: tcpHost is blank", () -> BusSettings.tcp("", 502));
        assertMessage("BusSettings: baud must be 300-4000000 bit/s, got 0", () -> ok.withBaud(0));
        assertMessage("BusSettings: parity is null", () -> ok.withParity(null));
        assertMessage("BusSettings: responseTimeout must be 1 ms-10000 ms, got 0 ms",
                () -> ok.withResponseTimeout(Duration.ZERO));
        assertMessage("BusSettings: responseTimeout is null", () -> ok.withResponseTimeout(null));
        assertMessage("BusSettings: retries must be 0-10, got -1", () -> ok.withRetries(-1));
        assertMessage("BusSettings: interFrameDelay must be 0 ms-1000 ms, got -1 ms",
                () -> ok.withInterFrameDelay(Duration.ofMillis(-1)));
        assertMessage("BusSettings: faultAfter must be 1 ms-60000 ms, got 61000 ms",
                () -> ok.withFaultAfter(Duration.ofSeconds(61)));
    }

    private static void assertMessage(String expected, org.junit.jupiter.api.function.Executable e) {
        assertEquals(expected, assertThrows(IllegalArgumentException.class, e).getMessage());
    }

    @ParameterizedTest
    @EnumSource(Via.class)
    void aLandmarkInViewIsSightedWhereTheTruthSaysAndOutOfViewIsNone(Via via) throws Exception {
        // the markers the simulator loads, read by the map model's own reader
        List<MapLandmark> marks = MapServerFormat.readLandmarks(PrivateXmppServer.repositoryRoot().resolve(
                "onboard-bridge/maps/lab.yaml"));
        LandmarkSighting sighting;
        LandmarkConfig defaults;
        List<String[]> truth;
        // south-east of the lab's marker 5 (5.6, 3.6), facing north-west
        try (SimProcess sim = SimProcess.start(dir, "--start", "6.2,3.3,2.0")) {
            try (ModbusBus bus = ModbusBuses.open(settings(sim, via))) {
                LandmarkClient camera = bus.landmark();
                defaults = camera.readConfig();
                assertEquals(new LandmarkConfig(mapDefault("landmark", "config", "view_radius"),
                        Duration.ofMillis(Math.round(mapDefault("landmark", "config", "period") * 1000))), defaults);
                sighting = awaitNewSightings(camera, 2);
                assertTrue(sighting.age().compareTo(defaults.period().plusMillis(10)) <= 0, "age " + sighting);

                // a view radius shorter than the marker's distance: measurements go on, nothing is seen
                camera.writeConfig(new LandmarkConfig(0.5, Duration.ofMillis(50)));
                assertEquals(new LandmarkConfig(0.5, Duration.ofMillis(50)), camera.readConfig());
                LandmarkSighting none = awaitNewSightings(camera, 2);
                assertFalse(none.seen(), "seen beyond the view radius: " + none);
                assertEquals(0.0, none.range());

                long sent = bus.statistics().landmark().framesSent();
                IllegalArgumentException bad = assertThrows(IllegalArgumentException.class,
                        () -> camera.writeConfig(new LandmarkConfig(6.0, Duration.ofMillis(100))));
                assertEquals("landmark view radius 6.0 m: 6000 is outside landmark/config/view_radius's bounds "
                        + "[100, 5000]", bad.getMessage());
                assertThrows(IllegalArgumentException.class,
                        () -> camera.writeConfig(new LandmarkConfig(1.5, Duration.ofMillis(5))));
                assertEquals(sent, bus.statistics().landmark().framesSent(), "nothing sent");
                assertEquals(new LandmarkConfig(0.5, Duration.ofMillis(50)), camera.readConfig(), "board unchanged");
                assertEquals(0, bus.statistics().landmark().timeouts());
            }
            sim.close();
            truth = sim.truthRows();
        }
        // the robot stood still: its last true pose is the pose of every measurement
        String[] last = truth.get(truth.size() - 1);
        double x = Double.parseDouble(last[2]);
        double y = Double.parseDouble(last[3]);
        double theta = Double.parseDouble(last[4]);
        MapLandmark nearest = marks.stream().min((a, b) -> Double.compare(Math.hypot(a.x() - x, a.y() - y),
                Math.hypot(b.x() - x, b.y() - y))).orElseThrow();
        double range = Math.hypot(nearest.x() - x, nearest.y() - y);
        assertTrue(range < defaults.viewRadius(), "the test pose has no marker in view");
        double bearing = Math.IEEEremainder(Math.atan2(nearest.y() - y, nearest.x() - x) - theta, 2 * Math.PI);
        assertEquals(nearest.id(), sighting.landmarkId(), sighting.toString());
        // 4 sigma of the board's noise (10 mm, 0.5 degree) plus a quantum
        assertEquals(range, sighting.range(), 4 * 0.010 + 0.001, sighting.toString());
        assertEquals(0.0, Math.IEEEremainder(sighting.bearing() - bearing, 2 * Math.PI),
                4 * Math.toRadians(0.5) + 1e-4, sighting + " vs true bearing " + bearing);
    }

    /** Reads until the sequence has moved on {@code n} times (each read one transaction, paced by the line). */
    private static LandmarkSighting awaitNewSightings(LandmarkClient camera, int n) throws IOException {
        long deadline = System.nanoTime() + 3_000_000_000L;
        LandmarkSighting first = camera.readLatest();
        LandmarkSighting s = first;
        while (((s.sequence() - first.sequence()) & 0xFFFF) < n) {
            if (System.nanoTime() > deadline) {
                throw new AssertionError("no " + n + " new landmark measurements within 3 s; last " + s);
            }
            s = camera.readLatest();
        }
        return s;
    }

    @Test
    void wireTimesAreComputedFromTheFrameSizes() {
        BusTiming t = BusTiming.of(BusSettings.serial("/dev/ttyUSB0"));
        // readWheels: request 5 + 2 x 7 = 19 bytes, answer 5 + 2 x (2 + 18) = 45 bytes; 64 x 11 / 115200 + 1.75 ms
        assertEquals(19, BusTiming.readRequestBytes(2));
        assertEquals(45, BusTiming.readAnswerBytes(9, 9));
        assertEquals(Math.round(64 * 11 * 1e9 / 115200) + 1_750_000, t.readTime(9, 9).toNanos());
        // setWheelSpeeds: 5 + 7 + 4 = 16 bytes each way
        assertEquals(16, BusTiming.writeBytes(2));
        assertEquals(Math.round(32 * 11 * 1e9 / 115200) + 1_750_000, t.writeTime(2).toNanos());
    }

    /**
     * The power board reads what the simulator's battery is: a robot started at 37 % of 2.5 Ah, then its charge set to
     * 5 % through the control channel; the readings follow within a period or two, and the capacity is the option's.
     */
    @ParameterizedTest
    @EnumSource(Via.class)
    void thePowerBoardReadsTheSimulatorsBattery(Via via) throws Exception {
        try (SimProcess sim = SimProcess.start(dir, "--battery-soc", "0.37", "--battery-capacity", "2.5");
                ModbusBus bus = ModbusBuses.open(settings(sim, via))) {
            PowerClient power = bus.power();
            assertEquals(new PowerConfig(2.5, Duration.ofMillis(Math.round(mapDefault("power", "config", "period")
                    * 1000))), power.readConfig());
            PowerReading r = awaitPower(power, x -> true);
            String truth = sim.command("battery 1");
            double soc = Double.parseDouble(truth.replaceAll(".* soc=([0-9.]+) .*", "$1"));
            double volts = Double.parseDouble(truth.replaceAll(".* voltage=([0-9.]+) .*", "$1"));
            assertEquals(soc, r.stateOfCharge(), 2e-4, truth);
            assertEquals(volts, r.voltage(), 0.05, truth);
            assertTrue(r.current() > 0.3 && r.current() < 1.0, "the base load: " + r);
            assertFalse(r.docked() || r.charging() || r.full(), r.toString());
            assertTrue(sim.command("battery 1 soc 0.05").startsWith("ok"));
            PowerReading low = awaitPower(power, x -> x.stateOfCharge() < 0.06);
            assertEquals(0.05, low.stateOfCharge(), 2e-4);
            assertTrue(low.voltage() < r.voltage() - 2.0, "an empty pack's voltage: " + low + " after " + r);
            assertEquals(0, bus.statistics().power().timeouts());
        }
    }

    private static PowerReading awaitPower(PowerClient power, java.util.function.Predicate<PowerReading> c)
            throws IOException {
        long deadline = System.nanoTime() + 3_000_000_000L;
        PowerReading first = power.readLatest();
        PowerReading r = first;
        while (r.sequence() == first.sequence() || !c.test(r)) {
            if (System.nanoTime() > deadline) {
                throw new AssertionError("no such power reading within 3 s; last " + r);
            }
            r = power.readLatest();
        }
        return r;
    }
}
